#pragma once
// The comparison table of the paper's Table I, one row per estimator back-end: cloud-to-cloud
// distance of the run's map to the prior (mean, std), trajectory errors against ground truth
// (ATE RMSE, RPE RMSE), time per scan (median, p99) and peak memory. The same rows are
// written for a terminal, as Markdown and as JSON, so `hylo demo` and `hylo compare` print one
// table. A figure that was not measured is NaN and printed as "n/a", never as 0.

#include <limits>
#include <string>
#include <vector>

#include "hylo/io/json.h"

namespace hylo::report {

/// What happened to a back-end's run.
enum class RowStatus {
  kOk,      ///< the run finished; figures are valid (NaN where not measured)
  kFailed,  ///< the run stopped with an error (see BackendRow::note)
};

/// "ok", "failed".
std::string ToString(RowStatus status);

/// One back-end's figures.
struct BackendRow {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  std::string backend;                   ///< "ieskf", "sliding_window"
  RowStatus status = RowStatus::kOk;     ///< whether the figures exist
  std::string note;                      ///< one line: why not ok, or a remark on the figures
  double c2c_mean_m = kNaN;              ///< cloud-to-cloud distance, run map to prior: mean, m
  double c2c_std_m = kNaN;               ///< ... standard deviation, m
  double ate_rmse_m = kNaN;              ///< absolute trajectory error (SE(3) aligned): RMSE, m
                                         ///< of the finalized states (trajectory.tum)
  double ate_live_rmse_m = kNaN;         ///< ... of the live states (trajectory_live.tum): what a
                                         ///< robot had at the time; the filter's are its finalized
  double rpe_rmse_m = kNaN;              ///< relative pose error (translation): RMSE, m
  double ms_per_scan_median = kNaN;      ///< wall time per scan: median, ms
  double ms_per_scan_p99 = kNaN;         ///< wall time per scan: 99th percentile, ms
  double cpu_ms_per_scan_median = kNaN;  ///< CPU time per scan (fair on a busy host): median, ms
  double peak_memory_mb = kNaN;          ///< peak resident memory of the run's process, MiB
  double scans = kNaN;                   ///< scans processed
};

enum class TableStyle {
  kTerminal,  ///< fixed-width columns, aligned with spaces
  kMarkdown,  ///< a GitHub-flavoured Markdown table
};

/// A figure with `decimals` decimals, or "n/a" for NaN.
std::string FormatFigure(double value, int decimals);

/// The table with a header line; rows that are not ok show their status in place of the
/// figures, and their notes follow the table (one line each).
std::string FormatTable(const std::vector<BackendRow>& rows, TableStyle style);

/// One object per row, every figure under a key with its unit (NaN written as null).
io::Json TableToJson(const std::vector<BackendRow>& rows);

}  // namespace hylo::report
