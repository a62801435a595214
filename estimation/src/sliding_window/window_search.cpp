#include "window_search.h"

#include <algorithm>
#include <cmath>

#include "hylo/lie/isometry.h"

namespace hylo::estimation {

MapAndWindowSearch::MapAndWindowSearch(const registration::NeighborSearch& map,
                                       std::vector<Scan> scans)
    : map_(map), scans_(std::move(scans)) {
  for (const Scan& s : scans_) {
    const Eigen::Isometry3f T_map_scan = lie::ToIsometry(s.T_map_scan).cast<float>();
    T_map_scan_.push_back(T_map_scan);
    T_scan_map_.push_back(T_map_scan.inverse());
  }
  // With an empty map every query searches every scan: their union, placed once, answers it
  // with one search.
  const auto listed = [](const Scan& s) { return s.point_list != nullptr; };
  if (map_.Size() != 0 || scans_.size() < 2 || !std::all_of(scans_.begin(), scans_.end(), listed)) {
    return;
  }
  PointCloud placed;
  placed.reserve(Size());
  for (const Scan& s : scans_) {
    for (const Eigen::Vector3d& p : *s.point_list) {
      placed.push_back((s.T_map_scan * p).cast<float>());
    }
  }
  scans_in_map_ = std::make_unique<mapping::IkdTree>();
  scans_in_map_->Build(placed);
}

void MapAndWindowSearch::KNearest(const Eigen::Vector3f& query_map, int k, float max_distance,
                                  std::vector<registration::Neighbor>* neighbors) const {
  if (scans_in_map_ != nullptr) {
    scans_in_map_->KNearest(query_map, k, max_distance, neighbors);
    return;
  }
  map_.KNearest(query_map, k, max_distance, neighbors);
  // The map first: where it has the neighbours, the window's scans (whose points are denser
  // and all from the last second) would crowd them out and turn the update into scan-to-scan
  // odometry, which drifts (measured on the scenario matrix); they fill in where the map has
  // too few (the first scans of a run, places seen for the first time).
  const auto wanted = static_cast<std::size_t>(k);
  if (neighbors->size() >= wanted) return;
  const auto nearer = [](const registration::Neighbor& a, const registration::Neighbor& b) {
    return a.squared_distance < b.squared_distance;
  };
  // Newest scan first, and each search no farther than the k-th nearest found so far: a
  // farther point cannot be among the k nearest, and a tree prunes most of its nodes with a
  // tight bound. The result is the k nearest of all the scans, as one search of their union
  // would find them.
  float reach_m = max_distance;
  std::vector<registration::Neighbor> found;
  for (std::size_t s = scans_.size(); s-- > 0;) {
    scans_[s].points->KNearest(T_scan_map_[s] * query_map, k, reach_m, &found);
    for (registration::Neighbor& n : found) {
      n.point = T_map_scan_[s] * n.point;  // a rigid motion keeps the distance
      neighbors->push_back(n);
    }
    if (neighbors->size() >= wanted) {
      std::nth_element(neighbors->begin(), neighbors->begin() + (k - 1), neighbors->end(), nearer);
      neighbors->resize(wanted);
      reach_m = std::sqrt((*neighbors)[wanted - 1].squared_distance);
    }
  }
  std::sort(neighbors->begin(), neighbors->end(), nearer);
}

std::size_t MapAndWindowSearch::Size() const {
  std::size_t size = map_.Size();
  for (const Scan& s : scans_) size += s.points->Size();
  return size;
}

}  // namespace hylo::estimation
