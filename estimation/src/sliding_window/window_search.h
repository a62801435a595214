#pragma once
// The map, filled in by the window's own scans where it has too few neighbours (private to
// the sliding window). The map holds finalized scans only, so the last window_size - 1 scans
// are missing from it: at the start of a run the map is empty, and a place seen for the first
// time is in the window only. Each scan's points stay in its own frame, placed in the map by
// the window's current estimate of its pose.

#include <memory>
#include <vector>

#include "hylo/lie/se3.h"
#include "hylo/mapping/ikd_tree.h"
#include "hylo/registration/neighbor_search.h"

namespace hylo::estimation {

class MapAndWindowSearch final : public registration::NeighborSearch {
 public:
  struct Scan {
    const registration::NeighborSearch* points = nullptr;      ///< in the scan's own frame
    const std::vector<Eigen::Vector3d>* point_list = nullptr;  ///< the same points
    lie::SE3d T_map_scan;
  };

  /// Keeps references to `map` and the scans' searches: they must outlive this view. With an
  /// empty map, builds one tree of the scans' points placed in the map (the first window of a
  /// run): each query then searches once instead of once per scan.
  MapAndWindowSearch(const registration::NeighborSearch& map, std::vector<Scan> scans);

  /// The map's k nearest, or when it has fewer than k within max_distance, the k nearest
  /// among the map's and every scan's (map frame); nearest first.
  void KNearest(const Eigen::Vector3f& query_map, int k, float max_distance,
                std::vector<registration::Neighbor>* neighbors) const override;
  std::size_t Size() const override;

 private:
  const registration::NeighborSearch& map_;
  std::vector<Scan> scans_;
  std::vector<Eigen::Isometry3f> T_scan_map_, T_map_scan_;  // float copies for the queries
  std::unique_ptr<mapping::IkdTree> scans_in_map_;          // the union, while the map is empty
};

}  // namespace hylo::estimation
