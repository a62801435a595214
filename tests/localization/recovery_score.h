#pragma once
// A recovery case scored against the drive's truth, in the prior map's frame and without any
// alignment:
//   recovered     a valid pose within max_error_m of the truth after the data's return (the
//                 log's start), and every pose of the next stable_s valid and within it;
//   time, distance  from the return (the log's start) to that pose: seconds, metres driven;
//   error after   median position error of the valid poses over error_window_s from there;
//   wrong accepts accepted start / relocalization events whose pose is > max_error_m off,
//                 anywhere in the run;
//   bad valid poses  scans whose pose was given as valid (the live result, what a node
//                 publishes) or finalized (what trajectory.tum holds) while > max_error_m off;
//   scan path     per-scan thread CPU (ScanResult::cpu_ms) and wall time (total_ms), median
//                 and p99, over the scans without a valid pose (lost, searching) and with one.

#include <cstddef>
#include <limits>
#include <string>

#include "hylo/io/json.h"
#include "localization/recovery_cases.h"

namespace hylo::testing {

struct RecoveryScoreOptions {
  double max_error_m = 1.0;      ///< a pose farther from the truth is wrong, m
  double stable_s = 5.0;         ///< a recovery holds this long, s
  double error_window_s = 10.0;  ///< the error after recovery is taken over this, s
};

/// Per-scan times of one group of scans.
struct ScanTimes {
  std::size_t scans = 0;
  double cpu_ms_median = 0.0, cpu_ms_p99 = 0.0;    ///< thread CPU, ms
  double wall_ms_median = 0.0, wall_ms_p99 = 0.0;  ///< wall time on the scan path, ms
};

struct RecoveryFigures {
  bool skipped = false;  ///< a gap case whose start failed before the cut: not counted
  /// Why it was skipped or not recovered: the pipeline's failure, else the last event's message.
  std::string note;
  bool recovered = false;
  double time_s = std::numeric_limits<double>::quiet_NaN();      ///< to recovery, s
  double distance_m = std::numeric_limits<double>::quiet_NaN();  ///< driven to recovery, m
  double error_after_m = std::numeric_limits<double>::quiet_NaN();
  int accepts = 0;          ///< accepted start / relocalization events after the return
  int failed_attempts = 0;  ///< failed relocalizations and search attempts after the return
  int wrong_accepts = 0;
  std::size_t bad_valid_live = 0, bad_valid_finalized = 0;
  double worst_valid_error_m = 0.0;  ///< over every valid live and finalized pose, m
  ScanTimes searching;               ///< scans without a valid pose (lost, provisional)
  ScanTimes tracking;                ///< scans with one
};

RecoveryFigures ScoreRecovery(const RecoveryRun& run, const DriveTruth& truth,
                              const RecoveryScoreOptions& options);

io::Json ToJson(const RecoveryFigures& f);
/// ToJson's inverse; throws io::Json::exception on a missing or malformed key.
RecoveryFigures RecoveryFiguresFromJson(const io::Json& j);

}  // namespace hylo::testing
