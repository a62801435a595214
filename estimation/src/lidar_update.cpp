#include "hylo/estimation/lidar_update.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "hylo/common/option_checks.h"

namespace hylo::estimation {

bool LidarUpdateOptions::IsValid(std::string* why) const {
  return CheckPositive("lidar_noise_m", lidar_noise_m, why) &&
         CheckAtLeast("min_matches", min_matches, 6, "(6 pose degrees of freedom)", why) &&
         CheckNonNegative("min_translation_information", min_translation_information, why) &&
         CheckNonNegative("min_rotation_information", min_rotation_information, why);
}

LidarFit::LidarFit(std::size_t num_points)
    : residuals_m_(num_points, std::numeric_limits<float>::quiet_NaN()) {}

void LidarFit::Add(std::size_t index, const Eigen::Vector3d& point_imu,
                   const Eigen::Vector3d& normal_imu, double residual_m, bool in_update) {
  residuals_m_[index] = static_cast<float>(residual_m);
  if (!in_update) return;
  const Eigen::Vector3d rotation_row = point_imu.cross(normal_imu);
  // Σ n nᵀ does not depend on the frame of n; the IMU frame serves both blocks.
  translation_information_.noalias() += normal_imu * normal_imu.transpose();
  rotation_information_.noalias() += rotation_row * rotation_row.transpose();
  sum_squared_residual_ += residual_m * residual_m;
  ++num_in_update_;
}

void LidarFit::Report(const LidarUpdateOptions& options, UpdateSummary* summary) {
  const double n = static_cast<double>(std::max<std::size_t>(num_in_update_, 1));
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(translation_information_ / n, Eigen::EigenvaluesOnly);
  summary->min_translation_information = eig.eigenvalues()(0);
  eig.computeDirect(rotation_information_ / n, Eigen::EigenvaluesOnly);
  summary->min_rotation_information = eig.eigenvalues()(0);
  summary->degenerate =
      summary->min_translation_information < options.min_translation_information ||
      summary->min_rotation_information < options.min_rotation_information;
  summary->rms_residual_m = std::sqrt(sum_squared_residual_ / n);
  summary->point_residuals_m = std::move(residuals_m_);
  if (summary->degenerate) {
    summary->message = "degenerate geometry: a pose direction is unobserved";
  }
}

std::string TooFewMatchesMessage(std::size_t matches, int min_matches) {
  return "too few plane matches (" + std::to_string(matches) + " < " + std::to_string(min_matches) +
         "): prediction only";
}

}  // namespace hylo::estimation
