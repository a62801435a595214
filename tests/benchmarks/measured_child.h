#pragma once
// A child process whose memory is watched while it runs: its resident set sampled from
// /proc/<pid>/status, and its peak (ru_maxrss) from wait4. What the tiled map benchmark
// measures `hylo tile` and `hylo localize` with, each in a process of its own.

#include <string>
#include <vector>

namespace hylo::benchmarks {

struct RssSample {
  double t_s = 0.0;     ///< since the start, s
  double rss_mb = 0.0;  ///< resident set, MB
};

struct ChildRun {
  int exit_code = -1;  ///< 128 + signal when killed
  double wall_s = 0.0;
  double cpu_s = 0.0;          ///< user + system CPU of the child, s
  double peak_rss_mb = 0.0;    ///< ru_maxrss
  std::vector<RssSample> rss;  ///< every `period_s`
};

/// Runs `argv` (argv[0] a path), stdout and stderr into `log_path`, sampling its resident set
/// every `period_s`. Throws std::runtime_error when it cannot be started.
ChildRun RunMeasured(const std::vector<std::string>& argv, const std::string& log_path,
                     double period_s = 0.2);

}  // namespace hylo::benchmarks
