#pragma once
// What `hylo demo` derives from the simulation before it runs anything: the run configuration
// that matches the simulated sensors (so the demo needs no file from the checkout), and the
// rough initial guess of session B's start in the prior map's frame.

#include <Eigen/Geometry>
#include <string>

#include "hylo/config/run_config.h"
#include "hylo/evaluation/trajectory_metrics.h"
#include "hylo/io/trajectory_io.h"
#include "hylo/sim/simulator.h"

namespace hylo::cli {

/// The configuration of config/presets/sim_vlp16.yaml, taken from `sim` itself: topics, Velodyne
/// point times, range limits, IMU rate and noise, and the simulator's lidar mounting.
config::RunConfig ConfigForSimulation(const sim::SimulationOptions& sim);

/// How far the demo's initial guess is from the truth.
struct GuessError {
  double translation_m = 1.0;  ///< horizontal offset of the guess, m
  double yaw_deg = 10.0;       ///< yaw offset of the guess, deg
};

/// T_map_imu guess of session B's first pose: the true pose (simulator frame, first line of
/// `truth_b_path`) moved into the prior map's frame with the inverse of session A's SE(3)
/// alignment `ate_a` (map A -> simulator), then offset by `error` (translation along
/// 36.87 deg, i.e. (0.8, 0.6) for 1 m, and yaw).
Eigen::Isometry3d SessionBGuess(const std::string& truth_b_path, const evaluation::AteResult& ate_a,
                                const GuessError& error);

/// Position error of session B's estimate (map frame) against B's truth without fitting a new
/// alignment: the estimate is taken into the truth's frame with session A's alignment
/// `ate_a`, so an offset between B's poses and the map the robot was given is not aligned
/// away (the SE(3)-aligned ATE of the table would hide it). RMSE, m; NaN when not computable.
double PriorFrameErrorRmse(const std::vector<io::StampedPose>& trajectory_map,
                           const std::string& truth_b_path, const evaluation::AteResult& ate_a);

/// A pose as the 16 numbers of localization::ParsePoseGuess (row-major 4×4), exact to 1e-12.
std::string PoseAsGuessText(const Eigen::Isometry3d& T);

}  // namespace hylo::cli
