// Marginalisation keeps the information of the states that leave the window: on a short
// sequence (3 s, 30 scans, noisy IMU, a few noisy point-to-plane matches per scan in a box
// room) the newest state of a 5-scan window with marginalisation must agree with the full
// batch solution of all states (a window longer than the sequence), and be closer to it than
// the same window that simply drops its oldest state. Distances are Mahalanobis distances in
// the batch's own marginal covariance of the newest state.
#include <gtest/gtest.h>

#include <random>

#include "hylo/common/time.h"
#include "hylo/estimation/initial_uncertainty.h"
#include "hylo/estimation/sliding_window/sliding_window.h"
#include "hylo/sim/imu_model.h"
#include "hylo/sim/simulator.h"

namespace hylo::estimation {
namespace {

// Exact nearest neighbours over a fixed cloud (the room), by brute force.
class BruteForceMap : public registration::NeighborSearch {
 public:
  explicit BruteForceMap(std::vector<Eigen::Vector3f> points) : points_(std::move(points)) {}
  void KNearest(const Eigen::Vector3f& q, int k, float max_distance,
                std::vector<registration::Neighbor>* out) const override {
    out->clear();
    for (const Eigen::Vector3f& p : points_) {
      const float d2 = (p - q).squaredNorm();
      if (d2 <= max_distance * max_distance) out->push_back({p, d2});
    }
    std::sort(out->begin(), out->end(),
              [](const auto& a, const auto& b) { return a.squared_distance < b.squared_distance; });
    if (static_cast<int>(out->size()) > k) out->resize(k);
  }
  std::size_t Size() const override { return points_.size(); }

