// Ground truth consistency: integrating the noise-free IMU reproduces the trajectory; the
// vehicle rests at the start, keeps its speed in the configured range and hits nothing.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>

#include "hylo/common/time.h"
#include "hylo/sim/imu_model.h"
#include "hylo/sim/simulator.h"

namespace hylo::sim {
namespace {

// Exp map of SO(3) (Rodrigues), kept local so the test checks the simulator, not Lie code.
Eigen::Matrix3d Exp(const Eigen::Vector3d& phi) {
  const double angle = phi.norm();
  if (angle < 1e-12) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, phi / angle).toRotationMatrix();
}

class GroundTruth : public ::testing::TestWithParam<SessionId> {
 protected:
  void SetUp() override {
    TerrainOptions terrain;
    terrain.resolution_m = 0.4;
    site_ = BuildSite(21, terrain);
    Rng rng(99);
    traj_ = Trajectory::FromRoute(GetParam() == SessionId::kA ? site_.route_a : site_.route_b,
                                  *site_.terrain, options_, SecondsToNanos(60.0), &rng);
  }
  Site site_;
  TrajectoryOptions options_;
  Trajectory traj_;
};

// Trapezoidal integration of the 200 Hz noise-free IMU over 10 s of motion (from 3 s: the
// vehicle starts moving inside the window), starting from the true state.
TEST_P(GroundTruth, IntegratingNoiseFreeImuReproducesTheTrajectory) {
  const double g = 9.81;
  const int64_t dt_ns = 5'000'000, t_begin = SecondsToNanos(3.0), t_end = SecondsToNanos(13.0);
  const double dt = NanosToSeconds(dt_ns);
  KinematicState s = traj_.StateAt(t_begin);
  Eigen::Matrix3d R = s.R_map_imu;
  Eigen::Vector3d p = s.position_map, v = s.velocity_map;
  ImuSample prev = TrueImuSample(s, g, t_begin);
  const Eigen::Vector3d gravity(0, 0, -g);
  double max_position_error = 0.0, max_angle_error = 0.0;
  for (int64_t t = t_begin + dt_ns; t <= t_end; t += dt_ns) {
    const KinematicState truth = traj_.StateAt(t);
    const ImuSample cur = TrueImuSample(truth, g, t);
    const Eigen::Matrix3d R_next = R * Exp(0.5 * (prev.gyro_imu + cur.gyro_imu) * dt);
    const Eigen::Vector3d a0 = R * prev.accel_imu + gravity;
    const Eigen::Vector3d a1 = R_next * cur.accel_imu + gravity;
    p += v * dt + (a0 / 3.0 + a1 / 6.0) * dt * dt;  // exact for linearly varying a
    v += 0.5 * (a0 + a1) * dt;
    R = R_next;
    prev = cur;
    max_position_error = std::max(max_position_error, (p - truth.position_map).norm());
    max_angle_error =
        std::max(max_angle_error, Eigen::AngleAxisd(R.transpose() * truth.R_map_imu).angle());
  }
  EXPECT_LT(max_position_error, 0.01) << "m over 10 s";
  EXPECT_LT(max_angle_error, 1e-3) << "rad over 10 s";
  // The window must contain real motion, or the test proves nothing.
  EXPECT_GT((traj_.StateAt(t_end).position_map - traj_.StateAt(t_begin).position_map).norm(), 5.0);
}

TEST_P(GroundTruth, StandsStillThenDrivesWithinTheSpeedRange) {
  const KinematicState start = traj_.StateAt(0);
  for (int64_t t = 0; t <= SecondsToNanos(options_.standstill_s); t += 5'000'000) {
    const KinematicState s = traj_.StateAt(t);
    ASSERT_LT(s.velocity_map.norm(), 1e-12);
    ASSERT_LT(s.omega_imu.norm(), 1e-12);
    ASSERT_LT((s.position_map - start.position_map).norm(), 1e-12);
    const ImuSample imu = TrueImuSample(s, 9.81, t);
    ASSERT_NEAR(imu.accel_imu.norm(), 9.81, 1e-9);  // at rest: reads +g upward
  }
  double max_speed = 0.0;
  for (int64_t t = 0; t <= traj_.duration_ns(); t += 50'000'000) {
    const KinematicState s = traj_.StateAt(t);
    max_speed = std::max(max_speed, s.velocity_map.head<2>().norm());
  }
  EXPECT_LE(max_speed, 1.5);
  EXPECT_GE(max_speed, 0.5);
  EXPECT_GT(traj_.path_length_m(), 40.0);
}

// The vehicle (a 1.4 m x 1.0 m footprint, 1.5 m tall) never overlaps a structure.
TEST_P(GroundTruth, RouteIsCollisionFree) {
  const std::vector<Primitive> parts = SessionPrimitives(site_, GetParam());
  for (int64_t t = 0; t <= traj_.duration_ns(); t += 100'000'000) {
    const Eigen::Vector3d p = traj_.StateAt(t).position_map;
    for (const Primitive& part : parts) {
      const Aabb box = BoundsOf(part);
      const double gap_x = std::max({box.min.x() - p.x(), p.x() - box.max.x(), 0.0});
      const double gap_y = std::max({box.min.y() - p.y(), p.y() - box.max.y(), 0.0});
      const bool overlaps_height = box.min.z() < p.z() + 1.0 && box.max.z() > p.z() - 0.8;
      ASSERT_FALSE(std::hypot(gap_x, gap_y) < 0.8 && overlaps_height)
          << "t = " << NanosToSeconds(t) << " s at (" << p.transpose() << ") object "
          << site_.objects[part.object_id].kind;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Sessions, GroundTruth, ::testing::Values(SessionId::kA, SessionId::kB),
                         [](const auto& info) { return "session_" + ToString(info.param); });

}  // namespace
}  // namespace hylo::sim
