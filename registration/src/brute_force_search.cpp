#include "hylo/registration/brute_force_search.h"

#include <algorithm>

namespace hylo::registration {
namespace {
void SortAndTruncate(std::vector<Neighbor>* neighbors, std::size_t k) {
  auto by_distance = [](const Neighbor& a, const Neighbor& b) {
    return a.squared_distance < b.squared_distance;
  };
  if (neighbors->size() > k) {
    std::partial_sort(neighbors->begin(), neighbors->begin() + k, neighbors->end(), by_distance);
    neighbors->resize(k);
  } else {
    std::sort(neighbors->begin(), neighbors->end(), by_distance);
  }
}
}  // namespace

void BruteForceSearch::KNearest(const Eigen::Vector3f& query, int k, float max_distance,
                                std::vector<Neighbor>* neighbors) const {
  Radius(query, max_distance, neighbors);
  SortAndTruncate(neighbors, static_cast<std::size_t>(std::max(k, 0)));
}

void BruteForceSearch::Radius(const Eigen::Vector3f& query, float radius,
                              std::vector<Neighbor>* neighbors) const {
  neighbors->clear();
  const float radius_sq = radius * radius;
  for (const Eigen::Vector3f& p : points_) {
    const float d2 = (p - query).squaredNorm();
    if (d2 <= radius_sq) neighbors->push_back({p, d2});
  }
  SortAndTruncate(neighbors, neighbors->size());
}

}  // namespace hylo::registration
