// Undistortion against a motion known in closed form: a lidar spinning about a fixed axis at a
// constant rate, whose pose at every point's time is exact. With IMU knots 5 ms apart the
// interpolation between knots is the fast one (normalised lerp), with no knot inside the
// scan it is slerp; both must move every return to where it is at the scan end.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "hylo/estimation/undistortion.h"

namespace hylo::estimation {
namespace {

// Only PredictAt matters to Undistort: the IMU frame turns about `axis` at `rate_radps` and
// its origin moves at `velocity_mps`; the lidar sits at `T_imu_lidar`.
class ConstantTwistEstimator final : public Estimator {
 public:
  ConstantTwistEstimator(const Eigen::Vector3d& axis, double rate_radps,
                         const Eigen::Vector3d& velocity_mps, const lie::SE3d& T_imu_lidar)
      : axis_(axis.normalized()), rate_(rate_radps), velocity_(velocity_mps) {
    state_.T_imu_lidar = T_imu_lidar;
  }
  void Initialize(const NavState&, const StateCovariance&) override {}
  void AddImu(const ImuSample&) override {}
  void SetScansExtendMap(bool) override {}
  NavState PredictAt(int64_t t_ns) const override {
    NavState x = state_;
    const double t = t_ns * 1e-9;
    x.t_ns = t_ns;
    x.R_map_imu = lie::SO3d::Exp(axis_ * rate_ * t);
    x.p_map_imu = velocity_ * t;
    return x;
  }
  UpdateSummary Update(const DeskewedScan&, const registration::PlaneMatcher&) override {
    return {};
  }
  bool initialized() const override { return true; }
  const NavState& state() const override { return state_; }
  StateCovariance Covariance() const override { return StateCovariance::Identity(); }
  void TakeFinalized(std::vector<NavState>*) override {}
  void Finish() override {}

 private:
  Eigen::Vector3d axis_;
  double rate_;
  Eigen::Vector3d velocity_;
  NavState state_;
};

constexpr int64_t kScanStartNs = 1'000'000'000;
constexpr int64_t kScanNs = 100'000'000;

// Returns on a 50 m sphere around the lidar, spread over the sweep in time.
LidarScan Sweep(int count) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  LidarScan scan;
  scan.t_ns = kScanStartNs;
  scan.end_t_ns = kScanStartNs + kScanNs;
  for (int i = 0; i < count; ++i) {
    ScanPoint p;
    p.position_lidar = (50.0 * Eigen::Vector3d(u(rng), u(rng), 0.3 * u(rng)).normalized()).cast<float>();
    p.offset_ns = static_cast<int32_t>(static_cast<int64_t>(i) * kScanNs / count);
    scan.points.push_back(p);
  }
  return scan;
}

// Largest distance between Undistort's output and the exact end-frame position, m.
double WorstError(const ConstantTwistEstimator& estimator, const LidarScan& scan,
                  const std::vector<int64_t>& knots) {
  const PointCloud out = Undistort(scan, estimator, knots);
  EXPECT_EQ(out.size(), scan.points.size());
  const lie::SE3d T_end_map = estimator.PredictAt(scan.end_t_ns).T_map_lidar().Inverse();
  double worst = 0.0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const lie::SE3d T_map_lidar_t =
        estimator.PredictAt(scan.t_ns + scan.points[i].offset_ns).T_map_lidar();
    const Eigen::Vector3d exact =
        T_end_map * (T_map_lidar_t * scan.points[i].position_lidar.cast<double>());
    worst = std::max(worst, (out[i].cast<double>() - exact).norm());
  }
  return worst;
}

std::vector<int64_t> ImuKnots(double rate_hz) {
  std::vector<int64_t> knots;
  const auto step = static_cast<int64_t>(1e9 / rate_hz);
  for (int64_t t = kScanStartNs - step; t <= kScanStartNs + kScanNs + step; t += step) {
    knots.push_back(t);
  }
  return knots;
}

TEST(Undistort, PureRotationIsExactWithDenseKnotsAndWithoutKnots) {
  // 3 rad/s about a tilted axis: 0.015 rad between 200 Hz knots, 0.3 rad over the sweep.
  const ConstantTwistEstimator spin(Eigen::Vector3d(0.2, -0.1, 1.0), 3.0, Eigen::Vector3d::Zero(),
                                    lie::SE3d());
  const LidarScan scan = Sweep(2000);
  // Float output at 50 m rounds to ~4 um; the interpolation adds < 0.05 mm at most.
  EXPECT_LT(WorstError(spin, scan, ImuKnots(200.0)), 5e-5);
  EXPECT_LT(WorstError(spin, scan, {}), 5e-5);  // slerp over the whole sweep
}

TEST(Undistort, RotationWithTranslationFollowsTheKnots) {
  // The lidar 0.3 m off the IMU and the IMU moving at 2 m/s: seen from the turning end frame,
  // the path between knots is an arc that linear interpolation cuts, by about
  // (v + ω·r)·dt·ω·dt / 8 = 2.9 · 0.005 · 0.015 / 8 ≈ 0.03 mm at 200 Hz.
  const lie::SE3d T_imu_lidar(lie::SO3d::Exp(Eigen::Vector3d(0.02, -0.03, 0.5)),
                              Eigen::Vector3d(0.1, 0.0, 0.3));
  const ConstantTwistEstimator moving(Eigen::Vector3d::UnitZ(), 3.0, Eigen::Vector3d(2.0, 0.5, 0.0),
                                      T_imu_lidar);
  const LidarScan scan = Sweep(2000);
  EXPECT_LT(WorstError(moving, scan, ImuKnots(200.0)), 5e-5);
  // Without the knots the same motion is only roughly followed: the knots matter.
  EXPECT_GT(WorstError(moving, scan, {}), 1e-3);
}

}  // namespace
}  // namespace hylo::estimation
