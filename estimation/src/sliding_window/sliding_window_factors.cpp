#include "sliding_window_factors.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "hylo/estimation/sliding_window/so3_manifold.h"
#include "hylo/registration/parallel.h"
#include "hylo/registration/point_to_plane.h"

namespace hylo::estimation {
namespace {

using RowMajor15x3 = Eigen::Matrix<double, 15, 3, Eigen::RowMajor>;
using RowMajor15x9 = Eigen::Matrix<double, 15, 9, Eigen::RowMajor>;

NavState StateFromBlocks(const double* rotation, const double* position, const double* speed_bias) {
  NavState x;
  x.R_map_imu = lie::SO3d(Eigen::Quaterniond(rotation));
  x.p_map_imu = Eigen::Map<const Eigen::Vector3d>(position);
  x.v_map_imu = Eigen::Map<const Eigen::Vector3d>(speed_bias);
  x.gyro_bias = Eigen::Map<const Eigen::Vector3d>(speed_bias + 3);
  x.accel_bias = Eigen::Map<const Eigen::Vector3d>(speed_bias + 6);
  return x;
}

// Writes the whitened tangent Jacobian of one state into its three ambient blocks.
void ScatterImuJacobian(const ImuJacobian& J, const double* rotation, double* jac_rotation,
                        double* jac_position, double* jac_speed_bias) {
  if (jac_rotation != nullptr) {
    LiftRotationJacobian<15>(rotation, Eigen::Matrix<double, 15, 3>(J.leftCols<3>()), jac_rotation);
  }
  if (jac_position != nullptr) Eigen::Map<RowMajor15x3>{jac_position} = J.middleCols<3>(3);
  if (jac_speed_bias != nullptr) Eigen::Map<RowMajor15x9>{jac_speed_bias} = J.rightCols<9>();
}

struct ConstantVelocityResidual {
  double dt_ab, dt_bc, inv_sigma_t, inv_sigma_r;

