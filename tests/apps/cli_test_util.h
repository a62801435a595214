#pragma once
// Running the built `hylo` executable from end-to-end tests, and reading what it wrote.
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace hylo::testing {

inline const std::string kHylo = std::string(HYLO_BINARY_DIR) + "/apps/hylo";

// The whole file, or "" when it cannot be read (the assertions that use it then fail).
inline std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs `hylo <args>` through the shell; stdout goes to `stdout_path` and stderr to
// `stderr_path` (the same path: both into one file, in order). Returns the exit status, or
// -1 when the process did not exit normally (a crash must not read as a clean exit).
inline int RunHylo(const std::string& args, const std::string& stdout_path,
                   const std::string& stderr_path) {
  const std::string redirect = stdout_path == stderr_path
                                   ? " > " + stdout_path + " 2>&1"
                                   : " > " + stdout_path + " 2> " + stderr_path;
  const int status = std::system((kHylo + " " + args + redirect).c_str());
  return status != -1 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace hylo::testing
