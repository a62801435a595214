#pragma once
// The one way registration code reaches a spatial index. The ikd-tree in mapping/ implements
// it; tests implement it by brute force, so every registration routine can be checked against
// an exact search.

#include <Eigen/Core>
#include <vector>

namespace hylo::registration {

/// One neighbour: the point and its squared distance to the query, m^2.
struct Neighbor {
  Eigen::Vector3f point = Eigen::Vector3f::Zero();
  float squared_distance = 0.f;
};

class NeighborSearch {
 public:
  virtual ~NeighborSearch() = default;

  /// Up to k nearest neighbours of `query` within `max_distance` (m), nearest first.
  /// Fewer than k are returned when the index holds fewer points in that range.
  virtual void KNearest(const Eigen::Vector3f& query, int k, float max_distance,
                        std::vector<Neighbor>* neighbors) const = 0;

  /// Number of points currently searchable.
  virtual std::size_t Size() const = 0;
};

}  // namespace hylo::registration
