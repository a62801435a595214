// The randomized scenarios: the same number gives the same scenario and the same bytes; the
// draws span the ranges they promise; the IMU's motion (vibration, mounting) has exact
// derivatives; drives keep clear of everything on the site; every scan pattern fires where
// and when it should; the sensor sheet describes the true extrinsic to its stated precision.
#include "hylo/sim/scenario.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <set>

#include "hylo/common/time.h"
#include "hylo/sim/scenario_simulator.h"

namespace hylo::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

double AngleBetween(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  return Eigen::AngleAxisd(a.transpose() * b).angle();
}

TEST(Scenario, TheSameNumberGivesTheSameScenarioAndOthersDiffer) {
  const Scenario a = DrawScenario(7), b = DrawScenario(7), c = DrawScenario(8);
  EXPECT_EQ(a.Summary(), b.Summary());
  EXPECT_TRUE(a.T_imu_lidar.isApprox(b.T_imu_lidar, 0.0));
  EXPECT_EQ(a.imu.base.gyro_noise_density, b.imu.base.gyro_noise_density);
  EXPECT_EQ(a.site.yard_size_m, b.site.yard_size_m);
  EXPECT_NE(a.trajectory.cruise_speed_mps, c.trajectory.cruise_speed_mps);
  const Site site_a = BuildScenarioSite(a), site_b = BuildScenarioSite(b);
  ASSERT_EQ(site_a.route_a.size(), site_b.route_a.size());
  for (std::size_t i = 0; i < site_a.route_a.size(); ++i) {
    EXPECT_EQ(site_a.route_a[i], site_b.route_a[i]);
  }
  EXPECT_EQ(site_a.objects.size(), site_b.objects.size());
}

TEST(Scenario, DrawsSpanTheirRangesAndEverySensorOnBothParities) {
  std::set<std::pair<SensorKind, int>> sensor_parity;
  double min_speed = 1e9, max_speed = 0.0, max_slope = 0.0, min_grade = 1.0, max_grade = 0.0;
  int with_spur = 0;
  for (uint64_t n = 0; n < 24; ++n) {
    const Scenario s = DrawScenario(n);
    sensor_parity.insert({s.lidar.kind, static_cast<int>(n % 2)});
    min_speed = std::min(min_speed, s.trajectory.cruise_speed_mps);
    max_speed = std::max(max_speed, s.trajectory.cruise_speed_mps);
    max_slope = std::max(max_slope, s.site.start_slope_deg);
    min_grade = std::min(min_grade, s.imu.grade);
    max_grade = std::max(max_grade, s.imu.grade);
    with_spur += s.site.featureless_m > 0.0 ? 1 : 0;
    EXPECT_GE(s.trajectory.cruise_speed_mps, 0.5);
    EXPECT_LE(s.trajectory.cruise_speed_mps, 3.0);
    EXPECT_LE(s.site.start_slope_deg, 20.0);
    EXPECT_LE(s.T_imu_lidar.translation().norm(), 0.5 + 1e-12);
    EXPECT_LE(std::abs(s.lidar_time_offset_ns), 15'000'000);
    EXPECT_GE(s.imu.base.gravity_mps2, 9.78);
    EXPECT_LE(s.imu.base.gravity_mps2, 9.83);
    EXPECT_NEAR(s.T_imu_lidar.linear().determinant(), 1.0, 1e-12);
  }
  EXPECT_EQ(sensor_parity.size(), 2 * AllSensorKinds().size());
  EXPECT_LT(min_speed, 1.0);
  EXPECT_GT(max_speed, 2.5);
  EXPECT_GT(max_slope, 12.0);
  EXPECT_LT(min_grade, 0.2);
  EXPECT_GT(max_grade, 0.8);
  EXPECT_GT(with_spur, 4);
  EXPECT_LT(with_spur, 20);
}

