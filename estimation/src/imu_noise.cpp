#include "hylo/estimation/imu_noise.h"

#include <cmath>
#include <sstream>

namespace hylo::estimation {

bool ImuNoise::IsValid(std::string* why) const {
  const std::pair<const char*, double> fields[] = {
      {"gyro_noise_density", gyro_noise_density},
      {"accel_noise_density", accel_noise_density},
      {"gyro_bias_random_walk", gyro_bias_random_walk},
      {"accel_bias_random_walk", accel_bias_random_walk}};
  for (const auto& [name, value] : fields) {
    if (!std::isfinite(value) || value < 0.0) {
      if (why != nullptr) {
        std::ostringstream os;
        os << name << " = " << value << ": must be finite and >= 0";
        *why = os.str();
      }
      return false;
    }
  }
  return true;
}

}  // namespace hylo::estimation
