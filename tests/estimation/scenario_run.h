#pragma once
// One randomized scenario through the pipeline, configured as a user would from its sensor
// sheet (preset + extrinsic + IMU noise, lidar stamps moved by the sheet's clock offset),
// and scored against the simulator's truth:
//   SLAM on the mapping drive with each back-end: ATE after SE(3) alignment, end drift (% of
//     the path, aligned at the first pose), CPU time per scan;
//   localization of the second drive in a map of the mapping drive's scans placed at their
//     true poses (sensor noise, no SLAM drift; thinned as `hylo localize` thins a prior), from
//     a guess off by 0.5-1.5 m and 3-10 deg: ATE without any alignment, CPU time per scan.
// One simulation pass feeds every back-end (each pipeline times only itself, thread CPU).
// Shared by hylo_scenario_matrix (the benchmark) and scenario_matrix_test.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "hylo/estimation/estimator.h"
#include "hylo/odometry/odometry_pipeline.h"
#include "hylo/io/json.h"
#include "hylo/sim/scenario.h"

namespace hylo::testing {

/// A configuration to try: a name and what it changes in every run's options (after the
/// sheet's values). "default" changes nothing.
struct Variant {
  std::string name = "default";
  std::function<void(odometry::OdometryPipelineOptions*)> adjust;
  std::vector<estimation::Estimator::Backend> backends;  ///< empty: every back-end of the run
};

struct ScenarioRunOptions {
  std::string preset_dir;  ///< where config/<preset>.yaml are
  std::vector<estimation::Estimator::Backend> backends = {
      estimation::Estimator::Backend::kIeskf, estimation::Estimator::Backend::kSlidingWindow};
  /// Every variant runs with every back-end on the same simulated data (one simulation pass).
  std::vector<Variant> variants = {Variant()};
  bool slam = true;
  bool localization = true;
  double prior_voxel_m = 0.1;  ///< uniform sampling of the true-pose map before thinning, m
  /// Not empty: every run writes trace_<scenario>_<variant>_<backend>_<mode>.txt here, one line
  /// per finalized state: t_s, estimated position (world, m) and quaternion (x y z w), the
  /// true ones, accel bias, gyro bias, gravity (map).
  std::string trace_dir;
};

/// One back-end in one mode on one scenario.
struct ModeFigures {
  bool ran = false;
  bool failed = false;  ///< the pipeline failed, or fewer than half the scans got a pose
  std::string message;
  double ate_m = 0.0;       ///< RMSE of the finalized states: SLAM after SE(3) alignment,
                            ///< localization without
  double ate_live_m = 0.0;  ///< the same for the live states (each scan's, at its time)
  double ate_max_m = 0.0;
  double rotation_rmse_deg = 0.0;
  double end_drift_m = 0.0;        ///< SLAM: end position error aligned at the first pose
  double end_drift_percent = 0.0;  ///< ... % of the path length
  double end_drift_xy_m = 0.0;     ///< ... its horizontal part, m
  double end_drift_z_m = 0.0;      ///< ... its vertical part (signed), m
  double end_error_se3_m = 0.0;    ///< SLAM: end position error after the SE(3) alignment, m
  double path_m = 0.0;
  double cpu_ms_median = 0.0;  ///< per scan, thread CPU time
  double cpu_ms_p99 = 0.0;
  double wall_ms_median = 0.0;  ///< per scan, wall time (one pipeline at a time runs)
  double wall_ms_p99 = 0.0;
  double process_cpu_ms_median = 0.0;  ///< per scan, CPU time of every thread of the process
  double process_cpu_ms_p99 = 0.0;
  std::size_t scans = 0, not_applied = 0, degenerate = 0;
  std::size_t out_of_time = 0;  ///< scans whose solve stopped at its time budget
  std::size_t searches = 0;     ///< searches while moving begun (localization)
  estimation::OnlineCalibration calibration;  ///< at the end of the run (not in the JSON)
};

/// One variant with one back-end.
struct BackendFigures {
  std::string variant;
  estimation::Estimator::Backend backend = estimation::Estimator::Backend::kIeskf;
  ModeFigures slam, localization;
};

struct ScenarioFigures {
  uint64_t number = 0;
  std::string summary;               ///< Scenario::Summary()
  double start_tilt_deg = 0;         ///< the vehicle's tilt at the mapping drive's start
  double sim_cpu_s = 0.0;            ///< simulation CPU time (both drives)
  std::vector<BackendFigures> runs;  ///< variant-major, back-ends in the options' order
};

ScenarioFigures RunScenario(const sim::Scenario& scenario, const ScenarioRunOptions& options);

io::Json ToJson(const ScenarioFigures& figures);
/// ToJson's inverse, to summarize matrices run apart (e.g. one half per core). Throws
/// std::runtime_error naming the scenario and key of a missing or malformed entry.
ScenarioFigures FromJson(const io::Json& j);

}  // namespace hylo::testing
