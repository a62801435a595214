// Lidar and session stream: per-point times inside the scan period, every return explained
// by the true pose at its own time, rates and arrival order, determinism in memory.
#include <gtest/gtest.h>

#include <cmath>

#include "hylo/common/time.h"
#include "hylo/sim/simulator.h"

namespace hylo::sim {
namespace {

class LidarSession : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    options_ = new SimulationOptions(SimulationOptions::Fast(8.0));
    site_ = new Site(BuildSite(options_->seed, options_->terrain));
  }
  static void TearDownTestSuite() {
    delete site_;
    delete options_;
  }
  static SimulationOptions* options_;
  static Site* site_;
};
SimulationOptions* LidarSession::options_ = nullptr;
Site* LidarSession::site_ = nullptr;

TEST_F(LidarSession, PerPointTimesLieInsideTheScanPeriod) {
  for (const LidarModel model : {LidarModel::kVlp16, LidarModel::kRs16}) {
    SimulationOptions options = *options_;
    options.lidar.model = model;
    const SessionSimulator sim(options, *site_, SessionId::kA);
    const int64_t period = sim.lidar().period_ns();
    for (const int index : {0, 45, 79}) {
      const LidarScan scan = sim.lidar().Scan(index, sim.start_ns());
      ASSERT_GT(scan.points.size(), 1000u);
      EXPECT_EQ(scan.t_ns, sim.start_ns() + index * period);
      for (const auto& p : scan.points) {
        ASSERT_GE(p.offset_ns, 0);
        ASSERT_LT(p.offset_ns, period);
        ASSERT_LT(p.ring, 16);
        const double range = p.position_lidar.cast<double>().norm();
        ASSERT_GE(range, options.lidar.min_range_m);
        ASSERT_LE(range, options.lidar.max_range_m);
      }
      EXPECT_LE(scan.end_t_ns, scan.t_ns + period);
    }
  }
}

// Each return, put in the map with the true pose at the return's own time, lands where
// the ray hit (exactly along the beam; within the range noise along it).
TEST_F(LidarSession, ReturnsAreExplainedByTheTruePoseAtTheirTime) {
  for (const double noise : {0.0, 0.02}) {
    SimulationOptions options = *options_;
    options.lidar.range_noise_m = noise;
    const SessionSimulator sim(options, *site_, SessionId::kB);
    const int64_t period = sim.lidar().period_ns();
    double max_along = 0.0, max_across = 0.0;
    for (const int index : {50, 70}) {  // the vehicle moves after 4.2 s
      std::vector<ReturnTruth> truth;
      const LidarScan scan = sim.lidar().Scan(index, sim.start_ns(), &truth);
      ASSERT_EQ(truth.size(), scan.points.size());
      for (size_t i = 0; i < truth.size(); ++i) {
        const auto& p = scan.points[i];
        const Eigen::Isometry3d T_map_lidar =
            sim.trajectory().PoseAt(index * period + p.offset_ns) * options.lidar.T_imu_lidar;
        const Eigen::Vector3d origin = T_map_lidar.translation();
        const Eigen::Vector3d measured = T_map_lidar * p.position_lidar.cast<double>();
        const Eigen::Vector3d beam = (truth[i].point_map - origin).normalized();
        const Eigen::Vector3d error = measured - truth[i].point_map;
        max_along = std::max(max_along, std::abs(error.dot(beam)));
        max_across = std::max(max_across, (error - error.dot(beam) * beam).norm());
      }
    }
    EXPECT_LT(max_across, 1e-4) << "float rounding only";
    EXPECT_LT(max_along, 6.0 * noise + 1e-4);
    if (noise > 0.0) {
      EXPECT_GT(max_along, noise);  // the noise is really there
    }
  }
}

TEST_F(LidarSession, StreamHasTheRatesAndArrivalOrder) {
  const SessionSimulator sim(*options_, *site_, SessionId::kA);
  SessionRecording rec;
  const SessionSummary summary = sim.Run(&rec);
  ASSERT_EQ(rec.scans.size(), 80u);  // 8 s at 10 Hz
  ASSERT_EQ(rec.imu.size(), 1601u);  // 8 s at 200 Hz, both ends
  ASSERT_EQ(rec.truth.size(), rec.imu.size());
  EXPECT_EQ(summary.scans, rec.scans.size());
  for (size_t i = 1; i < rec.imu.size(); ++i) {
    ASSERT_EQ(rec.imu[i].t_ns - rec.imu[i - 1].t_ns, 5'000'000);
  }
  for (size_t i = 1; i < rec.scans.size(); ++i) {
    ASSERT_EQ(rec.scans[i].t_ns - rec.scans[i - 1].t_ns, 100'000'000);
  }
  // At rest the accelerometer reads about +g along the IMU's up axis.
  double mean_norm = 0.0;
  for (int i = 0; i < 400; ++i) mean_norm += rec.imu[i].accel_imu.norm() / 400.0;
  EXPECT_NEAR(mean_norm, options_->imu.gravity_mps2, 0.1);
}

TEST_F(LidarSession, SameSeedSameDataDifferentSeedDifferentData) {
  const auto run = [&](uint64_t seed) {
    SimulationOptions options = *options_;
    options.seed = seed;
    options.duration_a_s = 1.0;
    const Site site = BuildSite(seed, options.terrain);
    SessionRecording rec;
    SessionSimulator(options, site, SessionId::kA).Run(&rec);
    return rec;
  };
  const SessionRecording a = run(5), b = run(5), c = run(6);
  ASSERT_EQ(a.scans.size(), b.scans.size());
  bool differs = false;
  for (size_t s = 0; s < a.scans.size(); ++s) {
    ASSERT_EQ(a.scans[s].points.size(), b.scans[s].points.size());
    for (size_t i = 0; i < a.scans[s].points.size(); ++i) {
      ASSERT_EQ(a.scans[s].points[i].position_lidar, b.scans[s].points[i].position_lidar);
      ASSERT_EQ(a.scans[s].points[i].intensity, b.scans[s].points[i].intensity);
    }
    differs |= a.scans[s].points.size() != c.scans[s].points.size();
  }
  for (size_t i = 0; i < a.imu.size(); ++i) ASSERT_EQ(a.imu[i].accel_imu, b.imu[i].accel_imu);
  EXPECT_TRUE(differs || a.imu[0].accel_imu != c.imu[0].accel_imu);
}

}  // namespace
}  // namespace hylo::sim
