// IESKF iterated update (FAST-LIO2 Sec. IV-D). Each iteration j linearises the point-to-plane
// residuals r at x_j and minimises ‖x_j ⊞ δ ⊟ x̂‖²_P⁻¹ + ‖r + H δ‖²_R⁻¹ over δ:
//   (Jᵀ P⁻¹ J + Hᵀ R⁻¹ H) δ = −(Jᵀ P⁻¹ (x_j ⊟ x̂) + Hᵀ R⁻¹ r)
// with J = ∂(x_j ⊞ δ ⊟ x̂)/∂δ (Jr⁻¹ on the rotation blocks). This is the paper's Eq. (18)-(20)
// (gain in the state dimension, cost independent of the number of points) written as the
// normal equations; the posterior covariance is their inverse, i.e. (I − K H) P_j.
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>

#include "hylo/common/time.h"
#include "hylo/estimation/ieskf.h"

namespace hylo::estimation {

using namespace state_index;  // NOLINT: index names only
using lie::SO3d;
using registration::Plane;

double PointToPlaneResidual(const NavState& x, const Eigen::Vector3d& point_lidar,
                            const Plane& plane, ResidualJacobian* jacobian) {
  const Eigen::Vector3d point_imu = x.T_imu_lidar * point_lidar;
  const Eigen::Vector3d point_map = x.R_map_imu * point_imu + x.p_map_imu;
  if (jacobian != nullptr) {
    // R·Exp(δθ)·q ≈ R q − R [q]^ δθ, so ∂r/∂δθ = −nᵀ R [q]^ = (q × Rᵀn)ᵀ.
    const Eigen::Vector3d n_imu = x.R_map_imu.Inverse() * plane.normal;
    const Eigen::Vector3d n_lidar = x.T_imu_lidar.so3().Inverse() * n_imu;
    jacobian->block<1, 3>(0, 0) = point_imu.cross(n_imu).transpose();
    jacobian->block<1, 3>(0, 3) = plane.normal.transpose();
    jacobian->block<1, 3>(0, 6) = point_lidar.cross(n_lidar).transpose();
    jacobian->block<1, 3>(0, 9) = n_imu.transpose();
  }
  return plane.Distance(point_map);
}

NavState Ieskf::SearchYaw(const NavState& prior, const DeskewedScan& scan,
                          const registration::PlaneMatcher& planes) {
  const double range = options_.ieskf.no_imu_yaw_search_deg * M_PI / 180.0;
  const double step = options_.ieskf.no_imu_yaw_search_step_deg * M_PI / 180.0;
  NavState best = prior;
  std::size_t best_matches = 0;
  for (double yaw = -range; yaw <= range + 1e-9; yaw += step) {
    NavState candidate = prior;
    candidate.R_map_imu = SO3d::Exp(Eigen::Vector3d(0.0, 0.0, yaw)) * prior.R_map_imu;
    Associate(candidate, scan, planes);
    const std::size_t matches = BuildLidarSystem(candidate, scan, planes).matches;
    if (matches > best_matches) {
      best_matches = matches;
      best = candidate;
    }
  }
  return best;
}

int Ieskf::ActiveDim() const {
  return options_.ieskf.online_extrinsic ? kDim : kDimNoExtrinsic;
}

void Ieskf::Associate(const NavState& x, const DeskewedScan& scan,
                      const registration::PlaneMatcher& planes) {
  const std::size_t n = scan.points_lidar.size();
  planes_.resize(n);
  matched_.assign(n, 0);
  const lie::SE3d T_map_lidar = x.T_map_lidar();
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d p_map = T_map_lidar * scan.points_lidar[i].cast<double>();
    matched_[i] = planes.Match(p_map, &planes_[i]) ? 1 : 0;
  }
}

Ieskf::LidarSystem Ieskf::BuildLidarSystem(const NavState& x, const DeskewedScan& scan,
                                           const registration::PlaneMatcher& planes) const {
  LidarSystem system;
  ResidualJacobian h;
  for (std::size_t i = 0; i < scan.points_lidar.size(); ++i) {
    if (!matched_[i]) continue;
    const Eigen::Vector3d p = scan.points_lidar[i].cast<double>();
    const double r = PointToPlaneResidual(x, p, planes_[i], &h);
    if (!planes.PassesGate(r, p.norm())) continue;
    system.HtH.noalias() += h.transpose() * h;
    system.Htr.noalias() += h.transpose() * r;
    system.sum_sq_residual += r * r;
    ++system.matches;
  }
  return system;
}

