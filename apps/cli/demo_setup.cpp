#include "demo_setup.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "hylo/io/trajectory_io.h"

namespace hylo::cli {

config::RunConfig ConfigForSimulation(const sim::SimulationOptions& sim) {
  config::RunConfig c;
  odometry::OdometryPipelineOptions& p = c.pipeline;
  p.estimator.backend = estimation::Estimator::Backend::kIeskf;
  c.lidar.topic = "/points";
  c.lidar.time_convention = logs::PointTimeConvention::kVelodyne;
  p.preprocess.min_range_m = sim.lidar.min_range_m;
  p.preprocess.max_range_m = sim.lidar.max_range_m;
  c.imu.topic = "/imu";
  p.imu.rate_hz = sim.imu.rate_hz;
  p.imu.gravity_mps2 = sim.imu.gravity_mps2;
  p.imu.noise.gyro_noise_density = sim.imu.gyro_noise_density;
  p.imu.noise.accel_noise_density = sim.imu.accel_noise_density;
  p.imu.noise.gyro_bias_random_walk = sim.imu.gyro_bias_random_walk;
  p.imu.noise.accel_bias_random_walk = sim.imu.accel_bias_random_walk;
  const Eigen::Isometry3d& T = sim.lidar.T_imu_lidar;
  // R = Rz(yaw) Ry(pitch) Rx(roll): Eigen's Euler angles about z, y, x give yaw, pitch, roll.
  const Eigen::Vector3d ypr = T.linear().eulerAngles(2, 1, 0) * 180.0 / M_PI;
  c.T_imu_lidar.translation_m = T.translation();
  c.T_imu_lidar.rotation_rpy_deg = Eigen::Vector3d(ypr.z(), ypr.y(), ypr.x());
  p.preprocess.scan_voxel_m = 0.5;
  p.map.voxel_size_m = 0.5;
  return c;
}

Eigen::Isometry3d SessionBGuess(const std::string& truth_b_path, const evaluation::AteResult& ate_a,
                                const GuessError& error) {
  if (!ate_a.ok)
    throw std::runtime_error("session A's alignment to the truth failed: " + ate_a.message);
  const std::vector<io::StampedPose> truth = io::ReadTum(truth_b_path);
  if (truth.empty()) throw std::runtime_error(truth_b_path + ": no pose");
  Eigen::Isometry3d T_map_imu =
      ate_a.T_reference_estimate.inverse() * truth.front().T_world_body();
  const double direction = std::atan2(0.6, 0.8);
  T_map_imu.translation() +=
      error.translation_m * Eigen::Vector3d(std::cos(direction), std::sin(direction), 0.0);
  // Yaw about the map's vertical, applied on the left so roll and pitch stay as they were.
  const Eigen::Matrix3d R_yaw =
      Eigen::AngleAxisd(error.yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T_map_imu.linear() = R_yaw * T_map_imu.linear();
  return T_map_imu;
}

double PriorFrameErrorRmse(const std::vector<io::StampedPose>& trajectory_map,
                           const std::string& truth_b_path, const evaluation::AteResult& ate_a) {
  std::vector<evaluation::TimedPose> estimate, truth;
  for (const io::StampedPose& p : trajectory_map) {
    estimate.push_back({p.t_ns, ate_a.T_reference_estimate * p.T_world_body()});
  }
  for (const io::StampedPose& p : io::ReadTum(truth_b_path)) {
    truth.push_back({p.t_ns, p.T_world_body()});
  }
  evaluation::AteOptions options;
  options.alignment = evaluation::Alignment::kNone;
  const evaluation::AteResult ate = evaluation::ComputeAte(estimate, truth, options);
  return ate.ok ? ate.rmse_m : std::nan("");
}

std::string PoseAsGuessText(const Eigen::Isometry3d& T) {
  std::string text;
  char number[40];
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      std::snprintf(number, sizeof(number), "%s%.15g", text.empty() ? "" : " ", T.matrix()(r, c));
      text += number;
    }
  }
  return text;
}

}  // namespace hylo::cli
