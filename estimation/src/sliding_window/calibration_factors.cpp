#include "calibration_factors.h"

#include <Eigen/Geometry>

#include "hylo/estimation/sliding_window/so3_manifold.h"
#include "hylo/lie/so3.h"
#include "hylo/registration/parallel.h"

namespace hylo::estimation {
namespace {

class TimeOffsetPrior final : public ceres::SizedCostFunction<1, 1> {
 public:
  TimeOffsetPrior(double centre_s, double sigma_s) : centre_s_(centre_s), sigma_s_(sigma_s) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    residuals[0] = (parameters[0][0] - centre_s_) / sigma_s_;
    if (jacobians != nullptr && jacobians[0] != nullptr) jacobians[0][0] = 1.0 / sigma_s_;
    return true;
  }

 private:
  double centre_s_, sigma_s_;
};

struct RotationPriorResidual {
  Eigen::Quaterniond centre;
  double inv_sigma = 1.0;

  template <typename T>
  bool operator()(const T* q, T* residual) const {
    const lie::SO3<T> Q{Eigen::Quaternion<T>(q)};
    const lie::SO3<T> C{centre.cast<T>()};
    Eigen::Map<Eigen::Matrix<T, 3, 1>>{residual} = lie::Minus(Q, C) * T(inv_sigma);
    return true;
  }
};

}  // namespace

CalibratedScanPlaneFactor::CalibratedScanPlaneFactor(const std::vector<PlaneMatch>& matches,
                                                     CalibrationLayout layout,
                                                     const Eigen::Vector3d& rate_imu,
                                                     const Eigen::Vector3d& lever_arm_imu)
    : matches_(matches), layout_(layout), rate_imu_(rate_imu), lever_arm_imu_(lever_arm_imu) {
  set_num_residuals(static_cast<int>(matches.size()));
  std::vector<int32_t>& sizes = *mutable_parameter_block_sizes();
  sizes = {4, 3, 9};
  if (layout.time_offset) sizes.push_back(1);
  if (layout.extrinsic_rotation) sizes.push_back(4);
}

bool CalibratedScanPlaneFactor::Evaluate(double const* const* parameters, double* residuals,
                                         double** jacobians) const {
  const Eigen::Matrix3d R = Eigen::Quaterniond(parameters[0]).normalized().toRotationMatrix();
  const Eigen::Map<const Eigen::Vector3d> p(parameters[1]);
  const Eigen::Map<const Eigen::Vector3d> v(parameters[2]);
  int next = 3;
  const int time_block = layout_.time_offset ? next++ : -1;
  const int rotation_block = layout_.extrinsic_rotation ? next++ : -1;
  const double dt = time_block >= 0 ? parameters[time_block][0] : 0.0;
  const Eigen::Matrix3d Q =
      rotation_block >= 0
          ? Eigen::Quaterniond(parameters[rotation_block]).normalized().toRotationMatrix()
          : Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d E = lie::SO3d::Exp(rate_imu_ * dt).Matrix();
  const Eigen::Matrix3d RE = R * E;
  const Eigen::Vector3d velocity_shift = v * dt;
  const auto wants = [jacobians](int block) {
    return block >= 0 && jacobians != nullptr && jacobians[block] != nullptr;
  };
  const bool any_jacobian = jacobians != nullptr;
  const Eigen::Matrix<double, 3, 4> lift_state =
      4.0 * RotationPlusJacobian(parameters[0]).transpose();
  const Eigen::Matrix<double, 3, 4> lift_extrinsic =
      rotation_block >= 0 ? Eigen::Matrix<double, 3, 4>(
                                4.0 * RotationPlusJacobian(parameters[rotation_block]).transpose())
                          : Eigen::Matrix<double, 3, 4>::Zero();
  // Each match writes its own residual and Jacobian rows: any number of threads.
  registration::ParallelFor(matches_.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const PlaneMatch& m = matches_[k];
      const Eigen::Vector3d arm = m.point_imu - lever_arm_imu_;  // R_il p, IMU frame
      const Eigen::Vector3d q_corrected = Q * arm + lever_arm_imu_;
      const Eigen::Vector3d q_then = E * q_corrected;  // the point at the state's orientation
      const Eigen::Vector3d P = R * q_then + p + velocity_shift;
      residuals[k] = m.sqrt_weight * m.plane.Distance(P);
      if (!any_jacobian) continue;
      const Eigen::RowVector3d wn = m.sqrt_weight * m.plane.normal.transpose();
      if (wants(0)) {  // R ⊞ δθ: −R [E q']× δθ
        const Eigen::RowVector3d J = -wn * R * lie::SO3d::Hat(q_then);
        Eigen::Map<Eigen::RowVector4d>(jacobians[0] + 4 * k) = J * lift_state;
      }
      if (wants(1)) Eigen::Map<Eigen::RowVector3d>(jacobians[1] + 3 * k) = wn;
      if (wants(2)) {  // only the velocity moves the point; ω is held at its value
        Eigen::Map<Eigen::Matrix<double, 1, 9>> J(jacobians[2] + 9 * k);
        J.setZero();
        J.head<3>() = wn * dt;
      }
      if (wants(time_block)) {  // d/dδt: R E (ω × q') + v
        jacobians[time_block][k] = wn * (RE * rate_imu_.cross(q_corrected) + v);
      }
      if (wants(rotation_block)) {  // Q ⊞ δφ: −R E Q [q − t]× δφ
        const Eigen::RowVector3d J = -wn * RE * Q * lie::SO3d::Hat(arm);
        Eigen::Map<Eigen::RowVector4d>(jacobians[rotation_block] + 4 * k) = J * lift_extrinsic;
      }
    }
  });
  return true;
}

ceres::CostFunction* MakeTimeOffsetPriorFactor(double centre_s, double sigma_s) {
  return new TimeOffsetPrior(centre_s, sigma_s);
}

ceres::CostFunction* MakeRotationPriorFactor(const double* centre_xyzw, double sigma_rad) {
  return new ceres::AutoDiffCostFunction<RotationPriorResidual, 3, 4>(
      new RotationPriorResidual{Eigen::Quaterniond(centre_xyzw), 1.0 / sigma_rad});
}

}  // namespace hylo::estimation
