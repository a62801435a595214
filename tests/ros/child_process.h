#pragma once
// A child process for integration tests: started in its own process group (roscore forks
// rosmaster and rosout; the group takes them all down), output to a log file, and stopped by
// the destructor (SIGINT, then SIGKILL after a grace period), so a failing assertion still
// cleans up every process the test started.

#include <sys/types.h>

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace hylo::testing {

class ChildProcess {
 public:
  /// Starts argv[0] (searched in PATH when it has no '/'); stdin is /dev/null, stdout and
  /// stderr go to `log_path`.
  /// Throws std::runtime_error when fork fails.
  ChildProcess(const std::vector<std::string>& argv, const std::string& log_path);
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  /// Exit code once the process ended (128 + signal when killed); nullopt while running.
  std::optional<int> Poll();
  /// Waits up to `timeout` for the end; nullopt on timeout.
  std::optional<int> Wait(std::chrono::milliseconds timeout);
  /// SIGINT to the group, SIGKILL after `grace`; idempotent.
  void Stop(std::chrono::milliseconds grace = std::chrono::milliseconds(5000));

  const std::string& log_path() const { return log_path_; }

 private:
  pid_t pid_ = -1;
  std::optional<int> exit_code_;
  std::string log_path_;
};

/// The full path of `program` in PATH, or "" when absent.
std::string FindInPath(const std::string& program);
/// A TCP port on 127.0.0.1 that was free a moment ago (bound to port 0, then released).
int FreeLoopbackPort();
/// The last `max_chars` characters of a file, for failure messages.
std::string Tail(const std::string& path, std::size_t max_chars = 2000);

}  // namespace hylo::testing