void Ieskf::ReportInformation(const LidarSystem& system, UpdateSummary* summary) const {
  const double n = static_cast<double>(std::max<std::size_t>(system.matches, 1));
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(system.HtH.block<3, 3>(3, 3) / n, Eigen::EigenvaluesOnly);
  summary->min_translation_information = eig.eigenvalues()(0);
  eig.computeDirect(system.HtH.block<3, 3>(0, 0) / n, Eigen::EigenvaluesOnly);
  summary->min_rotation_information = eig.eigenvalues()(0);
  summary->degenerate =
      summary->min_translation_information < options_.ieskf.min_translation_information ||
      summary->min_rotation_information < options_.ieskf.min_rotation_information;
  summary->rms_residual_m = std::sqrt(system.sum_sq_residual / n);
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
  J.block<3, 3>(kRotation, kRotation) =
      SO3d::RightJacobianInverse(dx.segment<3>(kRotation));
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
  Propagate(scan.t_ns);
  if (planes.map().Size() == 0) {
    summary.message = "map is empty: prediction only";
    return summary;
  }
  const int dim = ActiveDim();
  const NavState prior = state_;
  const Eigen::MatrixXd P_prior = P_.topLeftCorner(dim, dim);
  const Eigen::MatrixXd P_prior_inv =
      P_prior.ldlt().solve(Eigen::MatrixXd::Identity(dim, dim));
  const double weight = 1.0 / (options_.ieskf.lidar_noise_m * options_.ieskf.lidar_noise_m);
  NavState x = prior;
  if (!options_.use_imu && options_.ieskf.no_imu_yaw_search_deg > 0.0) {
    x = SearchYaw(prior, scan, planes);
  }
  Eigen::MatrixXd A;
  LidarSystem system;
  bool rematch = true;
  for (int it = 0; it < options_.ieskf.max_iterations; ++it) {
    if (rematch) Associate(x, scan, planes);
    system = BuildLidarSystem(x, scan, planes);
    summary.iterations = it + 1;
    summary.num_matches = system.matches;
    if (static_cast<int>(system.matches) < options_.ieskf.min_matches) {
      summary.message = "too few plane matches (" + std::to_string(system.matches) + " < " +
                        std::to_string(options_.ieskf.min_matches) + "): prediction only";
      state_ = prior;
      return summary;
    }
    const StateVector dx = BoxMinus(x, prior);
    const Eigen::MatrixXd J = PriorJacobian(dx, dim);
    A = J.transpose() * P_prior_inv * J;
    Eigen::VectorXd b = J.transpose() * (P_prior_inv * dx.head(dim));
    AddLidarSystem(system.HtH, system.Htr, weight, dim, &A, &b);
    const Eigen::VectorXd step = -A.ldlt().solve(b);
    StateVector delta = StateVector::Zero();
    delta.head(dim) = step;
    x = BoxPlus(x, delta);
    const double rot = delta.segment<3>(kRotation).norm();
    const double trans = delta.segment<3>(kPosition).norm();
    summary.converged = rot < options_.ieskf.convergence_rotation_rad &&
                        trans < options_.ieskf.convergence_translation_m;
    rematch = std::max(rot, trans) > options_.ieskf.rematch_threshold;
    if (summary.converged) break;
  }
  state_ = x;
  const Eigen::MatrixXd P_post = A.ldlt().solve(Eigen::MatrixXd::Identity(dim, dim));
  P_.topLeftCorner(dim, dim) = 0.5 * (P_post + P_post.transpose());
  summary.applied = true;
  ReportInformation(system, &summary);
  if (summary.degenerate) summary.message = "degenerate geometry: a pose direction is unobserved";
  if (!options_.use_imu && scan.t_ns > before.t_ns) {
    const double dt = NanosToSeconds(scan.t_ns - before.t_ns);
    state_.v_map_imu = (state_.p_map_imu - before.p_map_imu) / dt;
    omega_cv_imu_ = lie::Minus(state_.R_map_imu, before.R_map_imu) / dt;
  }
  return summary;
}

}  // namespace hylo::estimation
