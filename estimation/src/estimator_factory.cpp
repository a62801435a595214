// The back-end factory and the estimator options' validation.
#include <utility>

#include "hylo/common/check.h"
#include "hylo/common/enum_names.h"
#include "hylo/common/option_checks.h"
#include "hylo/estimation/estimator_options.h"
#include "hylo/estimation/ieskf/ieskf.h"
#include "hylo/estimation/sliding_window/sliding_window.h"

namespace hylo::estimation {
namespace {

const std::pair<Estimator::Backend, const char*> kBackendNames[] = {
    {Estimator::Backend::kIeskf, "ieskf"}, {Estimator::Backend::kSlidingWindow, "sliding_window"}};

}  // namespace

bool EstimatorOptions::IsValid(std::string* why) const {
  return CheckSection(lidar_update, "lidar_update", why) && CheckSection(no_imu, "no_imu", why) &&
         CheckSection(robust_registration, "robust_registration", why) &&
         CheckSection(standstill, "standstill", why) &&
         CheckSection(ieskf, "ieskf", why) && CheckSection(sliding_window, "sliding_window", why);
}

std::unique_ptr<Estimator> Estimator::Create(const EstimatorOptions& options,
                                             const ImuOptions& imu) {
  switch (options.backend) {
    case Backend::kIeskf:
      return std::make_unique<Ieskf>(options, imu);
    case Backend::kSlidingWindow:
      return std::make_unique<SlidingWindow>(options, imu);
  }
  throw InternalError("Estimator::Create: unknown back-end " +
                      std::to_string(static_cast<int>(options.backend)));
}

std::string ToString(Estimator::Backend backend) { return NameOf(kBackendNames, backend); }

bool ParseBackend(const std::string& name, Estimator::Backend* backend) {
  return ValueOf(kBackendNames, name, backend);
}

}  // namespace hylo::estimation
