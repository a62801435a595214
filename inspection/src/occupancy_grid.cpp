#include "hylo/inspection/occupancy_grid.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include "hylo/common/option_checks.h"

namespace hylo::inspection {
namespace {

std::size_t Words(std::size_t bits) { return (bits + 63) / 64; }

// Offsets (in voxels) of the voxels that come closer than the clearance to a voxel: the
// smallest distance between two voxels offset by o is edge * |max(|o| - 1, 0)| (per axis).
std::vector<Eigen::Vector3i> BallOffsets(double clearance_m, double voxel_m) {
  const double k = clearance_m / voxel_m;
  const int r = 1 + static_cast<int>(std::floor(k + 1e-9));
  const auto gap = [](int o) { return std::max(std::abs(o) - 1, 0); };
  std::vector<Eigen::Vector3i> offsets;
  for (int z = -r; z <= r; ++z) {
    for (int y = -r; y <= r; ++y) {
      for (int x = -r; x <= r; ++x) {
        const int g2 = gap(x) * gap(x) + gap(y) * gap(y) + gap(z) * gap(z);
        if ((x == 0 && y == 0 && z == 0) || g2 < k * k - 1e-9) offsets.emplace_back(x, y, z);
      }
    }
  }
  return offsets;
}

}  // namespace

bool OccupancyOptions::IsValid(std::string* why) const {
  return CheckPositive("voxel_size_m", voxel_size_m, why) &&
         CheckNonNegative("clearance_m", clearance_m, why) &&
         (clearance_m <= 20.0 * voxel_size_m ||
          FailOption("clearance_m", clearance_m, "must be <= 20 x voxel_size_m", why)) &&
         CheckAtLeast("max_voxels_million", max_voxels_million, 1, "", why);
}

double OccupancyOptions::BlockedReach() const {
  return clearance_m + 2.0 * std::sqrt(3.0) * voxel_size_m;
}

OccupancyGrid OccupancyGrid::Build(const PointCloud& map_local, const Eigen::Vector3d& box_min,
                                   const Eigen::Vector3d& box_max,
                                   const OccupancyOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("occupancy options: " + why);
  OccupancyGrid grid;
  const float v = static_cast<float>(options.voxel_size_m);
  grid.voxel_size_ = options.voxel_size_m;
  if (!box_min.allFinite() || !box_max.allFinite() || (box_max.array() < box_min.array()).any())
    return grid;  // nothing to look through
  // Grown so that a point outside the grid cannot block a voxel that a line inside the box
  // crosses (a blocked voxel lies within BlockedReach of its point).
  const Eigen::Vector3d margin = Eigen::Vector3d::Constant(options.BlockedReach() + v);
  const VoxelKey lo = VoxelOf((box_min - margin).cast<float>(), v);
  const VoxelKey hi = VoxelOf((box_max + margin).cast<float>(), v);
  const Eigen::Matrix<int64_t, 3, 1> dims = hi - lo + VoxelKey::Ones();
  const double total = static_cast<double>(dims.x()) * dims.y() * dims.z();
  if (total > options.max_voxels_million * 1e6) {
    std::ostringstream os;
    os << "the sight lines span " << dims.x() * v << " m x " << dims.y() * v << " m x "
       << dims.z() * v << " m: " << total / 1e6 << " million voxels of " << v
       << " m exceed max_voxels_million = " << options.max_voxels_million
       << " (use a coarser voxel_size_m or fewer, closer targets)";
    throw std::runtime_error(os.str());
  }
  grid.dims_ = dims.cast<int>();
  grid.min_corner_ = lo.cast<double>() * options.voxel_size_m;
  grid.row_stride_ = Words(grid.dims_.x()) * 64;
  const std::size_t rows = static_cast<std::size_t>(grid.dims_.y()) * grid.dims_.z();
  std::vector<uint64_t> occupied(rows * grid.row_stride_ / 64, 0);
  for (const Eigen::Vector3f& p : map_local) {
    if (!p.allFinite()) continue;
    const Eigen::Vector3i voxel = (VoxelOf(p, v) - lo).cast<int>();
    if (!grid.Contains(voxel)) continue;
    const std::size_t index = grid.LinearIndex(voxel);
    ++grid.summary_.points_in_box;
    occupied[index >> 6] |= uint64_t{1} << (index & 63);
  }
  grid.bits_.assign(occupied.size(), 0);
  const std::vector<Eigen::Vector3i> ball = BallOffsets(options.clearance_m, options.voxel_size_m);
  const std::size_t words_per_row = grid.row_stride_ / 64;
  for (std::size_t w = 0; w < occupied.size(); ++w) {
    if (occupied[w] == 0) continue;
    const std::size_t row = w / words_per_row;
    const int x0 = static_cast<int>((w % words_per_row) * 64);
    const int y = static_cast<int>(row % grid.dims_.y()), z = static_cast<int>(row / grid.dims_.y());
    for (uint64_t word = occupied[w]; word != 0; word &= word - 1) {
      ++grid.summary_.occupied_voxels;
      const Eigen::Vector3i at(x0 + __builtin_ctzll(word), y, z);
      for (const Eigen::Vector3i& offset : ball) {
        const Eigen::Vector3i voxel = at + offset;
        if (grid.Contains(voxel)) grid.SetBit(grid.LinearIndex(voxel));
      }
    }
  }
  for (const uint64_t word : grid.bits_) grid.summary_.blocked_voxels += __builtin_popcountll(word);
  grid.summary_.dims = grid.dims_;
  grid.MarkBricks();
  return grid;
}

void OccupancyGrid::MarkBricks() {
  brick_dims_ = (dims_.array() + kBrick - 1) / kBrick;
  const std::size_t bricks = static_cast<std::size_t>(brick_dims_.prod());
  brick_bits_.assign(Words(bricks), 0);
  const std::size_t words_per_row = row_stride_ / 64;
  for (std::size_t w = 0; w < bits_.size(); ++w) {
    if (bits_[w] == 0) continue;
    const std::size_t row = w / words_per_row;
    const std::size_t by = row % dims_.y() / kBrick, bz = row / dims_.y() / kBrick;
    for (int byte = 0; byte < 8; ++byte) {  // a byte of a row's word is one brick along x
      if (((bits_[w] >> (8 * byte)) & 0xff) == 0) continue;
      const std::size_t bx = ((w % words_per_row) * 64 + 8 * byte) / kBrick;
      const std::size_t i = (bz * brick_dims_.y() + by) * brick_dims_.x() + bx;
      brick_bits_[i >> 6] |= uint64_t{1} << (i & 63);
    }
  }
}

}  // namespace hylo::inspection
