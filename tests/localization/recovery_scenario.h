#pragma once
// One randomized scenario's recovery cases, run and scored (recovery_cases.h, recovery_score.h).
// The prior map is the mapping drive's scans at their true poses (TruePoseMap, thinned as
// `hylo localize` thins a prior). The cases run on a second drive along the mapping drive's
// route in the localization session's world (its changed clutter, its own sensor noise and
// IMU): the scenario's own localization drive keeps to the lanes the mapping drive covered and
// ends where they end, 16-112 m, too short for a 100 m gap with time left to recover. Every
// case of a scenario, with every back-end, is fed by one simulation of that drive.
// Shared by hylo_recovery_benchmark and recovery_test.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "hylo/estimation/estimator.h"
#include "hylo/io/json.h"
#include "hylo/odometry/odometry_pipeline.h"
#include "hylo/sim/scenario.h"
#include "localization/recovery_cases.h"
#include "localization/recovery_score.h"

namespace hylo::testing {

/// A case to place by hand instead of drawing (PlaceRecoveryCase).
struct RecoveryCaseSpec {
  RecoveryKind kind = RecoveryKind::kGapAll;
  double after_motion_s = 10.0;  ///< the cut (the log) begins this long after the motion, s
  double distance_m = 20.0;      ///< gaps: travel during the gap, m
};

struct RecoveryRunOptions {
  std::string preset_dir;  ///< where config/<preset>.yaml are
  std::vector<estimation::Estimator::Backend> backends = {estimation::Estimator::Backend::kIeskf};
  RecoveryDrawOptions draw;
  RecoveryScoreOptions score;
  std::vector<RecoveryCaseSpec> specs;  ///< not empty: these cases instead of drawn ones
  double max_drive_s = 0.0;             ///< > 0: both drives end after this much driving, s
  double prior_voxel_m = 0.1;  ///< uniform sampling of the true-pose map before thinning, m
  /// Not empty: only drawn cases of these kinds are run (the others are drawn and dropped, so
  /// a case keeps its index and place).
  std::vector<RecoveryKind> kinds;
  /// Not empty: every case's run is written there scan by scan (recovery_trace.h).
  std::string trace_dir;
  /// Scans that fall in a case's window (from the data's return to its end) are delivered no
  /// faster than the clock they were stamped with, as a live node receives them; elsewhere as
  /// fast as simulated. For a search beside the scan path, whose attempt takes wall time while
  /// the log would otherwise race ahead of it.
  bool real_time = false;
  /// Changes every run's options after the sheet's (e.g. a setting being chosen).
  std::function<void(odometry::OdometryPipelineOptions*)> adjust;
};

struct RecoveryResult {
  RecoveryCase recovery_case;
  estimation::Estimator::Backend backend = estimation::Estimator::Backend::kIeskf;
  RecoveryFigures figures;
};

struct RecoveryScenario {
  uint64_t number = 0;
  std::string summary;     ///< Scenario::Summary()
  double drive_m = 0.0;    ///< the cases' drive: path, m
  double drive_s = 0.0;    ///< ... duration, s
  double cpu_s = 0.0;      ///< process CPU: the simulations and every case's session, s
  int cases_left_out = 0;  ///< cases that found no place on the drive
  std::vector<RecoveryResult> results;  ///< case-major, back-ends in the options' order
};

/// The cases RunRecoveryScenario would run, without simulating anything, and where each
/// reappears (begins), world frame, m.
std::vector<RecoveryCase> PlanRecoveryCases(const sim::Scenario& scenario,
                                            const RecoveryRunOptions& options,
                                            std::vector<Eigen::Vector3d>* where_world);

RecoveryScenario RunRecoveryScenario(const sim::Scenario& scenario,
                                     const RecoveryRunOptions& options);

io::Json ToJson(const RecoveryScenario& s);
/// ToJson's inverse. Throws std::runtime_error naming the scenario and the key.
RecoveryScenario RecoveryScenarioFromJson(const io::Json& j);

}  // namespace hylo::testing
