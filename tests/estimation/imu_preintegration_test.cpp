// IMU preintegration (Forster et al. 2017): analytic Jacobians of the residual against
// central differences, the noise-free IMU of a known trajectory reproducing the relative
// motion, first-order bias correction, and the covariance against Monte Carlo.
#include <gtest/gtest.h>

#include <random>

#include "hylo/common/time.h"
#include "hylo/estimation/imu_preintegration.h"
#include "hylo/sim/imu_model.h"
#include "hylo/sim/simulator.h"

namespace hylo::estimation {
namespace {

constexpr int kDim = kImuFactorDim;

NavState RandomState(std::mt19937* rng, double scale) {
  std::normal_distribution<double> n(0.0, 1.0);
  const auto vec = [&](double s) -> Eigen::Vector3d {
    return Eigen::Vector3d(n(*rng), n(*rng), n(*rng)) * s;
  };
  NavState x;
  x.R_map_imu = lie::SO3d::Exp(vec(1.0));
  x.p_map_imu = vec(3.0 * scale);
  x.v_map_imu = vec(2.0 * scale);
  x.gyro_bias = vec(0.01);
  x.accel_bias = vec(0.1);
  return x;
}

ImuPreintegration RandomPreintegration(std::mt19937* rng, int samples) {
  std::normal_distribution<double> n(0.0, 1.0);
  ImuPreintegration pre(Eigen::Vector3d(0.003, -0.002, 0.001), Eigen::Vector3d(0.05, 0.02, -0.04),
                        ImuNoise{});
  for (int k = 0; k < samples; ++k) {
    ImuInterval in;
    in.dt_s = 0.005;
    in.gyro_imu = Eigen::Vector3d(n(*rng), n(*rng), n(*rng)) * 0.5;
    in.accel_imu = Eigen::Vector3d(n(*rng), n(*rng), 9.81 + n(*rng));
    pre.Integrate(in);
  }
  return pre;
}

StateVector Tangent(const Eigen::Matrix<double, kDim, 1>& d) {
  StateVector v = StateVector::Zero();
  v.head<kDim>() = d;
  return v;
}

// Central differences of the residual w.r.t. state i (which == 0) or j, perturbed by ⊞.
ImuJacobian NumericJacobian(const ImuPreintegration& pre, const NavState& xi, const NavState& xj,
                            const Eigen::Vector3d& g, int which) {
  const double h = 1e-6;
  ImuJacobian J;
  for (int c = 0; c < kDim; ++c) {
    Eigen::Matrix<double, kDim, 1> d = Eigen::Matrix<double, kDim, 1>::Zero();
    d(c) = h;
    const NavState ai = which == 0 ? BoxPlus(xi, Tangent(d)) : xi;
    const NavState aj = which == 1 ? BoxPlus(xj, Tangent(d)) : xj;
    const NavState bi = which == 0 ? BoxPlus(xi, Tangent(-d)) : xi;
    const NavState bj = which == 1 ? BoxPlus(xj, Tangent(-d)) : xj;
    J.col(c) = (pre.Evaluate(ai, aj, g, nullptr, nullptr) -
                pre.Evaluate(bi, bj, g, nullptr, nullptr)) / (2.0 * h);
  }
  return J;
}

TEST(ImuPreintegration, AnalyticJacobiansMatchCentralDifferences) {
  std::mt19937 rng(7);
  const Eigen::Vector3d g(0.0, 0.0, -9.81);
  for (int trial = 0; trial < 20; ++trial) {
    const ImuPreintegration pre = RandomPreintegration(&rng, 20 + trial);
    const NavState xi = RandomState(&rng, 1.0);
    // x_j near the prediction (small residual) in half the trials, arbitrary in the others.
    NavState xj = trial % 2 == 0 ? pre.Predict(xi, g) : RandomState(&rng, 1.0);
    xj.gyro_bias = xi.gyro_bias + Eigen::Vector3d(1e-3, -2e-3, 5e-4);
    ImuJacobian Ji, Jj;
    pre.Evaluate(xi, xj, g, &Ji, &Jj);
    const ImuJacobian Ni = NumericJacobian(pre, xi, xj, g, 0);
    const ImuJacobian Nj = NumericJacobian(pre, xi, xj, g, 1);
    EXPECT_LT((Ji - Ni).norm(), 1e-6 * std::max(1.0, Ni.norm())) << "trial " << trial << "\n"
                                                                   << Ji - Ni;
    EXPECT_LT((Jj - Nj).norm(), 1e-6 * std::max(1.0, Nj.norm())) << "trial " << trial;
    Eigen::Matrix<double, kDim, 3> Jg, Ng;
    pre.Evaluate(xi, xj, g, nullptr, nullptr, &Jg);
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d h = Eigen::Vector3d::Unit(c) * 1e-6;
      Ng.col(c) = (pre.Evaluate(xi, xj, g + h, nullptr, nullptr) -
                   pre.Evaluate(xi, xj, g - h, nullptr, nullptr)) / 2e-6;
    }
    EXPECT_LT((Jg - Ng).norm(), 1e-6 * std::max(1.0, Ng.norm())) << "trial " << trial;
  }
}

TEST(ImuPreintegration, NoiseFreeImuReproducesTheRelativeMotion) {
  sim::TerrainOptions terrain;
  terrain.resolution_m = 0.4;
  const sim::Site site = sim::BuildSite(21, terrain);
  sim::Rng rng(99);
  const sim::Trajectory traj = sim::Trajectory::FromRoute(
      site.route_a, *site.terrain, sim::TrajectoryOptions{}, SecondsToNanos(40.0), &rng);
  const double g = 9.81;
  const Eigen::Vector3d gravity(0.0, 0.0, -g);
  const int64_t dt_ns = 5'000'000;
  const auto truth = [&](int64_t t) {
    const sim::KinematicState s = traj.StateAt(t);
    NavState x;
    x.t_ns = t;
    x.R_map_imu = lie::SO3d::FromMatrix(s.R_map_imu);
    x.p_map_imu = s.position_map;
    x.v_map_imu = s.velocity_map;
    return x;
  };
  double moved = 0.0;
  for (const double span_s : {0.1, 1.0}) {
    for (int64_t t0 = SecondsToNanos(3.0); t0 < SecondsToNanos(30.0); t0 += SecondsToNanos(3.0)) {
      const int64_t t1 = t0 + SecondsToNanos(span_s);
      std::vector<ImuSample> samples;
      for (int64_t t = t0; t <= t1; t += dt_ns) {
        samples.push_back(sim::TrueImuSample(traj.StateAt(t), g, t));
      }
      ImuPreintegration pre(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), ImuNoise{});
      for (const ImuInterval& in : MakeIntervals(samples, t0, t1)) pre.Integrate(in);
      const NavState xi = truth(t0), xj = truth(t1);
      const NavState pred = pre.Predict(xi, gravity);
      moved = std::max(moved, (xj.p_map_imu - xi.p_map_imu).norm());
      // Trapezoidal samples at 200 Hz: errors grow with the span (cf. propagation_test).
      const double tol_p = span_s < 0.5 ? 2e-4 : 5e-3;
      EXPECT_LT((pred.p_map_imu - xj.p_map_imu).norm(), tol_p) << "t0 " << t0;
      EXPECT_LT((pred.v_map_imu - xj.v_map_imu).norm(), 10 * tol_p) << "t0 " << t0;
      EXPECT_LT(lie::Minus(pred.R_map_imu, xj.R_map_imu).norm(), 2e-4 * span_s * 10) << "t0 " << t0;
      const ImuResidual r = pre.Evaluate(xi, xj, gravity, nullptr, nullptr);
      EXPECT_LT(r.head<3>().norm(), 2e-3) << "t0 " << t0;
    }
  }
  EXPECT_GT(moved, 0.5);  // the vehicle moves over one second
}

