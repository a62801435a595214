#pragma once
// How the libraries' errors reach Python, with the message `hylo` prints after "error: ":
//   std::invalid_argument, config::ConfigError   -> ValueError (bad arrays, options, configuration)
//   FileError (ReadingFiles below)               -> OSError (FileNotFoundError when a path is missing)
//   run::RunFailed                               -> hylo.RunFailed, a ValueError (the log gave
//                                                   no trajectory: its start failed)
//   hylo::InternalError                          -> RuntimeError (a bug)
// The interpreter never sees a C++ exception it cannot handle.

#include <filesystem>
#include <initializer_list>
#include <stdexcept>
#include <string>

#include "hylo/config/run_config.h"
#include "hylo/run/run_log.h"

namespace hylo::python {

/// A file could not be read or written.
class FileError : public std::runtime_error {
 public:
  FileError(const std::string& what, bool missing) : std::runtime_error(what), missing_(missing) {}
  bool missing() const { return missing_; }

 private:
  bool missing_;
};

/// Runs `work`, which reads or writes `paths`: a reader's std::runtime_error becomes FileError
/// (missing when one of `paths` does not exist); configuration errors and RunFailed pass.
template <class Work>
auto ReadingFiles(std::initializer_list<std::string> paths, Work&& work) -> decltype(work()) {
  try {
    return work();
  } catch (const config::ConfigError&) {
    throw;
  } catch (const run::RunFailed&) {
    throw;
  } catch (const FileError&) {
    throw;
  } catch (const std::runtime_error& e) {
    bool missing = false;
    for (const std::string& path : paths) {
      std::error_code ec;
      if (!path.empty() && !std::filesystem::exists(path, ec)) missing = true;
    }
    throw FileError(e.what(), missing);
  }
}

}  // namespace hylo::python
