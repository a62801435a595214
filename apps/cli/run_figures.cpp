#include "run_figures.h"

#include <filesystem>

#include "hylo/io/cloud_io.h"

namespace hylo::cli {
namespace {

std::vector<Eigen::Vector3d> Positions(const std::vector<io::StampedPose>& poses) {
  std::vector<Eigen::Vector3d> out;
  for (const io::StampedPose& p : poses) out.push_back(p.position);
  return out;
}

// Ground truth in the map frame: x_map = T_ref_est^-1 x_ref (the ATE alignment maps the
// estimate's frame onto the truth's).
report::TrajectoryLine TruthInMap(const std::string& ground_truth,
                                  const std::vector<BackendRun>& runs) {
  report::TrajectoryLine truth{"ground truth", {}};
  for (const BackendRun& run : runs) {
    if (!run.ate.ok) continue;
    const Eigen::Isometry3d T_est_ref = run.ate.T_reference_estimate.inverse();
    for (const io::StampedPose& p : io::ReadTum(ground_truth)) {
      truth.positions_map.push_back(T_est_ref * p.position);
    }
    break;
  }
  return truth;
}

}  // namespace

std::vector<report::PlotFile> DrawRunFigures(const std::vector<BackendRun>& runs,
                                             const std::string& ground_truth,
                                             const std::string& map_path,
                                             const std::string& plot_dir) {
  std::filesystem::create_directories(plot_dir);
  std::vector<report::TrajectoryLine> lines;
  std::vector<report::ErrorCurve> curves;
  for (const BackendRun& run : runs) {
    if (run.trajectory.empty()) continue;
    lines.push_back({run.row.backend, Positions(run.trajectory)});
    if (!run.ate.ok) continue;
    report::ErrorCurve curve{run.row.backend, {}, run.ate.translation_errors_m};
    for (const int64_t t_ns : run.ate.t_ns) curve.t_s.push_back((t_ns - run.ate.t_ns[0]) * 1e-9);
    curves.push_back(curve);
  }
  if (!ground_truth.empty()) {
    report::TrajectoryLine truth = TruthInMap(ground_truth, runs);
    if (!truth.positions_map.empty()) lines.push_back(std::move(truth));
  }
  std::vector<Eigen::Vector3d> map_points;
  if (!map_path.empty()) map_points = io::ReadCloud(map_path).positions;
  return {report::PlotTopView(plot_dir + "/top_view.png", "Trajectories over the map (top view)",
                              map_points, lines),
          report::PlotErrorOverTime(plot_dir + "/error_over_time.png",
                                    "Position error after SE(3) alignment", curves)};
}

}  // namespace hylo::cli
