#include "hylo/estimation/no_imu_motion.h"

#include <cmath>

#include "hylo/common/option_checks.h"
#include "hylo/common/time.h"

namespace hylo::estimation {

bool NoImuOptions::IsValid(std::string* why) const {
  return CheckPositive("cv_translation_noise", cv_translation_noise, why) &&
         CheckPositive("cv_rotation_noise", cv_rotation_noise, why) &&
         CheckInRange("yaw_search_deg", yaw_search_deg, 0.0, 180.0, why) &&
         CheckPositive("yaw_search_step_deg", yaw_search_step_deg, why);
}

void ConstantVelocity::Learn(const NavState& before, NavState* after) {
  if (after->t_ns <= before.t_ns) return;
  const double dt = NanosToSeconds(after->t_ns - before.t_ns);
  after->v_map_imu = (after->p_map_imu - before.p_map_imu) / dt;
  omega_imu_ = lie::Minus(after->R_map_imu, before.R_map_imu) / dt;
}

NavState SearchYaw(const NavState& prior, const NoImuOptions& options,
                   const std::function<std::size_t(const NavState&)>& count_matches) {
  const double range = options.yaw_search_deg * M_PI / 180.0;
  const double step = options.yaw_search_step_deg * M_PI / 180.0;
  NavState best = prior;
  std::size_t best_matches = 0;
  for (double yaw = -range; yaw <= range + 1e-9; yaw += step) {
    NavState candidate = prior;
    candidate.R_map_imu = lie::SO3d::Exp(Eigen::Vector3d(0.0, 0.0, yaw)) * prior.R_map_imu;
    const std::size_t matches = count_matches(candidate);
    if (matches > best_matches) {
      best_matches = matches;
      best = candidate;
    }
  }
  return best;
}

}  // namespace hylo::estimation
