#pragma once
// The crafted map as a 3-D occupancy structure for line-of-sight tests: a dense bit grid of
// voxels over the box where sight lines can run (cameras and targets), each voxel blocked when
// a map point lies in it or within the clearance of one.
//
// Only occupied space is known: the crafted map holds surfaces, not the free space the lidar
// saw (an OctoMap would need the scans and poses, which `hylo craft` no longer has). A gap in
// the map narrower than twice the clearance is closed by the inflation; a wider one reads as
// free. Voxels follow the project's voxel rule (common/voxel_key.h): a point belongs to voxel
// floor(p / edge), so the grid's corner lies on a multiple of the edge.
//
// Inflation by the clearance c: a voxel is blocked when some point of it lies closer than c
// to some point of an occupied voxel. A sight line that enters no blocked voxel therefore
// passes every map point at c or more; a line blocked by the grid passes some map point within
// c + 2 sqrt(3) edge (`BlockedReach`): that band is the tolerance of every test against a
// truth.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/common/voxel_key.h"

namespace hylo::inspection {

struct OccupancyOptions {
  double voxel_size_m = 0.1;      ///< voxel edge, m
  double clearance_m = 0.15;      ///< sight lines keep at least this from every map point:
                                  ///< the map's noise plus the camera's pose uncertainty on
                                  ///< the spot, m
  int max_voxels_million = 1000;  ///< refuse larger grids (1000 M voxels = 125 MB), million

  /// True when usable; otherwise `why` names the field, its value and the constraint.
  bool IsValid(std::string* why) const;
  /// Farthest a point of a blocked voxel can be from the map point that blocked it, m:
  /// clearance_m + 2 sqrt(3) voxel_size_m.
  double BlockedReach() const;
};

/// What building the grid saw.
struct OccupancySummary {
  std::size_t points_in_box = 0;     ///< map points inside the grid's box
  std::size_t occupied_voxels = 0;   ///< voxels holding a point
  std::size_t blocked_voxels = 0;    ///< after inflation
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();  ///< voxels along x, y, z
};

class OccupancyGrid {
 public:
  OccupancyGrid() = default;

  /// Voxelizes the points of `map_local` inside [box_min, box_max] (grown by the inflation,
  /// so points just outside still block lines inside) and inflates them by the clearance.
  /// Throws std::invalid_argument for invalid options and std::runtime_error when the grid
  /// would exceed max_voxels_million, naming its size.
  static OccupancyGrid Build(const PointCloud& map_local, const Eigen::Vector3d& box_min,
                             const Eigen::Vector3d& box_max, const OccupancyOptions& options);

  /// Blocked voxel? Voxels outside the grid are free (no map point there matters).
  bool Blocked(const Eigen::Vector3i& voxel) const {
    return Contains(voxel) && TestBit(LinearIndex(voxel));
  }
  bool Contains(const Eigen::Vector3i& voxel) const {
    return (voxel.array() >= 0).all() && (voxel.array() < dims_.array()).all();
  }
  std::size_t LinearIndex(const Eigen::Vector3i& voxel) const {
    return (static_cast<std::size_t>(voxel.z()) * dims_.y() + voxel.y()) * row_stride_ + voxel.x();
  }
  bool TestBit(std::size_t index) const { return (bits_[index >> 6] >> (index & 63)) & 1u; }

  /// Bricks of kBrick^3 voxels: brick b holds voxels [kBrick b, kBrick (b + 1)) per axis.
  static constexpr int kBrick = 8;
  const Eigen::Vector3i& brick_dims() const { return brick_dims_; }
  /// True when the brick holds a blocked voxel (`brick` inside brick_dims()).
  bool BrickBlocked(const Eigen::Vector3i& brick) const {
    const std::size_t i =
        (static_cast<std::size_t>(brick.z()) * brick_dims_.y() + brick.y()) * brick_dims_.x() +
        brick.x();
    return (brick_bits_[i >> 6] >> (i & 63)) & 1u;
  }

  /// Continuous voxel coordinates of a local point: voxel v spans [v, v + 1) per axis.
  Eigen::Vector3d ToVoxelCoordinates(const Eigen::Vector3d& point_local) const {
    return (point_local - min_corner_) / voxel_size_;
  }
  const Eigen::Vector3i& dims() const { return dims_; }
  double voxel_size() const { return voxel_size_; }
  const Eigen::Vector3d& min_corner() const { return min_corner_; }
  const OccupancySummary& summary() const { return summary_; }

 private:
  void SetBit(std::size_t index) { bits_[index >> 6] |= uint64_t{1} << (index & 63); }

  void MarkBricks();

  Eigen::Vector3i dims_ = Eigen::Vector3i::Zero();
  Eigen::Vector3d min_corner_ = Eigen::Vector3d::Zero();  ///< local position of voxel (0,0,0)
  double voxel_size_ = 0.1;
  std::size_t row_stride_ = 0;  ///< bits per row: dims_.x() rounded up to 64, so a word of
                                ///< bits_ never spans two rows
  std::vector<uint64_t> bits_;  ///< blocked voxels, x fastest
  Eigen::Vector3i brick_dims_ = Eigen::Vector3i::Zero();
  std::vector<uint64_t> brick_bits_;  ///< bricks holding a blocked voxel
  OccupancySummary summary_;
};

}  // namespace hylo::inspection