  template <typename T>
  bool operator()(const T* q_a, const T* p_a, const T* q_b, const T* p_b, const T* q_c,
                  const T* p_c, T* residual) const {
    using Vec3 = Eigen::Matrix<T, 3, 1>;
    using Quat = Eigen::Quaternion<T>;
    const Eigen::Map<const Vec3> pa(p_a), pb(p_b), pc(p_c);
    const lie::SO3<T> Ra{Quat(q_a)}, Rb{Quat(q_b)}, Rc{Quat(q_c)};
    const Vec3 v_ab = (pb - pa) / T(dt_ab), v_bc = (pc - pb) / T(dt_bc);
    const Vec3 w_ab = lie::Minus(Rb, Ra) / T(dt_ab), w_bc = lie::Minus(Rc, Rb) / T(dt_bc);
    Eigen::Map<Vec3>{residual} = (v_bc - v_ab) * T(inv_sigma_t);
    Eigen::Map<Vec3>(residual + 3) = (w_bc - w_ab) * T(inv_sigma_r);
    return true;
  }
};

}  // namespace

NavState StateBlocks::ToNavState(const NavState& x) const {
  NavState y = StateFromBlocks(rotation, position, speed_bias);
  y.t_ns = x.t_ns;
  y.gravity_map = x.gravity_map;
  y.T_imu_lidar = x.T_imu_lidar;
  return y;
}

void StateBlocks::FromNavState(const NavState& x) {
  Eigen::Map<Eigen::Vector4d>{rotation} = x.R_map_imu.unit_quaternion().coeffs();
  Eigen::Map<Eigen::Vector3d>{position} = x.p_map_imu;
  Eigen::Map<Eigen::Vector3d>{speed_bias} = x.v_map_imu;
  Eigen::Map<Eigen::Vector3d>(speed_bias + 3) = x.gyro_bias;
  Eigen::Map<Eigen::Vector3d>(speed_bias + 6) = x.accel_bias;
}

ImuFactor::ImuFactor(const ImuPreintegration& preintegration) : preintegration_(preintegration) {
  // Σ = V D Vᵀ, so D^(-1/2) Vᵀ whitens the residual (rᵀ Σ⁻¹ r = ‖D^(-1/2) Vᵀ r‖²). Across an IMU
  // gap Σ holds a large, almost rank-one block (one unknown acceleration error drives both δp
  // and δv) beside the tiny white-noise terms: inverting it and then factoring the inverse
  // loses its definiteness to rounding, the eigen-decomposition does not.
  const Eigen::SelfAdjointEigenSolver<ImuCovariance> eigen(preintegration.ResidualCovariance());
  const Eigen::Matrix<double, kImuFactorDim, 1> d = eigen.eigenvalues();
  const double floor = std::max(d.maxCoeff() * 1e-15, std::numeric_limits<double>::min());
  sqrt_information_ =
      d.cwiseMax(floor).cwiseSqrt().cwiseInverse().asDiagonal() * eigen.eigenvectors().transpose();
}

bool ImuFactor::Evaluate(double const* const* parameters, double* residuals,
                         double** jacobians) const {
  const NavState x_i = StateFromBlocks(parameters[0], parameters[1], parameters[2]);
  const NavState x_j = StateFromBlocks(parameters[3], parameters[4], parameters[5]);
  const Eigen::Map<const Eigen::Vector3d> gravity_map(parameters[6]);
  ImuJacobian J_i, J_j;
  Eigen::Matrix<double, 15, 3> J_g;
  const bool want = jacobians != nullptr;
  const ImuResidual r = preintegration_.Evaluate(x_i, x_j, gravity_map, want ? &J_i : nullptr,
                                                 want ? &J_j : nullptr, want ? &J_g : nullptr);
  Eigen::Map<ImuResidual>{residuals} = sqrt_information_ * r;
  if (!want) return true;
  ScatterImuJacobian(sqrt_information_ * J_i, parameters[0], jacobians[0], jacobians[1],
                     jacobians[2]);
  ScatterImuJacobian(sqrt_information_ * J_j, parameters[3], jacobians[3], jacobians[4],
                     jacobians[5]);
  if (jacobians[6] != nullptr) Eigen::Map<RowMajor15x3>{jacobians[6]} = sqrt_information_ * J_g;
  return true;
}

ScanPairFactor::ScanPairFactor(const std::vector<PlaneMatch>& matches) : matches_(matches) {
  set_num_residuals(static_cast<int>(matches.size()));
  mutable_parameter_block_sizes()->assign({4, 3, 4, 3});
}

bool ScanPairFactor::Evaluate(double const* const* parameters, double* residuals,
                              double** jacobians) const {
  const Eigen::Matrix3d R_a = Eigen::Quaterniond(parameters[0]).normalized().toRotationMatrix();
  const Eigen::Map<const Eigen::Vector3d> p_a(parameters[1]);
  const Eigen::Matrix3d R_b = Eigen::Quaterniond(parameters[2]).normalized().toRotationMatrix();
  const Eigen::Map<const Eigen::Vector3d> p_b(parameters[3]);
  const auto wants = [jacobians](int block) {
    return jacobians != nullptr && jacobians[block] != nullptr;
  };
  const bool any_jacobian = wants(0) || wants(1) || wants(2) || wants(3);
  const Eigen::Matrix<double, 3, 4> lift_a = 4.0 * RotationPlusJacobian(parameters[0]).transpose();
  const Eigen::Matrix<double, 3, 4> lift_b = 4.0 * RotationPlusJacobian(parameters[2]).transpose();
  registration::ParallelFor(matches_.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const PlaneMatch& m = matches_[k];
      // b's plane in the map: the scan-to-map factor for a, whose plane moves with b.
      registration::Plane plane_map;
      plane_map.normal = R_b * m.plane.normal;
      plane_map.offset = m.plane.offset - plane_map.normal.dot(p_b);
      const Eigen::Vector3d y_map = R_a * m.point_imu + p_a;
      residuals[k] = m.sqrt_weight * plane_map.Distance(y_map);
      if (!any_jacobian) continue;
      const registration::Vector6 J_a =
          m.sqrt_weight * registration::PointToPlaneJacobian(R_a, m.point_imu, plane_map);
      if (wants(0))
        Eigen::Map<Eigen::RowVector4d>(jacobians[0] + 4 * k) = J_a.head<3>().transpose() * lift_a;
      if (wants(1))
        Eigen::Map<Eigen::RowVector3d>(jacobians[1] + 3 * k) = J_a.tail<3>().transpose();
      // R_b ⊞ δ moves the point seen from b, z = R_bᵀ (y − p_b), by [z]× δ.
      const Eigen::Vector3d z_b = R_b.transpose() * (y_map - p_b);
      if (wants(2)) {
        const Eigen::RowVector3d J_rotation_b =
            m.sqrt_weight * m.plane.normal.transpose() * lie::SO3d::Hat(z_b);
        Eigen::Map<Eigen::RowVector4d>(jacobians[2] + 4 * k) = J_rotation_b * lift_b;
      }
      if (wants(3)) {
        Eigen::Map<Eigen::RowVector3d>(jacobians[3] + 3 * k) =
            -m.sqrt_weight * plane_map.normal.transpose();
      }
    }
  });
  return true;
}

bool ZeroVelocityFactor::Evaluate(double const* const* parameters, double* residuals,
                                  double** jacobians) const {
  for (int i = 0; i < 3; ++i) residuals[i] = sqrt_information_ * parameters[0][i];
  if (jacobians != nullptr && jacobians[0] != nullptr) {
    Eigen::Map<Eigen::Matrix<double, 3, 9, Eigen::RowMajor>> J(jacobians[0]);
    J.setZero();
    J.leftCols<3>().diagonal().setConstant(sqrt_information_);
  }
  return true;
}

ceres::CostFunction* MakeConstantVelocityFactor(double dt_ab_s, double dt_bc_s,
                                                double translation_noise, double rotation_noise) {
  const double dt_mid = 0.5 * (dt_ab_s + dt_bc_s);
  const ConstantVelocityResidual functor{dt_ab_s, dt_bc_s,
                                         1.0 / (translation_noise * std::sqrt(dt_mid)),
                                         1.0 / (rotation_noise * std::sqrt(dt_mid))};
  return new ceres::AutoDiffCostFunction<ConstantVelocityResidual, 6, 4, 3, 4, 3, 4, 3>(
      new ConstantVelocityResidual(functor));
}

}  // namespace hylo::estimation
