#pragma once
// Voxel-grid downsampling shared by the scan pre-processing, the dense map of a run, the map
// and map crafting.

#include <cstddef>
#include <memory>
#include <vector>

#include "hylo/common/point_types.h"

namespace hylo::registration {

/// Uniform sampling: per occupied voxel of edge `voxel_size_m`, keep the input point nearest
/// the voxel centre (an original point, not an average, so surfaces are not blurred).
/// Output order follows the first appearance of each voxel in the input. voxel_size_m <= 0
/// returns the input unchanged.
PointCloud UniformSample(const PointCloud& points, float voxel_size_m);

/// Indices (into `points`) of the points UniformSample keeps, for callers carrying attributes.
std::vector<std::size_t> UniformSampleIndices(const PointCloud& points, float voxel_size_m);

/// Uniform sampling of a stream of clouds (a dense map accumulated scan by scan): after any
/// sequence of Add calls, points() is UniformSample of everything added so far, i.e. per voxel
/// the point nearest the voxel centre, the earlier point on ties, in first-appearance order.
/// A flat hash table of voxels, not a spatial index: it answers no neighbour queries, which
/// is what makes an insert a single probe (~50-90 B per kept point).
class UniformSampler {
 public:
  /// `voxel_size_m` must be finite and > 0 (hylo::InternalError otherwise).
  explicit UniformSampler(float voxel_size_m);
  ~UniformSampler();
  UniformSampler(UniformSampler&&) noexcept;
  UniformSampler& operator=(UniformSampler&&) noexcept;

  /// Offers every finite point; returns how many points were skipped: non-finite, or beyond
  /// the voxel indices' int32 range (coordinates over ~2e9 voxels from the origin).
  std::size_t Add(const PointCloud& points);
  const PointCloud& points() const { return points_; }
  std::size_t MemoryBytes() const;

 private:
  class Table;
  std::unique_ptr<Table> table_;
  PointCloud points_;
  float voxel_size_m_;
};

}  // namespace hylo::registration
