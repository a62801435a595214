// IESKF iterated update (FAST-LIO2 Sec. IV-D). Each iteration j linearises the point-to-plane
// residuals r at x_j and minimises ‖x_j ⊞ δ ⊟ x̂‖²_P⁻¹ + ‖r + H δ‖²_R⁻¹ over δ:
//   (Jᵀ P⁻¹ J + Hᵀ R⁻¹ H) δ = −(Jᵀ P⁻¹ (x_j ⊟ x̂) + Hᵀ R⁻¹ r)
// with J = ∂(x_j ⊞ δ ⊟ x̂)/∂δ (Jr⁻¹ on the rotation blocks). This is the paper's Eq. (18)-(20)
// (gain in the state dimension, cost independent of the number of points) written as the
// normal equations; the posterior covariance is their inverse, i.e. (I − K H) P_j.
#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "hylo/estimation/ieskf/ieskf.h"
#include "hylo/estimation/lidar_update.h"
#include "hylo/registration/parallel.h"
#include "hylo/registration/point_to_plane.h"

namespace hylo::estimation {

using namespace state_index;  // NOLINT: index names only
using lie::SO3d;
using registration::Plane;

namespace {

// A state's pose and extrinsic as matrices, built once per linearisation, not per point.
struct PosesAsMatrices {
  explicit PosesAsMatrices(const NavState& x)
      : R_map_imu(x.R_map_imu.Matrix()),
        p_map_imu(x.p_map_imu),
        R_imu_lidar(x.T_imu_lidar.so3().Matrix()),
        t_imu_lidar(x.T_imu_lidar.translation()) {}
  Eigen::Matrix3d R_map_imu;
  Eigen::Vector3d p_map_imu;
  Eigen::Matrix3d R_imu_lidar;
  Eigen::Vector3d t_imu_lidar;
};

double Residual(const PosesAsMatrices& x, const Eigen::Vector3d& point_lidar, const Plane& plane,
                ResidualJacobian* jacobian) {
  const Eigen::Vector3d point_imu = x.R_imu_lidar * point_lidar + x.t_imu_lidar;
  const double r = plane.Distance(x.R_map_imu * point_imu + x.p_map_imu);
  if (jacobian != nullptr) {
    // The pose blocks are the point-to-plane factor's (registration/point_to_plane.h); the
    // extrinsic's are the same factor one frame further in: p_imu = R_il p_lidar + t_il, so
    // ∂r/∂δθ_il = (p_lidar × R_ilᵀ n_imu)ᵀ and ∂r/∂δt_il = n_imuᵀ.
    const Plane plane_imu{x.R_map_imu.transpose() * plane.normal, 0.0};
    jacobian->block<1, 6>(0, 0) =
        registration::PointToPlaneJacobian(x.R_map_imu, point_imu, plane).transpose();
    jacobian->block<1, 6>(0, 6) =
        registration::PointToPlaneJacobian(x.R_imu_lidar, point_lidar, plane_imu).transpose();
  }
  return r;
}

}  // namespace

double PointToPlaneResidual(const NavState& x, const Eigen::Vector3d& point_lidar,
                            const Plane& plane, ResidualJacobian* jacobian) {
  return Residual(PosesAsMatrices(x), point_lidar, plane, jacobian);
}

int Ieskf::ActiveDim() const {
  return options_.ieskf.online_extrinsic && !calibration_held_ ? kDim : kDimNoExtrinsic;
}

void Ieskf::Associate(const NavState& x, const DeskewedScan& scan,
                      const registration::PlaneMatcher& planes) {
  const std::size_t n = scan.points_lidar.size();
  planes_.resize(n);
  matched_.assign(n, 0);
  const lie::SE3d T_map_lidar = x.T_map_lidar();
  registration::ParallelFor(n, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const Eigen::Vector3d p_map = T_map_lidar * scan.points_lidar[i].cast<double>();
      matched_[i] = planes.Match(p_map, &planes_[i]) ? 1 : 0;
    }
  });
}

Ieskf::LidarSystem Ieskf::BuildLidarSystem(const NavState& x, const DeskewedScan& scan,
                                           const registration::PlaneMatcher& planes) const {
  const PosesAsMatrices poses(x);
  return registration::Reduce<12>(
      scan.points_lidar.size(),
      [&](std::size_t i) {
        registration::LinearizedResidual<12> l;
        if (!matched_[i]) return l;
        const Eigen::Vector3d p = scan.points_lidar[i].cast<double>();
        ResidualJacobian h;
        l.matched = true;
        l.r = Residual(poses, p, planes_[i], &h);
        l.used = planes.PassesGate(l.r, p.norm());
        l.J = h.transpose();
        return l;
      },
      registration::RobustKernel::None());
}

void Ieskf::ReportFit(const NavState& x, const DeskewedScan& scan,
                      const registration::PlaneMatcher& planes, UpdateSummary* summary) const {
  LidarFit fit(scan.points_lidar.size());
  const lie::SO3d R_imu_map = x.R_map_imu.Inverse();
  const PosesAsMatrices poses(x);
  for (std::size_t i = 0; i < scan.points_lidar.size(); ++i) {
    if (!matched_[i]) continue;
    const Eigen::Vector3d p = scan.points_lidar[i].cast<double>();
    const double r = Residual(poses, p, planes_[i], nullptr);
    fit.Add(i, x.T_imu_lidar * p, R_imu_map * planes_[i].normal, r, planes.PassesGate(r, p.norm()));
  }
  fit.Report(options_.lidar_update, summary);
}

