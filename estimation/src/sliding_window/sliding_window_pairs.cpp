// Sliding window: the scans of the window as searchable clouds in their own frames, and the
// constraints between them (scan_pairs): each new scan's points matched to planes of every
// earlier scan's own points, in that scan's IMU frame, so the window moves its poses relative
// to each other (ScanPairFactor).
#include <algorithm>

#include "hylo/estimation/sliding_window/sliding_window.h"
#include "hylo/registration/parallel.h"
#include "sliding_window_state.h"

namespace hylo::estimation {

void SlidingWindow::KeepOwnPoints(WindowState* state) const {
  state->own_points.reset();
  state->pairs.clear();
  // Searched only by the fill-in (scans extending the map) or the pairs: against a fixed
  // prior the tree would be built for nothing on every scan.
  if (state->points_imu.empty() || !(scans_extend_map_ || options_.sliding_window.scan_pairs)) {
    return;
  }
  PointCloud points;
  points.reserve(state->points_imu.size());
  for (const Eigen::Vector3d& p : state->points_imu) points.push_back(p.cast<float>());
  state->own_points = std::make_unique<mapping::IkdTree>();
  state->own_points->Build(points);
}

std::size_t SlidingWindow::AssociatePairs(const registration::PlaneMatcherOptions& options) {
  WindowState& newest = *window_.back();
  newest.pairs.clear();
  const std::size_t n = newest.points_imu.size();
  if (n == 0) return 0;
  // Evenly spread points, the same for every earlier scan.
  const std::size_t stride =
      (n + options_.sliding_window.pair_points - 1) / options_.sliding_window.pair_points;
  const std::size_t selected = (n + stride - 1) / stride;
  point_planes_.resize(selected);
  point_matched_.resize(selected);
  const lie::SE3d T_map_newest = StateAt(window_.size() - 1).T_map_imu();
  std::size_t total = 0;
  for (std::size_t k = 0; k + 1 < window_.size(); ++k) {
    WindowState& earlier = *window_[k];
    if (earlier.own_points == nullptr || earlier.own_points->Size() == 0) continue;
    const lie::SE3d T_earlier_newest = StateAt(k).T_map_imu().Inverse() * T_map_newest;
    const registration::PlaneMatcher planes(*earlier.own_points, options);
    registration::ParallelFor(selected, [&](std::size_t begin, std::size_t end) {
      for (std::size_t s = begin; s < end; ++s) {
        const Eigen::Vector3d p_earlier = T_earlier_newest * newest.points_imu[s * stride];
        point_matched_[s] =
            planes.Match(p_earlier, &point_planes_[s]) &&
            planes.PassesGate(point_planes_[s].Distance(p_earlier), newest.ranges_m[s * stride]);
      }
    });
    ScanPairMatches pair;
    pair.earlier = &earlier;
    for (std::size_t s = 0; s < selected; ++s) {
      if (!point_matched_[s]) continue;
      const auto index = static_cast<uint32_t>(s * stride);
      pair.matches.push_back(
          {newest.points_imu[index], point_planes_[s], LeastSquaresSqrtWeight(), index});
    }
    total += pair.matches.size();
    if (!pair.matches.empty()) newest.pairs.push_back(std::move(pair));
  }
  return total;
}

}  // namespace hylo::estimation