TEST(ImuPreintegration, FirstOrderBiasCorrectionMatchesReintegration) {
  std::mt19937 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<ImuInterval> intervals;
  for (int k = 0; k < 40; ++k) {
    ImuInterval in;
    in.dt_s = 0.005;
    in.gyro_imu = Eigen::Vector3d(n(rng), n(rng), n(rng)) * 0.5;
    in.accel_imu = Eigen::Vector3d(n(rng), n(rng), 9.81 + n(rng));
    intervals.push_back(in);
  }
  const Eigen::Vector3d bg0(0.001, 0.002, -0.001), ba0(0.02, -0.01, 0.03);
  const Eigen::Vector3d dbg(0.004, -0.003, 0.002), dba(0.05, 0.04, -0.06);
  ImuPreintegration at_old(bg0, ba0, ImuNoise{}), at_new(bg0 + dbg, ba0 + dba, ImuNoise{});
  for (const ImuInterval& in : intervals) {
    at_old.Integrate(in);
    at_new.Integrate(in);
  }
  NavState xi;
  xi.gyro_bias = bg0 + dbg;
  xi.accel_bias = ba0 + dba;
  const Eigen::Vector3d g(0, 0, -9.81);
  const NavState corrected = at_old.Predict(xi, g);
  const NavState exact = at_new.Predict(xi, g);
  NavState uncorrected_input = xi;
  uncorrected_input.gyro_bias = bg0;
  uncorrected_input.accel_bias = ba0;
  const NavState uncorrected = at_old.Predict(uncorrected_input, g);
  const double err_corrected = (corrected.p_map_imu - exact.p_map_imu).norm() +
                               (corrected.v_map_imu - exact.v_map_imu).norm() +
                               lie::Minus(corrected.R_map_imu, exact.R_map_imu).norm();
  const double err_uncorrected = (uncorrected.p_map_imu - exact.p_map_imu).norm() +
                                 (uncorrected.v_map_imu - exact.v_map_imu).norm() +
                                 lie::Minus(uncorrected.R_map_imu, exact.R_map_imu).norm();
  std::printf("bias change: error %.3e with first-order correction, %.3e without\n",
              err_corrected, err_uncorrected);
  EXPECT_LT(err_corrected, 1e-5);
  EXPECT_LT(err_corrected, 0.01 * err_uncorrected);
}

