#include "hylo/mapping/map_manager.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "hylo/common/check.h"

namespace hylo::mapping {

bool MapManagerOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  if (!(voxel_size_m > 0.0) || !std::isfinite(voxel_size_m)) {
    os << "voxel_size_m = " << voxel_size_m << ": must be finite and > 0";
  } else if (!(window_size_m >= 0.0) || !std::isfinite(window_size_m)) {
    os << "window_size_m = " << window_size_m << ": must be finite and >= 0 (0 = no window)";
  } else if (window_size_m > 0.0 &&
             !(window_margin_m > 0.0 && window_margin_m < 0.5 * window_size_m)) {
    os << "window_margin_m = " << window_margin_m << ": must be in (0, window_size_m / 2 = "
       << 0.5 * window_size_m << ")";
  } else {
    return true;
  }
  if (why != nullptr) *why = os.str();
  return false;
}

MapManager::MapManager(const MapManagerOptions& options) : options_(options) {
  std::string why;
  if (!options_.IsValid(&why)) throw InternalError("invalid options: " + why);
}

void MapManager::SetPrior(const PointCloud& points_map) {
  streamed_.reset();
  prior_ = std::make_unique<IkdTree>();
  prior_->Build(points_map);
}

void MapManager::SetStreamedPrior(std::shared_ptr<StreamedPrior> prior) {
  HYLO_CHECK(prior != nullptr);
  prior_.reset();
  streamed_ = std::move(prior);
}

void MapManager::BeginScan(const Eigen::Vector3f& position_map) {
  if (streamed_ != nullptr) streamed_->Follow(position_map);
}

void MapManager::SetOnDemand(bool on_demand) {
  if (streamed_ != nullptr) streamed_->SetOnDemand(on_demand);
}

bool MapManager::OnPriorMap(const Eigen::Vector3f& position_map) const {
  return streamed_ == nullptr || streamed_->OnMap(position_map);
}

std::string MapManager::prior_error() const {
  return streamed_ == nullptr ? std::string() : streamed_->error();
}

void MapManager::UpdateWindow(const Eigen::Vector3f& sensor) {
  const float half = static_cast<float>(0.5 * options_.window_size_m);
  const float margin = static_cast<float>(options_.window_margin_m);
  if (!window_set_) {
    window_.min = sensor - Eigen::Vector3f::Constant(half);
    window_.max = sensor + Eigen::Vector3f::Constant(half);
    window_set_ = true;
    return;
  }
  for (int axis = 0; axis < 3; ++axis) {
    const bool near_min = sensor[axis] - window_.min[axis] < margin;
    const bool near_max = window_.max[axis] - sensor[axis] < margin;
    if (!near_min && !near_max) continue;
    // Re-centre on the sensor along this axis; the slab that leaves the cube is deleted.
    Box3f slab = window_;
    const float new_min = sensor[axis] - half;
    const float new_max = sensor[axis] + half;
    if (near_max) {
      slab.max[axis] = new_min;
    } else {
      slab.min[axis] = new_max;
    }
    if (keep_windowed_out_) run_.BoxSearch(slab, &windowed_out_);
    counters_.points_windowed_out += run_.DeleteBox(slab);
    window_.min[axis] = new_min;
    window_.max[axis] = new_max;
    ++counters_.window_moves;
  }
}

IkdTree::InsertSummary MapManager::AddScan(const PointCloud& points_map,
                                           const Eigen::Vector3f& sensor_position_map) {
  if (options_.window_size_m > 0.0) UpdateWindow(sensor_position_map);
  const IkdTree::InsertSummary summary =
      run_.Insert(points_map, static_cast<float>(options_.voxel_size_m));
  ++counters_.scans_added;
  counters_.points_inserted += summary.num_inserted;
  return summary;
}

void MapManager::KNearest(const Eigen::Vector3f& query, int k, float max_distance,
                          std::vector<registration::Neighbor>* neighbors) const {
  run_.KNearest(query, k, max_distance, neighbors);
  thread_local std::vector<registration::Neighbor> from_prior;
  if (streamed_ != nullptr) {
    streamed_->KNearest(query, k, max_distance, &from_prior);
  } else if (prior_ != nullptr && prior_->Size() > 0) {
    prior_->KNearest(query, k, max_distance, &from_prior);
  } else {
    return;
  }
  if (from_prior.empty()) return;
  neighbors->insert(neighbors->end(), from_prior.begin(), from_prior.end());
  std::sort(neighbors->begin(), neighbors->end(),
            [](const registration::Neighbor& a, const registration::Neighbor& b) {
              return a.squared_distance < b.squared_distance;
            });
  if (static_cast<int>(neighbors->size()) > k) neighbors->resize(k);
}

std::size_t MapManager::prior_size() const {
  if (streamed_ != nullptr) return streamed_->HeldSize();
  return prior_ == nullptr ? 0 : prior_->Size();
}

std::size_t MapManager::Size() const {
  return run_.Size() + (streamed_ != nullptr ? streamed_->Size() : prior_size());
}

PointCloud MapManager::Flatten() const {
  PointCloud points = streamed_ != nullptr ? streamed_->FlattenHeld()
                      : prior_ == nullptr  ? PointCloud{}
                                           : prior_->Flatten();
  const PointCloud run = run_.Flatten();
  points.insert(points.end(), run.begin(), run.end());
  return points;
}

std::size_t MapManager::MemoryBytes() const {
  return run_.MemoryBytes() + (prior_ == nullptr ? 0 : prior_->MemoryBytes()) +
         (streamed_ == nullptr ? 0 : streamed_->MemoryBytes());
}

}  // namespace hylo::mapping