// Central differences of the pose against the reported velocity, acceleration and body rate.
TEST(Scenario, TheImuMotionHasExactDerivativesAndStartsAtRest) {
  Scenario s = DrawScenario(3);
  s.max_drive_a_s = 20.0;
  const ScenarioSimulator sim(s, BuildScenarioSite(s), SessionId::kA);
  const VehicleMotion& motion = sim.motion();
  const KinematicState rest = motion.StateAt(0);
  for (int64_t t = 0; t <= SecondsToNanos(s.trajectory.standstill_s); t += 10'000'000) {
    const KinematicState x = motion.StateAt(t);
    ASSERT_LT(x.velocity_map.norm() + x.accel_map.norm() + x.omega_imu.norm(), 1e-12);
    ASSERT_LT((x.position_map - rest.position_map).norm(), 1e-12);
  }
  const int64_t h = 10'000;  // 10 us
  const double h_s = 1e-5;
  double worst_v = 0.0, worst_a = 0.0, worst_w = 0.0;
  for (const double t_s : {4.33, 4.97, 6.21, 9.74, 14.16}) {  // off the spline knots
    const int64_t t = SecondsToNanos(t_s);
    const KinematicState x = motion.StateAt(t), xm = motion.StateAt(t - h),
                         xp = motion.StateAt(t + h);
    const Eigen::Vector3d v = (xp.position_map - xm.position_map) / (2 * h_s);
    const Eigen::Vector3d a = (xp.velocity_map - xm.velocity_map) / (2 * h_s);
    const Eigen::AngleAxisd turn(xm.R_map_imu.transpose() * xp.R_map_imu);
    const Eigen::Vector3d w = turn.angle() * turn.axis() / (2 * h_s);
    worst_v = std::max(worst_v, (v - x.velocity_map).norm());
    worst_a = std::max(worst_a, (a - x.accel_map).norm());
    worst_w = std::max(worst_w, (w - x.omega_imu).norm());
  }
  EXPECT_LT(worst_v, 1e-6);
  EXPECT_LT(worst_a, 1e-4);
  EXPECT_LT(worst_w, 1e-5);
  // The vibration is really there: accelerations well beyond a ground robot's driving.
  double peak_accel = 0.0;
  for (int64_t t = SecondsToNanos(7.0); t < SecondsToNanos(8.0); t += 1'000'000) {
    peak_accel = std::max(peak_accel, motion.StateAt(t).accel_map.norm());
  }
  EXPECT_GT(peak_accel, 0.1);
}

TEST(Scenario, DrivesKeepClearOfEverythingAndStartOnTheDrawnSlope) {
  for (const uint64_t n : {0, 5, 11, 16}) {
    Scenario s = DrawScenario(n);
    const Site site = BuildScenarioSite(s);
    for (const SessionId session : {SessionId::kA, SessionId::kB}) {
      const ScenarioSimulator sim(s, site, session);
      const VehicleMotion& motion = sim.motion();
      double closest = 1e9;
      for (int64_t t = 0; t < sim.duration_ns(); t += 200'000'000) {
        const Eigen::Vector3d p = motion.vehicle().PoseAt(t).translation();
        for (const Primitive& q : sim.world().primitives()) {
          closest = std::min(closest, SignedDistance(q, p));
        }
      }
      EXPECT_GT(closest, 0.8) << "scenario " << n << " session " << ToString(session);
    }
    // The vehicle's tilt at the start (the IMU may sit in any orientation on it).
    const ScenarioSimulator sim(s, site, SessionId::kA);
    const Eigen::Vector3d up_vehicle =
        sim.motion().vehicle().PoseAt(0).linear() * Eigen::Vector3d::UnitZ();
    const double tilt_deg = std::acos(std::min(1.0, up_vehicle.z())) / kDeg;
    EXPECT_NEAR(tilt_deg, s.site.start_slope_deg, 8.0) << "scenario " << n;
  }
}

