#pragma once
// Where `hylo demo` puts each file, what it measured, and the summary.json + report.md it
// writes from that.

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "backend_runs.h"
#include "demo_inspection.h"
#include "demo_setup.h"
#include "hylo/io/json.h"
#include "hylo/report/plots.h"
#include "hylo/sim/simulator.h"
#include "site_mapping_steps.h"

namespace hylo::cli {

/// Every path of one demo run, under `dir`.
struct DemoPaths {
  std::string dir;
  std::string sim_dir, bag_a, bag_b, truth_a, truth_b;
  std::string slam_dir;                               ///< SLAM on A (RunLog outputs)
  std::string map_dir, crafted_map, ground, objects;  ///< crafted prior map, ground split
  std::string costmap_dir, costmap_png;
  std::string inspection_dir;                 ///< `hylo inspect` outputs for the equipment
  std::string localize_config, localize_dir;  ///< B, one sub-folder per back-end
  std::string plot_dir, summary, report;
};
DemoPaths MakeDemoPaths(const std::string& dir);

/// The settings and figures of one demo run.
struct DemoSummary {
  bool quick = false;
  sim::SimulationOptions sim;
  io::Json simulation;  ///< per session: duration, scans, path, wall time
  io::Json slam;        ///< RunLog summary of session A + its ATE/RPE
  CraftStep craft;
  GroundStep ground;
  TraversabilityStep traversability;
  InspectionStep inspection;
  GuessError guess_error;       ///< how far the initial guess of B is from the truth
  double hybrid_after_s = 5.0;  ///< localization.update_after_s of the localization runs, s
  Eigen::Isometry3d guess_world_imu = Eigen::Isometry3d::Identity();  ///< the guess used
  std::vector<double> prior_frame_error_m;  ///< per run: PriorFrameErrorRmse, m (NaN: none)
  double elapsed_s = 0.0;                   ///< wall time up to the report, s
};

/// Writes summary.json (every figure) and report.md (table, figures, costmap, parameters,
/// files).
void WriteDemoOutputs(const DemoPaths& paths, const DemoSummary& summary,
                      const std::vector<BackendRun>& runs,
                      const std::vector<report::PlotFile>& plots);

}  // namespace hylo::cli
