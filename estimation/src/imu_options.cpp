#include "hylo/estimation/imu_options.h"

#include <cmath>

#include "hylo/common/option_checks.h"

namespace hylo::estimation {

bool ImuNoise::IsValid(std::string* why) const {
  return CheckNonNegative("gyro_noise_density", gyro_noise_density, why) &&
         CheckNonNegative("accel_noise_density", accel_noise_density, why) &&
         CheckNonNegative("gyro_bias_random_walk", gyro_bias_random_walk, why) &&
         CheckNonNegative("accel_bias_random_walk", accel_bias_random_walk, why);
}

bool ImuOptions::IsValid(std::string* why) const {
  if (!enabled) return true;
  if (!(CheckPositive("rate_hz", rate_hz, why) &&
        CheckInRange("gravity_mps2", gravity_mps2, 9.7, 9.9, why) &&
        CheckSection(noise, "noise", why) &&
        CheckNonNegative("gyro_range_radps", gyro_range_radps, why) &&
        CheckNonNegative("accel_range_mps2", accel_range_mps2, why))) {
    return false;
  }
  if (accel_range_mps2 > 0.0 && accel_range_mps2 < 2.0 * gravity_mps2) {
    return FailOption("accel_range_mps2", accel_range_mps2,
                      "must be 0 (no check) or >= 2 g: a vehicle's IMU reads gravity plus its "
                      "motion, and no part is made with a smaller range",
                      why);
  }
  return true;
}

int64_t ImuOptions::GapNs() const { return static_cast<int64_t>(std::llround(5e9 / rate_hz)); }

}  // namespace hylo::estimation
