#include <ceres/types.h>

#include <cmath>
#include <sstream>

#include "hylo/estimation/sliding_window_options.h"

namespace hylo::estimation {
namespace {

bool Fail(std::string* why, const std::string& field, const std::string& value,
          const char* constraint) {
  if (why != nullptr) *why = field + " = " + value + ": " + constraint;
  return false;
}

std::string Str(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

}  // namespace

/// The Ceres linear solvers the configuration may name (all run single-threaded here).
bool ParseLinearSolver(const std::string& name, ceres::LinearSolverType* type) {
  if (name == "sparse_normal_cholesky") {
    *type = ceres::SPARSE_NORMAL_CHOLESKY;
  } else if (name == "dense_normal_cholesky") {
    *type = ceres::DENSE_NORMAL_CHOLESKY;
  } else if (name == "dense_schur") {
    *type = ceres::DENSE_SCHUR;
  } else if (name == "sparse_schur") {
    *type = ceres::SPARSE_SCHUR;
  } else if (name == "dense_qr") {
    *type = ceres::DENSE_QR;
  } else {
    return false;
  }
  return true;
}

bool SlidingWindowOptions::IsValid(std::string* why) const {
  if (window_size < 2) return Fail(why, "window_size", Str(window_size), "must be >= 2");
  if (max_iterations < 1) return Fail(why, "max_iterations", Str(max_iterations), "must be >= 1");
  if (association_rounds < 1)
    return Fail(why, "association_rounds", Str(association_rounds), "must be >= 1");
  if (min_matches < 6) return Fail(why, "min_matches", Str(min_matches), "must be >= 6");
  ceres::LinearSolverType type;
  if (!ParseLinearSolver(linear_solver, &type))
    return Fail(why, "linear_solver", "'" + linear_solver + "'",
                "must be sparse_normal_cholesky, dense_normal_cholesky, dense_schur, "
                "sparse_schur or dense_qr");
  if (robust_loss != "huber" && robust_loss != "cauchy" && robust_loss != "none")
    return Fail(why, "robust_loss", "'" + robust_loss + "'", "must be huber, cauchy or none");
  const std::pair<const char*, double> positive[] = {
      {"max_solver_time_s", max_solver_time_s},
      {"robust_loss_scale_m", robust_loss_scale_m},
      {"lidar_noise_m", lidar_noise_m},
      {"cv_translation_noise", cv_translation_noise},
      {"cv_rotation_noise", cv_rotation_noise},
      {"no_imu_yaw_search_step_deg", no_imu_yaw_search_step_deg}};
  for (const auto& [name, value] : positive) {
    if (!std::isfinite(value) || value <= 0.0)
      return Fail(why, name, Str(value), "must be finite and > 0");
  }
  const std::pair<const char*, double> non_negative[] = {
      {"min_translation_information", min_translation_information},
      {"min_rotation_information", min_rotation_information}};
  for (const auto& [name, value] : non_negative) {
    if (!std::isfinite(value) || value < 0.0)
      return Fail(why, name, Str(value), "must be finite and >= 0");
  }
  if (!std::isfinite(no_imu_yaw_search_deg) || no_imu_yaw_search_deg < 0.0 ||
      no_imu_yaw_search_deg > 180.0)
    return Fail(why, "no_imu_yaw_search_deg", Str(no_imu_yaw_search_deg), "must be in [0, 180]");
  return true;
}

}  // namespace hylo::estimation
