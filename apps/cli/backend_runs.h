#pragma once
// The same log through each estimator back-end, each in its own child process of `hylo`
// (/proc/self/exe), so that every back-end's peak memory is its own: `hylo compare` and the
// localization step of `hylo demo`. The child is `hylo compare ... --only-backend NAME`
// (RunLog into out_dir/NAME); the parent reads the child's files back and evaluates the
// trajectory against ground truth. A child that fails gets a "failed" row with its error:
// never a crash.

#include <string>
#include <vector>

#include "hylo/evaluation/trajectory_metrics.h"
#include "hylo/io/trajectory_io.h"
#include "hylo/report/backend_table.h"

namespace hylo::cli {

/// The back-ends `hylo compare` and `hylo demo` run, in table order.
const std::vector<std::string>& AllBackends();

struct BackendRunsRequest {
  std::string log;           ///< ROS1 bag, ROS 2 recording or scan folder
  std::string config_path;   ///< run configuration (YAML); its backend key is overridden
  std::string prior_map;     ///< prior map (PCD/PLY); empty = SLAM from scratch
  std::string guess;         ///< T_world_imu guess, localization::ParsePoseGuess text
  std::string ground_truth;  ///< TUM trajectory of the IMU; empty = no ATE/RPE
  std::string out_dir;       ///< back-end `b` writes out_dir/b/
  std::vector<std::string> backends = AllBackends();  ///< which, in order
  double rpe_delta_m = 1.0;  ///< RPE pair spacing along the reference path, m, > 0
};

/// One back-end's run as the parent sees it.
struct BackendRun {
  report::BackendRow row;                   ///< the table row
  std::string dir;                          ///< its output folder
  std::vector<io::StampedPose> trajectory;  ///< T_world_imu (empty unless the run finished)
  evaluation::AteResult ate;                ///< against ground truth (SE(3) aligned)
};

/// Runs every requested back-end in turn. Throws only for a bad request (no log, ...).
std::vector<BackendRun> RunBackends(const BackendRunsRequest& request);

/// The child's side: runs `backend` in this process into out_dir/backend/ and writes
/// process.json (this process's own peak resident memory). On failure it writes error.txt
/// (one line) before rethrowing.
void RunBackendHere(const BackendRunsRequest& request, const std::string& backend);

/// ATE/RPE of a trajectory against a TUM ground truth, into `row` (SE(3) alignment, the
/// reference interpolated at the estimate's stamps).
evaluation::AteResult EvaluateTrajectory(const std::vector<io::StampedPose>& trajectory,
                                         const std::string& ground_truth, double rpe_delta_m,
                                         report::BackendRow* row);

}  // namespace hylo::cli
