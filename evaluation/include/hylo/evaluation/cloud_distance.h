#pragma once
// The paper's cloud-to-cloud metric (Alamanos et al., Sec. V, Table I): for every point of a
// cloud A, the distance to its nearest neighbour in a reference cloud B; pairs farther than a
// threshold are outliers (parts of A that B never saw, or changed parts of the site) and are
// rejected before the statistics.

#include <string>

#include "hylo/common/point_types.h"
#include "hylo/registration/neighbor_search.h"

namespace hylo::evaluation {

struct CloudDistanceOptions {
  double max_distance_m = 0.5;  ///< nearest-neighbour distances above this are outliers,
                                ///< rejected from the statistics, m, > 0
  bool IsValid(std::string* why) const;
};

struct CloudDistanceSummary {
  std::size_t num_points = 0;      ///< finite points of A queried
  std::size_t num_nonfinite = 0;   ///< points of A with a NaN/inf coordinate, skipped
  std::size_t count = 0;           ///< inlier pairs (distance <= max_distance_m)
  std::size_t num_rejected = 0;    ///< points of A without a neighbour within max_distance_m
  double rejected_fraction = 0.0;  ///< num_rejected / num_points (0 when num_points = 0)
  double mean_m = 0.0;             ///< mean inlier distance, m
  double std_m = 0.0;              ///< population standard deviation (divide by count), m
  double median_m = 0.0;           ///< median inlier distance (mean of the two middle), m
  double rms_m = 0.0;              ///< sqrt(mean of squared inlier distances), m
  double max_m = 0.0;              ///< largest inlier distance, m
  bool ok = false;                 ///< at least one inlier pair; else statistics are 0
  std::string message;             ///< why ok is false, or empty
};

/// Distances from each point of `cloud` to its nearest neighbour in `reference`.
/// Bad input (invalid options, empty clouds, no inlier) gives ok = false and a message.
CloudDistanceSummary CloudToCloudDistance(const PointCloud& cloud,
                                          const registration::NeighborSearch& reference,
                                          const CloudDistanceOptions& options = {});

}  // namespace hylo::evaluation
