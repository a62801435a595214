// IMU propagation of the filter (PredictAt and Update's covariance propagation share the same
// code) against the simulator's noise-free IMU and ground-truth trajectory.
#include <gtest/gtest.h>

#include "hylo/common/time.h"
#include "hylo/estimation/ieskf/ieskf.h"
#include "hylo/estimation/imu_propagation.h"
#include "hylo/estimation/initial_uncertainty.h"
#include "hylo/sim/imu_model.h"
#include "hylo/sim/simulator.h"

namespace hylo::estimation {
namespace {

// A map with nothing in it: an Update is then a propagation alone.
class EmptyMap : public registration::NeighborSearch {
 public:
  void KNearest(const Eigen::Vector3f&, int, float,
                std::vector<registration::Neighbor>* n) const override {
    n->clear();
  }
  std::size_t Size() const override { return 0; }
};

NavState FromTruth(const sim::KinematicState& s, int64_t t_ns, double g) {
  NavState x;
  x.t_ns = t_ns;
  x.R_map_imu = lie::SO3d::FromMatrix(s.R_map_imu);
  x.p_map_imu = s.position_map;
  x.v_map_imu = s.velocity_map;
  x.gravity_map = Eigen::Vector3d(0, 0, -g);
  return x;
}

TEST(ImuPropagation, NoiseFreeImuReproducesTheTrajectory) {
  sim::TerrainOptions terrain;
  terrain.resolution_m = 0.4;
  const sim::Site site = sim::BuildSite(21, terrain);
  sim::Rng rng(99);
  const sim::Trajectory traj = sim::Trajectory::FromRoute(
      site.route_a, *site.terrain, sim::TrajectoryOptions{}, SecondsToNanos(40.0), &rng);
  const double g = 9.81;
  const int64_t dt_ns = 5'000'000, t0 = SecondsToNanos(3.0), t1 = SecondsToNanos(13.0);
  Ieskf filter(EstimatorOptions{}, ImuOptions{});
  filter.Initialize(FromTruth(traj.StateAt(t0), t0, g), InitialUncertainty().SlamCovariance());
  for (int64_t t = t0; t <= t1; t += dt_ns) {
    filter.AddImu(sim::TrueImuSample(traj.StateAt(t), g, t));
  }
  double max_position_error = 0.0, max_angle_error = 0.0, distance = 0.0;
  Eigen::Vector3d last = traj.StateAt(t0).position_map;
  for (int64_t t = t0 + 100'000'000; t <= t1; t += 100'000'000) {
    const sim::KinematicState truth = traj.StateAt(t);
    const NavState x = filter.PredictAt(t);
    max_position_error = std::max(max_position_error, (x.p_map_imu - truth.position_map).norm());
    max_angle_error = std::max(
        max_angle_error,
        lie::Minus(x.R_map_imu, lie::SO3d::FromMatrix(truth.R_map_imu)).norm());
    distance += (truth.position_map - last).norm();
    last = truth.position_map;
  }
  std::printf("10 s, %.1f m: max position error %.4f m, max angle error %.5f rad\n", distance,
              max_position_error, max_angle_error);
  EXPECT_GT(distance, 3.0);  // the vehicle moves in this window
  EXPECT_LT(max_position_error, 0.05);
  EXPECT_LT(max_angle_error, 2e-3);
}

// A sweep after a long lidar gap asks for a dozen times at the end of thousands of samples:
// one walk must give what each time's own propagation gives, to the last bit, across a gap in
// the IMU, past its last sample, on sample stamps and before the state.
TEST(ImuPropagation, OneWalkGivesEachTimesOwnPrediction) {
  sim::Rng rng(7);
  std::vector<ImuSample> imu;
  const int64_t t0 = SecondsToNanos(100.0);
  for (int i = 1; i <= 2000; ++i) {
    if (i > 900 && i < 1100) continue;  // a 1 s hole in the IMU
    ImuSample s;
    s.t_ns = t0 + int64_t{i} * 5'000'000;
    s.accel_imu = Eigen::Vector3d(0.3 * rng.Gaussian(), 0.3 * rng.Gaussian(), 9.81);
    s.gyro_imu = Eigen::Vector3d(0.05 * rng.Gaussian(), 0.05 * rng.Gaussian(), 0.2);
    imu.push_back(s);
  }
  NavState x0;
  x0.t_ns = t0 + 2'500'000;
  x0.v_map_imu = Eigen::Vector3d(1.5, 0.2, 0.0);
  x0.gravity_map = Eigen::Vector3d(0, 0, -9.81);
  ImuGapModel gap;
  gap.gap_ns = 50'000'000;
  gap.accel_sigma_mps2 = 0.3;
  gap.gyro_sigma_radps = 0.05;
  gap.accel_mean_imu = Eigen::Vector3d(0, 0, 9.81);
  const std::vector<int64_t> times{t0 - 1'000'000,   t0 + 2'500'000,   t0 + 5'000'000,
                                   t0 + 4'000'000'000, t0 + 4'600'000'000, t0 + 5'000'000'000,
                                   t0 + 5'500'000'007, t0 + 9'995'000'000, t0 + 12'000'000'000};
  for (const bool use_imu : {true, false}) {
    const Eigen::Vector3d omega(0.0, 0.0, 0.1);
    const std::vector<NavState> along =
        PredictNominalAlong(x0, imu, use_imu, omega, times, &gap);
    ASSERT_EQ(along.size(), times.size());
    for (std::size_t k = 0; k < times.size(); ++k) {
      const NavState own = PredictNominal(x0, imu, use_imu, omega, times[k], &gap);
      EXPECT_EQ(along[k].t_ns, own.t_ns) << k;
      EXPECT_TRUE(along[k].p_map_imu == own.p_map_imu) << k << ": " << along[k].p_map_imu.transpose()
                                                       << " vs " << own.p_map_imu.transpose();
      EXPECT_TRUE(along[k].v_map_imu == own.v_map_imu) << k;
      EXPECT_TRUE(along[k].R_map_imu.Matrix() == own.R_map_imu.Matrix()) << k;
    }
    EXPECT_GT((along.back().p_map_imu - x0.p_map_imu).norm(), 5.0);  // it did move
  }
}

// A state carried forward on the IMU as it arrives (through a lidar gap) is the state the
// next update would reach from where it was: the walk splits at a sample stamp either way.
TEST(ImuPropagation, CarryingForwardOnTheWayChangesNothing) {
  sim::Rng rng(11);
  std::vector<ImuSample> imu;
  for (int i = 0; i <= 2400; ++i) {
    ImuSample s;
    s.t_ns = int64_t{i} * 5'000'000 + 1'234;
    s.accel_imu = Eigen::Vector3d(0.3 * rng.Gaussian(), 0.3 * rng.Gaussian(), 9.81);
    s.gyro_imu = Eigen::Vector3d(0.05 * rng.Gaussian(), 0.05 * rng.Gaussian(), 0.2);
    imu.push_back(s);
  }
  const EmptyMap map;
  const registration::PlaneMatcher matcher(map, registration::PlaneMatcherOptions{});
  NavState x0;
  x0.t_ns = 0;
  x0.v_map_imu = Eigen::Vector3d(1.5, 0.2, 0.0);
  x0.gravity_map = Eigen::Vector3d(0, 0, -9.81);
  DeskewedScan scan;
  scan.t_ns = imu.back().t_ns - 2'000'000;
  Ieskf whole(EstimatorOptions{}, ImuOptions{}), carried(EstimatorOptions{}, ImuOptions{});
  whole.Initialize(x0, InitialUncertainty().SlamCovariance());
  carried.Initialize(x0, InitialUncertainty().SlamCovariance());
  for (std::size_t i = 0; i < imu.size(); ++i) {
    whole.AddImu(imu[i]);
    carried.AddImu(imu[i]);
    if (i % 60 == 59 && i < 2200) carried.CarryForward(imu[i].t_ns);
  }
  EXPECT_EQ(carried.state().t_ns, imu[2159].t_ns);
  whole.Update(scan, matcher);
  carried.Update(scan, matcher);
  EXPECT_EQ(carried.state().t_ns, whole.state().t_ns);
  EXPECT_TRUE(carried.state().p_map_imu == whole.state().p_map_imu)
      << carried.state().p_map_imu.transpose() << " vs " << whole.state().p_map_imu.transpose();
  EXPECT_TRUE(carried.state().v_map_imu == whole.state().v_map_imu);
  EXPECT_TRUE(carried.state().R_map_imu.Matrix() == whole.state().R_map_imu.Matrix());
  EXPECT_TRUE(carried.Covariance() == whole.Covariance())
      << (carried.Covariance() - whole.Covariance()).cwiseAbs().maxCoeff();
  EXPECT_GT((whole.state().p_map_imu - x0.p_map_imu).norm(), 5.0);  // it did move
}

TEST(ImuPropagation, CovarianceGrowsWithoutMeasurements) {
  Ieskf filter(EstimatorOptions{}, ImuOptions{});
  NavState x;
  filter.Initialize(x, InitialUncertainty().SlamCovariance());
  const double before = filter.PoseCovariance().trace();
  for (int i = 0; i <= 200; ++i) {
    ImuSample s;
    s.t_ns = i * 5'000'000LL;
    s.accel_imu = Eigen::Vector3d(0, 0, 9.81);
    filter.AddImu(s);
  }
  DeskewedScan scan;
  scan.t_ns = 1'000'000'000;
  const EmptyMap map;
  const registration::PlaneMatcher matcher(map, registration::PlaneMatcherOptions{});
  const UpdateSummary summary = filter.Update(scan, matcher);
  EXPECT_FALSE(summary.applied);
  EXPECT_EQ(filter.state().t_ns, scan.t_ns);
  EXPECT_GT(filter.PoseCovariance().trace(), before);
  // At rest with the exact gravity the nominal state stays put.
  EXPECT_LT(filter.state().p_map_imu.norm(), 1e-9);
}

}  // namespace
}  // namespace hylo::estimation
