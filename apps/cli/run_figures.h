#pragma once
// The figures shared by `hylo compare` and `hylo demo`: each back-end's trajectory and the
// ground truth over the map, seen from above, and each back-end's position error over time.

#include <string>
#include <vector>

#include "backend_runs.h"
#include "hylo/report/plots.h"

namespace hylo::cli {

/// Draws top_view.png and error_over_time.png into `plot_dir`. `map_path` (PCD/PLY, may be
/// empty) is the background; the ground truth (TUM, may be empty) is brought into the map's
/// frame by the first evaluated back-end's SE(3) alignment. Missing plots come back with
/// their reason.
std::vector<report::PlotFile> DrawRunFigures(const std::vector<BackendRun>& runs,
                                             const std::string& ground_truth,
                                             const std::string& map_path,
                                             const std::string& plot_dir);

}  // namespace hylo::cli