namespace {

// Scatters the compact 12-column lidar system into the active state dimension.
void AddLidarSystem(const Eigen::Matrix<double, 12, 12>& HtH,
                    const Eigen::Matrix<double, 12, 1>& Htr, double weight, int dim,
                    Eigen::MatrixXd* A, Eigen::VectorXd* b) {
  const int index[4] = {kRotation, kPosition, kExtrinsicRotation, kExtrinsicTranslation};
  const int blocks = dim == kDim ? 4 : 2;
  for (int i = 0; i < blocks; ++i) {
    b->segment<3>(index[i]) += weight * Htr.segment<3>(3 * i);
    for (int j = 0; j < blocks; ++j) {
      A->block<3, 3>(index[i], index[j]) += weight * HtH.block<3, 3>(3 * i, 3 * j);
    }
  }
}

// J⁻¹... J = ∂(x ⊞ δ ⊟ x̂)/∂δ: identity except Jr⁻¹(dθ) on the rotation blocks.
Eigen::MatrixXd PriorJacobian(const StateVector& dx, int dim) {
  Eigen::MatrixXd J = Eigen::MatrixXd::Identity(dim, dim);
  J.block<3, 3>(kRotation, kRotation) = SO3d::RightJacobianInverse(dx.segment<3>(kRotation));
  if (dim == kDim) {
    J.block<3, 3>(kExtrinsicRotation, kExtrinsicRotation) =
        SO3d::RightJacobianInverse(dx.segment<3>(kExtrinsicRotation));
  }
  return J;
}

}  // namespace

UpdateSummary Ieskf::Update(const DeskewedScan& scan, const registration::PlaneMatcher& planes) {
  UpdateSummary summary;
  summary.num_points = scan.points_lidar.size();
  if (!initialized_) {
    summary.message = "estimator not initialised";
    return summary;
  }
  const NavState before = state_;
  // Tested before propagation drops the interval's samples; the speed is the last update's.
  summary.standstill = TestStandstillBetween(state_.t_ns, scan.t_ns, state_.v_map_imu).at_rest;
  Propagate(scan.t_ns);
  if (planes.map().Size() == 0) {
    summary.message = "map is empty: prediction only";
  } else {
    Correct(scan, planes, &summary);
    if (summary.applied && !imu_options_.enabled) constant_velocity_.Learn(before, &state_);
  }
  finalized_.push_back(state_);
  return summary;
}

void Ieskf::Correct(const DeskewedScan& scan, const registration::PlaneMatcher& planes,
                    UpdateSummary* summary) {
  const int dim = ActiveDim();
  if (dim < kDim && options_.ieskf.online_extrinsic) {
    // Held: the update treats the extrinsic as known, so its correlation with the rest of the
    // state, which this update would not carry, is dropped rather than left stale. (Never
    // estimated, the extrinsic has no correlation: propagation does not couple it.)
    P_.block(0, dim, dim, kDim - dim).setZero();
    P_.block(dim, 0, kDim - dim, dim).setZero();
  }
  const NavState prior = state_;
  const Eigen::MatrixXd P_prior = P_.topLeftCorner(dim, dim);
  const Eigen::MatrixXd P_prior_inv = P_prior.ldlt().solve(Eigen::MatrixXd::Identity(dim, dim));
  const LidarUpdateOptions& lidar = options_.lidar_update;
  const double weight = 1.0 / (lidar.lidar_noise_m * lidar.lidar_noise_m);
  const double sigma_v = options_.standstill.velocity_noise_mps;
  const double zero_velocity_weight = 1.0 / (sigma_v * sigma_v);
  NavState x = UpdateStart(prior, scan, planes,
                           [&](const NavState& candidate) {
                             Associate(candidate, scan, planes);
                             return BuildLidarSystem(candidate, scan, planes).used;
                           },
                           summary);
  Eigen::MatrixXd A;
  bool rematch = true;
  for (int it = 0; it < options_.ieskf.max_iterations; ++it) {
    if (rematch) Associate(x, scan, planes);
    const LidarSystem system = BuildLidarSystem(x, scan, planes);
    summary->iterations = it + 1;
    summary->num_matches = system.used;
    if (static_cast<int>(system.used) < lidar.min_matches) {
      summary->message = TooFewMatchesMessage(system.used, lidar.min_matches);
      return;  // the prediction stands
    }
    const StateVector dx = BoxMinus(x, prior);
    const Eigen::MatrixXd J = PriorJacobian(dx, dim);
    A = J.transpose() * P_prior_inv * J;
    Eigen::VectorXd b = J.transpose() * (P_prior_inv * dx.head(dim));
    AddLidarSystem(system.JtJ, system.Jtr, weight, dim, &A, &b);
    if (summary->standstill) {
      // v_map = 0 measured with noise σ: residual v, Jacobian I on the velocity block.
      A.block<3, 3>(kVelocity, kVelocity).diagonal().array() += zero_velocity_weight;
      b.segment<3>(kVelocity) += zero_velocity_weight * x.v_map_imu;
    }
    const Eigen::VectorXd step = -A.ldlt().solve(b);
    StateVector delta = StateVector::Zero();
    delta.head(dim) = step;
    x = BoxPlus(x, delta);
    const double rot = delta.segment<3>(kRotation).norm();
    const double trans = delta.segment<3>(kPosition).norm();
    summary->converged = rot < options_.ieskf.convergence_rotation_rad &&
                         trans < options_.ieskf.convergence_translation_m;
    rematch = std::max(rot, trans) > options_.ieskf.rematch_threshold;
    if (summary->converged) break;
  }
  state_ = x;
  LearnFromUpdate(prior, x);
  const Eigen::MatrixXd P_post = A.ldlt().solve(Eigen::MatrixXd::Identity(dim, dim));
  P_.topLeftCorner(dim, dim) = 0.5 * (P_post + P_post.transpose());
  summary->applied = true;
  ReportFit(x, scan, planes, summary);
}

}  // namespace hylo::estimation