 private:
  std::vector<Eigen::Vector3f> points_;
};

// A 24 × 24 × 6 m box around `center` (floor 2 m below it), sampled every 0.3 m.
std::vector<Eigen::Vector3f> Room(const Eigen::Vector3d& center) {
  std::vector<Eigen::Vector3f> points;
  const double h = 0.3, half = 12.0, low = -2.0, high = 4.0;
  for (double a = -half; a <= half; a += h) {
    for (double b = -half; b <= half; b += h) {
      points.push_back((center + Eigen::Vector3d(a, b, low)).cast<float>());
      points.push_back((center + Eigen::Vector3d(a, b, high)).cast<float>());
    }
    for (double z = low; z <= high; z += h) {
      for (const double s : {-half, half}) {
        points.push_back((center + Eigen::Vector3d(s, a, z)).cast<float>());
        points.push_back((center + Eigen::Vector3d(a, s, z)).cast<float>());
      }
    }
  }
  return points;
}

struct Sequence {
  NavState start;
  std::vector<ImuSample> imu;
  std::vector<DeskewedScan> scans;
  std::vector<Eigen::Isometry3d> T_map_imu_truth;  ///< per scan
  Eigen::Vector3d center;
};

Sequence MakeSequence(int points_per_scan) {
  sim::TerrainOptions terrain;
  terrain.resolution_m = 0.4;
  const sim::Site site = sim::BuildSite(21, terrain);
  sim::Rng route_rng(99);
  const sim::Trajectory traj = sim::Trajectory::FromRoute(
      site.route_a, *site.terrain, sim::TrajectoryOptions{}, SecondsToNanos(20.0), &route_rng);
  std::mt19937 rng(17);
  std::normal_distribution<double> n(0.0, 1.0);
  const auto noise = [&](double s) -> Eigen::Vector3d {
    return Eigen::Vector3d(n(rng), n(rng), n(rng)) * s;
  };
  const int64_t t0 = SecondsToNanos(5.0), dt_imu = 5'000'000, dt_scan = 100'000'000;
  Sequence seq;
  const sim::KinematicState s0 = traj.StateAt(t0);
  seq.center = s0.position_map;
  seq.start.t_ns = t0;
  seq.start.R_map_imu = lie::SO3d::FromMatrix(s0.R_map_imu);
  seq.start.p_map_imu = s0.position_map;
  seq.start.v_map_imu = s0.velocity_map;
  // Biases the estimator must find: constant, with white noise of 10× the default density.
  const Eigen::Vector3d bg(0.004, -0.003, 0.002), ba(0.08, -0.05, 0.06);
  for (int64_t t = t0; t <= t0 + 31 * dt_scan; t += dt_imu) {
    ImuSample s = sim::TrueImuSample(traj.StateAt(t), 9.81, t);
    s.gyro_imu += bg + noise(10 * 6.1e-5 / std::sqrt(0.005));
    s.accel_imu += ba + noise(10 * 1.4e-3 / std::sqrt(0.005));
    seq.imu.push_back(s);
  }
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::vector<Eigen::Vector3f> room = Room(seq.center);
  for (int k = 1; k <= 30; ++k) {
    DeskewedScan scan;
    scan.t_ns = t0 + k * dt_scan;
    seq.T_map_imu_truth.push_back(traj.PoseAt(scan.t_ns));
    const Eigen::Isometry3d T_imu_map = seq.T_map_imu_truth.back().inverse();
    for (int i = 0; i < points_per_scan; ++i) {
      const Eigen::Vector3d p_map = room[static_cast<std::size_t>((u(rng) + 1.0) * 0.5 *
                                                                   (room.size() - 1))]
                                        .cast<double>();
      scan.points_lidar.push_back((T_imu_map * p_map + noise(0.02)).cast<float>());
    }
    seq.scans.push_back(scan);
  }
  return seq;
}

struct Result {
  NavState newest;
  StateCovariance covariance;
};

Result RunSmoother(const Sequence& seq, int window_size, bool marginalize, bool use_imu = true,
                   double* max_position_error_m = nullptr) {
  EstimatorOptions options;
  ImuOptions imu;
  imu.enabled = use_imu;
  options.backend = Estimator::Backend::kSlidingWindow;
  imu.noise.gyro_noise_density = 10 * 6.1e-5;
  imu.noise.accel_noise_density = 10 * 1.4e-3;
  options.sliding_window.window_size = window_size;
  options.sliding_window.marginalize = marginalize;
  options.lidar_update.min_matches = 10;
  options.sliding_window.max_iterations = 20;
  options.sliding_window.max_solver_time_s = 10.0;
  SlidingWindow smoother(options, imu);
  const BruteForceMap map(Room(seq.center));
  const registration::PlaneMatcher matcher(map, registration::PlaneMatcherOptions{});
  InitialUncertainty init;
  init.velocity_sigma_mps = 0.1;
  smoother.Initialize(seq.start, init.SlamCovariance());
  std::size_t next_imu = 0;
  double max_error = 0.0;
  for (std::size_t k = 0; k < seq.scans.size(); ++k) {
    const DeskewedScan& scan = seq.scans[k];
    while (next_imu < seq.imu.size() && seq.imu[next_imu].t_ns <= scan.t_ns + 5'000'000) {
      smoother.AddImu(seq.imu[next_imu++]);
    }
    const UpdateSummary summary = smoother.Update(scan, matcher);
    EXPECT_TRUE(summary.applied) << summary.message;
    max_error = std::max(max_error, (smoother.state().p_map_imu -
                                     seq.T_map_imu_truth[k].translation()).norm());
  }
  if (max_position_error_m != nullptr) *max_position_error_m = max_error;
  return {smoother.state(), smoother.Covariance()};
}

double Mahalanobis(const NavState& x, const Result& batch) {
  const StateVector d = BoxMinus(x, batch.newest);
  const Eigen::Matrix<double, 15, 15> P = batch.covariance.topLeftCorner<15, 15>();
  const Eigen::Matrix<double, 15, 1> e = d.head<15>();
  return std::sqrt(e.dot(P.ldlt().solve(e)));
}

TEST(SlidingWindowMarginalization, AgreesWithTheFullBatchBetterThanDropping) {
  const Sequence seq = MakeSequence(40);  // few, noisy points: the past's information matters
  const Result batch = RunSmoother(seq, 100, true);  // every state stays: the full batch solution
  const Result marginalized = RunSmoother(seq, 5, true);
  const Result dropped = RunSmoother(seq, 5, false);
  const double d_marg = Mahalanobis(marginalized.newest, batch);
  const double d_drop = Mahalanobis(dropped.newest, batch);
  const auto print = [&](const char* name, const NavState& x) {
    std::printf("%-13s |dp| %.4f m |dv| %.4f m/s |dbg| %.5f rad/s |dba| %.4f m/s2\n", name,
                (x.p_map_imu - batch.newest.p_map_imu).norm(),
                (x.v_map_imu - batch.newest.v_map_imu).norm(),
                (x.gyro_bias - batch.newest.gyro_bias).norm(),
                (x.accel_bias - batch.newest.accel_bias).norm());
  };
  print("marginalised", marginalized.newest);
  print("dropped", dropped.newest);
  std::printf("Mahalanobis distance to the batch (its covariance): marginalised %.2e, dropped "
              "%.2e\n", d_marg, d_drop);
  // Within one standard deviation of the batch's own uncertainty (the window relinearises
  // less than the batch, so it is not exact), and clearly closer than forgetting.
  EXPECT_LT(d_marg, 1.0);
  EXPECT_LT(d_marg, 0.5 * d_drop);
  // The covariance keeps the information too: the marginalised window's newest position
  // uncertainty is within 30 % of the batch's.
  const double batch_sigma = std::sqrt(batch.covariance.block<3, 3>(3, 3).trace());
  const double marg_sigma = std::sqrt(marginalized.covariance.block<3, 3>(3, 3).trace());
  EXPECT_NEAR(marg_sigma / batch_sigma, 1.0, 0.3);
}

TEST(SlidingWindowNoImu, ConstantVelocityWindowTracksTheTrajectory) {
  // Without an IMU (constant-velocity factors, nothing deskewed) from scans alone: every
  // newest pose within 3 cm of the truth along 3 s of the simulated vehicle's motion.
  const Sequence seq = MakeSequence(300);
  double max_error_m = 0.0;
  RunSmoother(seq, 10, true, false, &max_error_m);
  const double travelled = (seq.T_map_imu_truth.back().translation() -
                            seq.T_map_imu_truth.front().translation()).norm();
  std::printf("no IMU: %.2f m travelled, max position error %.4f m\n", travelled, max_error_m);
  EXPECT_GT(travelled, 1.0);
  EXPECT_LT(max_error_m, 0.03);
}

}  // namespace
}  // namespace hylo::estimation
