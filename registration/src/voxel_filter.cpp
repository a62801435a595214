#include "hylo/registration/voxel_filter.h"

#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>

namespace hylo::registration {
namespace {
struct VoxelKeyHash {
  std::size_t operator()(const Eigen::Vector3i& k) const {
    // Large primes from the spatial-hashing literature (Teschner et al. 2003).
    return (static_cast<std::size_t>(k.x()) * 73856093u) ^
           (static_cast<std::size_t>(k.y()) * 19349663u) ^
           (static_cast<std::size_t>(k.z()) * 83492791u);
  }
};
struct VoxelKeyEqual {
  bool operator()(const Eigen::Vector3i& a, const Eigen::Vector3i& b) const { return a == b; }
};
}  // namespace

std::vector<std::size_t> UniformSampleIndices(const PointCloud& points, float voxel_size_m) {
  std::vector<std::size_t> kept;
  if (voxel_size_m <= 0.f) {
    kept.resize(points.size());
    std::iota(kept.begin(), kept.end(), 0);
    return kept;
  }
  struct Best {
    std::size_t slot;  // position in `kept`
    float squared_distance;
  };
  std::unordered_map<Eigen::Vector3i, Best, VoxelKeyHash, VoxelKeyEqual> best;
  best.reserve(points.size() / 4 + 16);
  const float inv = 1.f / voxel_size_m;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3f scaled = points[i] * inv;
    const Eigen::Vector3i key(static_cast<int>(std::floor(scaled.x())),
                              static_cast<int>(std::floor(scaled.y())),
                              static_cast<int>(std::floor(scaled.z())));
    const Eigen::Vector3f centre = (key.cast<float>() + Eigen::Vector3f::Constant(0.5f)) * voxel_size_m;
    const float d2 = (points[i] - centre).squaredNorm();
    auto [it, inserted] = best.try_emplace(key, Best{kept.size(), d2});
    if (inserted) {
      kept.push_back(i);
    } else if (d2 < it->second.squared_distance) {
      it->second.squared_distance = d2;
      kept[it->second.slot] = i;
    }
  }
  return kept;
}

PointCloud UniformSample(const PointCloud& points, float voxel_size_m) {
  PointCloud out;
  const std::vector<std::size_t> kept = UniformSampleIndices(points, voxel_size_m);
  out.reserve(kept.size());
  for (std::size_t i : kept) out.push_back(points[i]);
  return out;
}

}  // namespace hylo::registration
