#include "hylo/estimation/imu_propagation.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "hylo/common/check.h"
#include "hylo/common/time.h"

namespace hylo::estimation {

using namespace state_index;  // NOLINT: index names only
using lie::SO3d;

NavState PropagateNominal(const NavState& x, const ImuInterval& in) {
  const double dt = in.dt_s;
  const Eigen::Vector3d omega = in.gyro_imu - x.gyro_bias;
  const Eigen::Vector3d accel_map = x.R_map_imu * (in.accel_imu - x.accel_bias) + x.gravity_map;
  NavState y = x;
  y.t_ns = x.t_ns + SecondsToNanos(dt);
  y.R_map_imu = x.R_map_imu * SO3d::Exp(omega * dt);
  y.p_map_imu = x.p_map_imu + x.v_map_imu * dt + 0.5 * accel_map * dt * dt;
  y.v_map_imu = x.v_map_imu + accel_map * dt;
  return y;
}

StateCovariance PropagationJacobian(const NavState& x, const ImuInterval& in) {
  const double dt = in.dt_s;
  const Eigen::Vector3d omega_dt = (in.gyro_imu - x.gyro_bias) * dt;
  const Eigen::Vector3d accel = in.accel_imu - x.accel_bias;
  const Eigen::Matrix3d R = x.R_map_imu.Matrix();
  const Eigen::Matrix3d R_a_hat = R * SO3d::Hat(accel);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  StateCovariance F = StateCovariance::Identity();
  // R·Exp(δθ)·Exp(ω dt) = R·Exp(ω dt)·Exp(Exp(−ω dt) δθ); bias: Exp((ω − δb) dt) ≈
  // Exp(ω dt)·Exp(−Jr(ω dt) δb dt) (Barfoot Eq. 7.33 with the right Jacobian).
  F.block<3, 3>(kRotation, kRotation) = SO3d::Exp(-omega_dt).Matrix();
  F.block<3, 3>(kRotation, kGyroBias) = -SO3d::RightJacobian(omega_dt) * dt;
  // R·Exp(δθ)·a ≈ R a − R [a]^ δθ.
  F.block<3, 3>(kVelocity, kRotation) = -R_a_hat * dt;
  F.block<3, 3>(kVelocity, kAccelBias) = -R * dt;
  F.block<3, 3>(kVelocity, kGravity) = I * dt;
  F.block<3, 3>(kPosition, kVelocity) = I * dt;
  F.block<3, 3>(kPosition, kRotation) = -0.5 * R_a_hat * dt * dt;
  F.block<3, 3>(kPosition, kAccelBias) = -0.5 * R * dt * dt;
  F.block<3, 3>(kPosition, kGravity) = 0.5 * I * dt * dt;
  return F;
}

StateCovariance PropagateCovariance(const StateCovariance& F, const StateCovariance& P) {
  constexpr int kBlocks = kDim / 3;
  enum class Block : uint8_t { kZero, kIdentity, kGeneral };
  Block kind[kBlocks][kBlocks];
  for (int i = 0; i < kBlocks; ++i) {
    for (int j = 0; j < kBlocks; ++j) {
      const auto f = F.block<3, 3>(3 * i, 3 * j);
      kind[i][j] = (f.array() == 0.0).all()                        ? Block::kZero
                   : (f - Eigen::Matrix3d::Identity()).isZero(0.0) ? Block::kIdentity
                                                                   : Block::kGeneral;
    }
  }
  StateCovariance FP = StateCovariance::Zero();
  for (int i = 0; i < kBlocks; ++i) {
    for (int k = 0; k < kBlocks; ++k) {
      if (kind[i][k] == Block::kIdentity) {
        FP.middleRows<3>(3 * i) += P.middleRows<3>(3 * k);
      } else if (kind[i][k] == Block::kGeneral) {
        FP.middleRows<3>(3 * i).noalias() += F.block<3, 3>(3 * i, 3 * k) * P.middleRows<3>(3 * k);
      }
    }
  }
  StateCovariance FPFt = StateCovariance::Zero();
  for (int j = 0; j < kBlocks; ++j) {
    for (int k = 0; k < kBlocks; ++k) {
      if (kind[j][k] == Block::kIdentity) {
        FPFt.middleCols<3>(3 * j) += FP.middleCols<3>(3 * k);
      } else if (kind[j][k] == Block::kGeneral) {
        FPFt.middleCols<3>(3 * j).noalias() +=
            FP.middleCols<3>(3 * k) * F.block<3, 3>(3 * j, 3 * k).transpose();
      }
    }
  }
  return FPFt;
}

StateCovariance PropagationNoise(const ImuNoise& noise, const ImuInterval& in) {
  // A continuous density σ_c gives a per-sample variance σ_c²/dt, integrated over dt:
  // σ_c² dt on the propagated quantity (the Jr factor on the rotation is ≈ I at IMU rates).
  const double dt = in.dt_s;
  StateCovariance Q = StateCovariance::Zero();
  const auto set = [&](int index, double density) {
    Q.block<3, 3>(index, index).diagonal().setConstant(density * density * dt);
  };
  set(kRotation, noise.gyro_noise_density);
  set(kVelocity, noise.accel_noise_density);
  set(kGyroBias, noise.gyro_bias_random_walk);
  set(kAccelBias, noise.accel_bias_random_walk);
  // Inside an IMU gap: an unknown constant error δω, δa over dt (imu_propagation.h), whose
  // position and velocity parts are correlated through δp = ½ δa dt², δv = δa dt.
  const double sg2 = in.gap_gyro_sigma_radps * in.gap_gyro_sigma_radps;
  const double sa2 = in.gap_accel_sigma_mps2 * in.gap_accel_sigma_mps2;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  Q.block<3, 3>(kRotation, kRotation) += sg2 * dt * dt * I;
  Q.block<3, 3>(kVelocity, kVelocity) += sa2 * dt * dt * I;
  Q.block<3, 3>(kPosition, kPosition) += 0.25 * sa2 * dt * dt * dt * dt * I;
  Q.block<3, 3>(kPosition, kVelocity) += 0.5 * sa2 * dt * dt * dt * I;
  Q.block<3, 3>(kVelocity, kPosition) += 0.5 * sa2 * dt * dt * dt * I;
  return Q;
}

ImuSample InterpolateImu(const std::vector<ImuSample>& samples, int64_t t_ns) {
  HYLO_CHECK(!samples.empty(), "no IMU samples");
  const auto later = std::lower_bound(
      samples.begin(), samples.end(), t_ns,
      [](const ImuSample& s, int64_t t) { return s.t_ns < t; });
  if (later == samples.begin()) return samples.front();
  if (later == samples.end()) return samples.back();
  const ImuSample& a = *(later - 1);
  const ImuSample& b = *later;
  const double w = static_cast<double>(t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
  ImuSample out;
  out.t_ns = t_ns;
  out.accel_imu = (1.0 - w) * a.accel_imu + w * b.accel_imu;
  out.gyro_imu = (1.0 - w) * a.gyro_imu + w * b.gyro_imu;
  return out;
}

namespace {

/// The last sample's stamp before [a_ns, b_ns] when the interval lies between samples farther
/// apart than `gap_ns` (or that far past the last sample); nullopt outside a gap.
std::optional<int64_t> GapStart(const std::vector<ImuSample>& samples, int64_t a_ns, int64_t b_ns,
                                int64_t gap_ns) {
  const auto after = std::lower_bound(
      samples.begin(), samples.end(), b_ns,
      [](const ImuSample& s, int64_t t) { return s.t_ns < t; });  // first at or after b
  const auto before =
      std::upper_bound(samples.begin(), samples.end(), a_ns,
                       [](int64_t t, const ImuSample& s) { return t < s.t_ns; });  // first after a
  const int64_t lo = before == samples.begin() ? a_ns : (before - 1)->t_ns;
  const int64_t hi = after == samples.end() ? b_ns : after->t_ns;
  if (hi - lo <= gap_ns) return std::nullopt;
  return lo;
}

}  // namespace

std::vector<ImuInterval> MakeIntervals(const std::vector<ImuSample>& samples, int64_t t0_ns,
                                       int64_t t1_ns, const ImuGapModel* gap) {
  std::vector<ImuInterval> intervals;
  if (samples.empty() || t1_ns <= t0_ns) return intervals;
  std::vector<int64_t> knots{t0_ns};
  for (const ImuSample& s : samples) {
    if (s.t_ns > t0_ns && s.t_ns < t1_ns) knots.push_back(s.t_ns);
  }
  knots.push_back(t1_ns);
  const auto measure = [&](int64_t t) {
    if (gap == nullptr || t <= samples.back().t_ns) return InterpolateImu(samples, t);
    ImuSample mean;
    mean.t_ns = t;
    mean.accel_imu = gap->accel_mean_imu;
    mean.gyro_imu = gap->gyro_mean_imu;
    return mean;
  };
  ImuSample prev = measure(knots.front());
  for (std::size_t i = 1; i < knots.size(); ++i) {
    const ImuSample cur = measure(knots[i]);
    ImuInterval in;
    in.dt_s = NanosToSeconds(knots[i] - knots[i - 1]);
    in.gyro_imu = 0.5 * (prev.gyro_imu + cur.gyro_imu);
    in.accel_imu = 0.5 * (prev.accel_imu + cur.accel_imu);
    const std::optional<int64_t> gap_start =
        gap != nullptr ? GapStart(samples, knots[i - 1], knots[i], gap->gap_ns) : std::nullopt;
    if (gap_start) {
      // The error is one constant over the whole gap: its effect on the velocity (and
      // rotation) grows with the time e already spent in the gap, as σ (e + dt) in all, so this
      // interval adds σ² ((e + dt)² − e²) = σ² dt² (1 + 2 e / dt).
      const double elapsed_s = NanosToSeconds(knots[i - 1] - *gap_start);
      const double growth = std::sqrt(1.0 + 2.0 * elapsed_s / in.dt_s);
      in.gap_accel_sigma_mps2 = growth * gap->accel_sigma_mps2;
      in.gap_gyro_sigma_radps = growth * gap->gyro_sigma_radps;
    }
    intervals.push_back(in);
    prev = cur;
  }
  return intervals;
}

NavState PredictNominal(const NavState& x0, const std::vector<ImuSample>& imu, bool use_imu,
                        const Eigen::Vector3d& omega_cv_imu, int64_t t_ns, const ImuGapModel* gap) {
  NavState x = x0;
  if (t_ns <= x0.t_ns) return x;
  if (!use_imu) {
    const double dt = NanosToSeconds(t_ns - x0.t_ns);
    x.R_map_imu = x.R_map_imu * lie::SO3d::Exp(omega_cv_imu * dt);
    x.p_map_imu += x.v_map_imu * dt;
  } else if (!imu.empty()) {
    for (const ImuInterval& in : MakeIntervals(imu, x0.t_ns, t_ns, gap)) {
      x = PropagateNominal(x, in);
    }
  }
  x.t_ns = t_ns;
  return x;
}

std::vector<NavState> PredictNominalAlong(const NavState& x0, const std::vector<ImuSample>& imu,
                                          bool use_imu, const Eigen::Vector3d& omega_cv_imu,
                                          const std::vector<int64_t>& times_ns,
                                          const ImuGapModel* gap) {
  std::vector<NavState> states;
  states.reserve(times_ns.size());
  NavState at_sample = x0;  // carried to the last sample stamp passed so far
  auto next = std::upper_bound(imu.begin(), imu.end(), x0.t_ns,
                               [](int64_t t, const ImuSample& s) { return t < s.t_ns; });
  for (int64_t t : times_ns) {
    if (use_imu) {
      // The last sample strictly before t: PredictNominal to t splits there too.
      auto last = next;
      while (last != imu.end() && last->t_ns < t) ++last;
      if (last != next) {
        at_sample = PredictNominal(at_sample, imu, use_imu, omega_cv_imu, (last - 1)->t_ns, gap);
        next = last;
      }
      states.push_back(PredictNominal(at_sample, imu, use_imu, omega_cv_imu, t, gap));
    } else {
      states.push_back(PredictNominal(x0, imu, use_imu, omega_cv_imu, t, gap));
    }
  }
  return states;
}

}  // namespace hylo::estimation
