#pragma once
// The per-scan files of a run (private to hylo::run): trajectory, odometry stream, timing.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "hylo/config/run_config.h"
#include "hylo/odometry/odometry_pipeline.h"
#include "hylo/io/trajectory_io.h"

namespace hylo::run {

/// T_world_imu of each state: the map pose plus the map's world origin.
std::vector<io::StampedPose> WorldTrajectory(const std::vector<estimation::NavState>& states,
                                             const Eigen::Vector3d& origin_world);
/// The live states of `results` whose pose is a place in the map (`valid`), or of the others
/// (lost, or provisional while searching).
std::vector<estimation::NavState> LiveStates(const std::vector<odometry::ScanResult>& results,
                                            bool valid);

/// odometry.csv: per scan at its end time, frames named by `frames`, pose T_world_base, body
/// twist, pose covariance [x y z (world/map axes, m); rx ry rz (base axes, rad)] and twist
/// covariance [vx vy vz; wx wy wz] (base axes), row-major, the map→odom transform and health.
void WriteOdometryCsv(const std::string& path, const std::vector<odometry::ScanResult>& results,
                      const Eigen::Vector3d& origin_world, const config::OutputFrames& frames);

/// timing.csv: per-scan sizes, update figures and wall/CPU times.
void WriteTimingCsv(const std::string& path, const std::vector<odometry::ScanResult>& results);

/// The q-quantile (0..1, nearest rank) of `values`; 0 for none.
double Percentile(std::vector<double> values, double q);

}  // namespace hylo::run
