#include "hylo/estimation/ieskf/ieskf_options.h"

#include "hylo/common/option_checks.h"

namespace hylo::estimation {

bool IeskfOptions::IsValid(std::string* why) const {
  return CheckAtLeast("max_iterations", max_iterations, 1, "", why) &&
         CheckPositive("convergence_rotation_rad", convergence_rotation_rad, why) &&
         CheckPositive("convergence_translation_m", convergence_translation_m, why) &&
         CheckPositive("rematch_threshold", rematch_threshold, why);
}

}  // namespace hylo::estimation
