#include "hylo/localization/attempt_cloud.h"

#include <utility>

#include "hylo/common/transformed_cloud.h"

namespace hylo::localization {

PointCloud AttemptCloud::Resolve() const { return Transformed(T_attempt_from, points); }

std::shared_future<AttemptClouds> Ready(AttemptClouds clouds) {
  std::promise<AttemptClouds> ready;
  ready.set_value(std::move(clouds));
  return ready.get_future().share();
}

}  // namespace hylo::localization
