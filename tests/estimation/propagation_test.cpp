// IMU propagation of the filter (PredictAt and Update's covariance propagation share the same
// code) against the simulator's noise-free IMU and ground-truth trajectory.
#include <gtest/gtest.h>

#include "hylo/common/time.h"
#include "hylo/estimation/ieskf/ieskf.h"
#include "hylo/estimation/initial_uncertainty.h"
#include "hylo/sim/imu_model.h"
#include "hylo/sim/simulator.h"

namespace hylo::estimation {
namespace {

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
  class EmptyMap : public registration::NeighborSearch {
   public:
    void KNearest(const Eigen::Vector3f&, int, float,
                  std::vector<registration::Neighbor>* n) const override { n->clear(); }
    std::size_t Size() const override { return 0; }
  } map;
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
