#pragma once
// A cloud a search attempt looks at, taken where the search accumulates its scans and moved
// into the attempt's frame where the attempt runs: transforming a search's accumulated cloud
// (hundreds of thousands of points) costs milliseconds, which on the scan thread would set the
// searching scans' worst times.

#include <Eigen/Geometry>
#include <future>

#include "hylo/common/point_types.h"

namespace hylo::localization {

struct AttemptCloud {
  PointCloud points;  ///< in the frame they were taken in ("from")
  /// The attempt's frame (the vehicle's IMU frame at the attempt's scan) from theirs.
  Eigen::Isometry3d T_attempt_from = Eigen::Isometry3d::Identity();

  /// The points in the attempt's frame, in their order.
  PointCloud Resolve() const;
};

/// What an attempt looks at: the cloud to place and, when it places nothing, the last scans
/// alone (empty: none).
struct AttemptClouds {
  AttemptCloud accumulated;
  AttemptCloud recent;
};

/// `clouds` as a future that is ready.
std::shared_future<AttemptClouds> Ready(AttemptClouds clouds);

}  // namespace hylo::localization
