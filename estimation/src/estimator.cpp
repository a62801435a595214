#include "hylo/estimation/estimator.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "hylo/estimation/ieskf.h"
#include "hylo/estimation/sliding_window.h"

namespace hylo::estimation {
namespace {

bool Fail(std::string* why, const std::string& field, double value, const char* constraint) {
  if (why != nullptr) {
    std::ostringstream os;
    os << field << " = " << value << ": " << constraint;
    *why = os.str();
  }
  return false;
}

bool Positive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

bool IeskfOptions::IsValid(std::string* why) const {
  if (max_iterations < 1) return Fail(why, "max_iterations", max_iterations, "must be >= 1");
  if (min_matches < 6) return Fail(why, "min_matches", min_matches, "must be >= 6 (6 pose dof)");
  const std::pair<const char*, double> positive[] = {
      {"convergence_rotation_rad", convergence_rotation_rad},
      {"convergence_translation_m", convergence_translation_m},
      {"rematch_threshold", rematch_threshold},
      {"lidar_noise_m", lidar_noise_m},
      {"init_rotation_sigma_rad", init_rotation_sigma_rad},
      {"init_velocity_sigma_mps", init_velocity_sigma_mps},
      {"init_gyro_bias_sigma_radps", init_gyro_bias_sigma_radps},
      {"init_accel_bias_sigma_mps2", init_accel_bias_sigma_mps2},
      {"init_gravity_sigma_mps2", init_gravity_sigma_mps2},
      {"init_extrinsic_rotation_sigma_rad", init_extrinsic_rotation_sigma_rad},
      {"init_extrinsic_translation_sigma_m", init_extrinsic_translation_sigma_m},
      {"cv_translation_noise", cv_translation_noise},
      {"cv_rotation_noise", cv_rotation_noise},
      {"no_imu_yaw_search_step_deg", no_imu_yaw_search_step_deg}};
  for (const auto& [name, value] : positive) {
    if (!Positive(value)) return Fail(why, name, value, "must be finite and > 0");
  }
  if (!std::isfinite(no_imu_yaw_search_deg) || no_imu_yaw_search_deg < 0.0 ||
      no_imu_yaw_search_deg > 180.0)
    return Fail(why, "no_imu_yaw_search_deg", no_imu_yaw_search_deg, "must be in [0, 180]");
  if (!std::isfinite(min_translation_information) || min_translation_information < 0.0)
    return Fail(why, "min_translation_information", min_translation_information,
                "must be finite and >= 0");
  if (!std::isfinite(min_rotation_information) || min_rotation_information < 0.0)
    return Fail(why, "min_rotation_information", min_rotation_information,
                "must be finite and >= 0");
  return true;
}

bool Estimator::Options::IsValid(std::string* why) const {
  std::string inner;
  if (!imu_noise.IsValid(&inner)) {
    if (why != nullptr) *why = "imu_noise." + inner;
    return false;
  }
  if (!ieskf.IsValid(&inner)) {
    if (why != nullptr) *why = "ieskf." + inner;
    return false;
  }
  if (!sliding_window.IsValid(&inner)) {
    if (why != nullptr) *why = "sliding_window." + inner;
    return false;
  }
  return true;
}

std::unique_ptr<Estimator> Estimator::Create(const Options& options) {
  switch (options.backend) {
    case Backend::kIeskf:
      return std::make_unique<Ieskf>(options);
    case Backend::kSlidingWindow:
      return std::make_unique<SlidingWindow>(options);
  }
  throw std::invalid_argument("estimator back-end '" + ToString(options.backend) +
                              "' is not available in this build");
}

std::string ToString(Estimator::Backend backend) {
  return backend == Estimator::Backend::kIeskf ? "ieskf" : "sliding_window";
}

bool ParseBackend(const std::string& name, Estimator::Backend* backend) {
  if (name == "ieskf") {
    *backend = Estimator::Backend::kIeskf;
  } else if (name == "sliding_window") {
    *backend = Estimator::Backend::kSlidingWindow;
  } else {
    return false;
  }
  return true;
}

}  // namespace hylo::estimation
