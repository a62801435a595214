// Static initialisation: gravity direction, gyro bias, and clear errors when it cannot work.
#include "hylo/estimation/imu_initializer.h"

#include <gtest/gtest.h>

#include <random>

namespace hylo::estimation {
namespace {

// 200 Hz samples of a sensor at rest with orientation R_map_imu, plus white noise.
std::vector<ImuSample> AtRest(const Eigen::Matrix3d& R_map_imu, const Eigen::Vector3d& gyro_bias,
                              double seconds, double g) {
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 0.02);
  std::vector<ImuSample> samples;
  for (int i = 0; i <= seconds * 200; ++i) {
    ImuSample s;
    s.t_ns = i * 5'000'000LL;
    s.accel_imu = R_map_imu.transpose() * Eigen::Vector3d(0, 0, g) +
                  Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    s.gyro_imu = gyro_bias + 0.01 * Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    samples.push_back(s);
  }
  return samples;
}

TEST(ImuInitializer, RecoversRollPitchAndGyroBias) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(-0.15, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  const Eigen::Vector3d bias(0.003, -0.002, 0.001);
  ImuInitializer init(ImuInitializerOptions{}, 9.81);
  for (const ImuSample& s : AtRest(R, bias, 1.5, 9.81)) init.Add(s);
  ASSERT_EQ(init.status(), ImuInitializer::Status::kDone) << init.message();
  // The estimated orientation maps the IMU's up direction like the truth (yaw is free).
  const Eigen::Vector3d up_true = R.transpose() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d up_est = init.state().R_map_imu.Inverse() * Eigen::Vector3d::UnitZ();
  EXPECT_LT(std::acos(std::min(1.0, up_true.dot(up_est))), 2e-3);  // rad
  EXPECT_LT((init.state().gyro_bias - bias).norm(), 2e-3);
  EXPECT_NEAR(init.state().gravity_map.z(), -9.81, 1e-12);
}

// A log that starts on the move still gets a start: the attitude from the mean specific force
// (here the vehicle turns and surges about a level mean), no gyro bias (the rate is the turn).
TEST(ImuInitializer, ReportsMotionDuringInitialisationAndGivesAMovingStart) {
  std::vector<ImuSample> samples = AtRest(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(),
                                          1.5, 9.81);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    samples[i].gyro_imu.z() += 0.5 * std::sin(0.05 * i);  // turning
    samples[i].accel_imu.x() += 1.0 * std::sin(0.03 * i);
  }
  ImuInitializer init(ImuInitializerOptions{}, 9.81);
  for (const ImuSample& s : samples) init.Add(s);
  ASSERT_EQ(init.status(), ImuInitializer::Status::kMoving);
  EXPECT_NE(init.message().find("moves"), std::string::npos) << init.message();
  const Eigen::Vector3d up_est = init.state().R_map_imu.Matrix().transpose() *
                                 Eigen::Vector3d::UnitZ();
  EXPECT_LT(std::acos(std::min(1.0, up_est.z())), 0.05);  // rad: the sine means average out
  EXPECT_EQ(init.state().gyro_bias, Eigen::Vector3d::Zero());
}

TEST(ImuInitializer, ReportsAccelerationsInTheWrongUnit) {
  ImuInitializer init(ImuInitializerOptions{}, 9.81);
  for (const ImuSample& s : AtRest(Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), 1.5,
                                   1.0)) {  // a driver reporting g
    init.Add(s);
  }
  ASSERT_EQ(init.status(), ImuInitializer::Status::kFailed);
  EXPECT_NE(init.message().find("accel_scale"), std::string::npos) << init.message();
}

}  // namespace
}  // namespace hylo::estimation