TEST(ImuPreintegration, CovarianceMatchesMonteCarlo) {
  // Noise densities large enough that the spread dominates rounding; 200 Hz, 0.5 s.
  ImuNoise noise;
  noise.gyro_noise_density = 0.01;
  noise.accel_noise_density = 0.1;
  const double dt = 0.005;
  const int steps = 100, runs = 2000;
  std::mt19937 rng(11);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<ImuInterval> clean(steps);
  for (int k = 0; k < steps; ++k) {
    clean[k].dt_s = dt;
    clean[k].gyro_imu = Eigen::Vector3d(0.3, -0.2, 0.5);
    clean[k].accel_imu = Eigen::Vector3d(1.0, 0.5, 9.81);
  }
  ImuPreintegration nominal(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), noise);
  for (const ImuInterval& in : clean) nominal.Integrate(in);
  Eigen::Matrix<double, 9, 9> sample = Eigen::Matrix<double, 9, 9>::Zero();
  for (int run = 0; run < runs; ++run) {
    ImuPreintegration noisy(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), noise);
    for (ImuInterval in : clean) {
      // A density σ sampled over dt has the per-sample σ/√dt.
      in.gyro_imu +=
          Eigen::Vector3d(n(rng), n(rng), n(rng)) * noise.gyro_noise_density / std::sqrt(dt);
      in.accel_imu +=
          Eigen::Vector3d(n(rng), n(rng), n(rng)) * noise.accel_noise_density / std::sqrt(dt);
      noisy.Integrate(in);
    }
    Eigen::Matrix<double, 9, 1> e;
    e << lie::Minus(noisy.delta_R(), nominal.delta_R()), noisy.delta_p() - nominal.delta_p(),
        noisy.delta_v() - nominal.delta_v();
    sample += e * e.transpose() / runs;
  }
  const Eigen::Matrix<double, 9, 9>& predicted = nominal.covariance();
  for (int i = 0; i < 9; ++i) {
    EXPECT_NEAR(sample(i, i) / predicted(i, i), 1.0, 0.15) << "diagonal " << i;
  }
  // Off-diagonal structure (θ-v and p-v couplings) within 15 % of the whole matrix's norm.
  EXPECT_LT((sample - predicted).norm(), 0.15 * predicted.norm());
}

}  // namespace
}  // namespace hylo::estimation
