#pragma once
// Exact neighbour search by scanning every point: the reference that spatial indexes and
// registration routines are tested against. O(n) per query; not for production use.

#include "hylo/common/point_types.h"
#include "hylo/registration/neighbor_search.h"

namespace hylo::registration {

class BruteForceSearch final : public NeighborSearch {
 public:
  explicit BruteForceSearch(PointCloud points) : points_(std::move(points)) {}

  void KNearest(const Eigen::Vector3f& query, int k, float max_distance,
                std::vector<Neighbor>* neighbors) const override;
  std::size_t Size() const override { return points_.size(); }

  /// All points within `radius` (m) of `query`, nearest first.
  void Radius(const Eigen::Vector3f& query, float radius, std::vector<Neighbor>* neighbors) const;

  const PointCloud& points() const { return points_; }

 private:
  PointCloud points_;
};

}  // namespace hylo::registration
