#pragma once
// What the recovery benchmark prints and writes: one line per case, and per back-end, case
// kind and half of the scenarios (even: where defaults may be chosen; odd: held out) the share
// recovered, how soon, the wrong accepts and bad valid poses, and the scan path's times while
// searching against while tracking.

#include <string>
#include <vector>

#include "hylo/io/json.h"
#include "localization/recovery_scenario.h"

namespace hylo::benchmarks {

/// One line per case of `s`, flushed.
void PrintCases(const testing::RecoveryScenario& s);

/// Over one group of cases (skipped ones counted apart, never as recovered or not).
struct RecoveryStats {
  std::size_t cases = 0, skipped = 0, recovered = 0;
  double recovered_percent = 0.0;                        ///< of the cases not skipped
  double time_median_s = 0.0, time_p90_s = 0.0;          ///< over the recovered cases
  double distance_median_m = 0.0, distance_p90_m = 0.0;  ///< ...
  double error_after_median_m = 0.0;                     ///< median of the cases' medians
  std::size_t wrong_accepts = 0, bad_valid_live = 0, bad_valid_finalized = 0;
  double worst_valid_error_m = 0.0;
  /// Per-case wall ms on the scan path: the median over the cases of their tracking median and
  /// p99, of their searching median and p99, and the worst searching p99 (searching: cases with
  /// such scans only).
  double tracking_wall_ms_median = 0.0, tracking_wall_ms_p99 = 0.0;
  double searching_wall_ms_median = 0.0;
  double searching_wall_ms_p99 = 0.0, searching_wall_ms_p99_worst = 0.0;
  /// The same in thread CPU.
  double tracking_cpu_ms_median = 0.0, tracking_cpu_ms_p99 = 0.0;
  double searching_cpu_ms_median = 0.0;
  double searching_cpu_ms_p99 = 0.0, searching_cpu_ms_p99_worst = 0.0;
  /// Per case, searching p99 over tracking median (wall): median and worst over the cases.
  double p99_over_median = 0.0, p99_over_median_worst = 0.0;
};

/// The cases of `all` run with `backend`, of `kind` ("" = every kind), from the scenarios of
/// `parity` (0 even, 1 odd, -1 all).
RecoveryStats Summarize(const std::vector<testing::RecoveryScenario>& all,
                        estimation::Estimator::Backend backend, const std::string& kind,
                        int parity);

io::Json ToJson(const RecoveryStats& s);

/// Prints the table (markdown) for every back-end that ran, and returns it as JSON:
/// {backend: {kind or "all": {"even"|"odd"|"all": stats}}}.
io::Json PrintSummary(const std::vector<testing::RecoveryScenario>& all);

}  // namespace hylo::benchmarks