TEST(Scenario, PatternsFireWithinTheirFrameAndTheRosetteNeverRepeats) {
  for (const SensorKind kind : AllSensorKinds()) {
    const ScanPattern pattern(kind);
    std::vector<Shot> shots;
    pattern.Frame(3, &shots);
    ASSERT_EQ(shots.size(), pattern.shots_per_frame()) << ToString(kind);
    uint16_t max_ring = 0;
    for (std::size_t i = 0; i < shots.size(); ++i) {
      ASSERT_GE(shots[i].offset_ns, 0);
      ASSERT_LT(shots[i].offset_ns, pattern.period_ns());
      if (i > 0) {
        ASSERT_GE(shots[i].offset_ns, shots[i - 1].offset_ns);
      }
      ASSERT_NEAR(shots[i].direction_lidar.norm(), 1.0, 1e-12);
      max_ring = std::max(max_ring, shots[i].ring);
    }
    const int channels[] = {16, 16, 32, 64, 128, 6};
    EXPECT_EQ(max_ring + 1, channels[static_cast<int>(kind)]) << ToString(kind);
  }
  const ScanPattern rosette(SensorKind::kLivoxRosette);
  std::vector<Shot> one, two;
  rosette.Frame(10, &one);
  rosette.Frame(11, &two);
  double moved = 0.0, widest = 0.0;
  for (std::size_t i = 0; i < one.size(); ++i) {
    moved += (one[i].direction_lidar - two[i].direction_lidar).norm() / one.size();
    widest = std::max(widest, std::acos(one[i].direction_lidar.x()));
  }
  EXPECT_GT(moved, 0.05) << "frames of a non-repetitive pattern differ";
  EXPECT_NEAR(widest / kDeg, 35.2, 2.5) << "a 70 deg field of view";
}

TEST(Scenario, TheSheetGivesTheExtrinsicToItsPrecision) {
  for (uint64_t n = 0; n < 12; ++n) {
    const Scenario s = DrawScenario(n);
    const SensorSheet sheet = SheetOf(s);
    const Eigen::Vector3d rpy = sheet.rotation_rpy_deg * kDeg;
    const Eigen::Matrix3d R = RotationFromYawPitchRoll(rpy.z(), rpy.y(), rpy.x());
    EXPECT_LT(AngleBetween(R, s.T_imu_lidar.linear()), 0.1 * kDeg) << n;
    EXPECT_LT((sheet.translation_m - s.T_imu_lidar.translation()).cwiseAbs().maxCoeff(),
              5e-4 + 1e-12);
    EXPECT_LE(std::abs(sheet.lidar_time_offset_s - 1e-9 * s.lidar_time_offset_ns), 5e-4 + 1e-12);
    EXPECT_LE(std::abs(sheet.rotation_rpy_deg.y()), 90.0);
    EXPECT_NE(sheet.ToYaml().find("preset: " + s.lidar.preset), std::string::npos);
  }
}

// Two runs of the same short session give the same bytes; scans carry the clock offset.
TEST(Scenario, SessionsAreReproducibleAndStampedOnTheLidarClock) {
  Scenario s = DrawScenario(0);  // a 16-beam head: quick
  s.max_drive_a_s = 1.0;
  const Site site = BuildScenarioSite(s);
  SessionRecording one, two;
  ScenarioSimulator(s, site, SessionId::kA).Run(&one);
  ScenarioSimulator(s, site, SessionId::kA).Run(&two);
  ASSERT_EQ(one.scans.size(), two.scans.size());
  ASSERT_GT(one.scans.size(), 40u);
  for (std::size_t i = 0; i < one.scans.size(); ++i) {
    ASSERT_EQ(one.scans[i].points.size(), two.scans[i].points.size());
    for (std::size_t k = 0; k < one.scans[i].points.size(); ++k) {
      ASSERT_EQ(one.scans[i].points[k].position_lidar, two.scans[i].points[k].position_lidar);
    }
    EXPECT_EQ(one.scans[i].t_ns,
              s.start_a_ns + static_cast<int64_t>(i) * 100'000'000 + s.lidar_time_offset_ns);
  }
  ASSERT_EQ(one.imu.size(), two.imu.size());
  EXPECT_EQ(one.imu.back().accel_imu, two.imu.back().accel_imu);
  // At rest the accelerometer reads about the local gravity (biases and scale errors aside).
  EXPECT_NEAR(one.imu.front().accel_imu.norm(), s.imu.base.gravity_mps2, 0.5);
}

}  // namespace
}  // namespace hylo::sim
