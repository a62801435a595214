#include "hylo/localization/attempt_cloud.h"

#include <utility>

namespace hylo::localization {

PointCloud AttemptCloud::Resolve() const {
  PointCloud points_attempt;
  points_attempt.reserve(points.size());
  for (const Eigen::Vector3f& p : points) {
    points_attempt.push_back((T_attempt_from * p.cast<double>()).cast<float>());
  }
  return points_attempt;
}

std::shared_future<AttemptClouds> Ready(AttemptClouds clouds) {
  std::promise<AttemptClouds> ready;
  ready.set_value(std::move(clouds));
  return ready.get_future().share();
}

}  // namespace hylo::localization
