// The global localizer's raster and its branch-and-bound pyramid (global_map.h).
#include "hylo/localization/global_map.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "hylo/common/option_checks.h"

namespace hylo::localization {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
// Bin 0 starts this far below the lowest 0.1 % of the map's points: terrain a little lower
// than the map's floor (a ditch seen in one scan) still falls into a bin, and a few stray
// points below the ground do not waste the bins.
constexpr double kFloorMarginM = 1.0;
constexpr double kFloorQuantile = 0.001;

float FloorZ(const PointCloud& points) {
  std::vector<float> z;
  z.reserve(points.size());
  for (const Eigen::Vector3f& p : points) z.push_back(p.z());
  const std::size_t k = static_cast<std::size_t>(kFloorQuantile * static_cast<double>(z.size()));
  std::nth_element(z.begin(), z.begin() + static_cast<std::ptrdiff_t>(k), z.end());
  return static_cast<float>(z[k] - kFloorMarginM);
}

GlobalMap::Level EmptyLevel(std::size_t cells) {
  GlobalMap::Level level;
  level.occupancy.assign(cells, 0);
  level.ground_min_m.assign(cells, kInf);
  level.ground_max_m.assign(cells, -kInf);
  return level;
}

// Level k from level k-1: the block of 2^k cells at (x, y) is the union of the four blocks of
// 2^(k-1) cells at (x, y), (x + h, y), (x, y + h), (x + h, y + h); cells past the edge are
// empty.
GlobalMap::Level Coarsen(const GlobalMap::Level& fine, int32_t width, int32_t height, int32_t h) {
  GlobalMap::Level coarse = EmptyLevel(fine.occupancy.size());
  for (int32_t y = 0; y < height; ++y) {
    for (int32_t x = 0; x < width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      for (int32_t dy = 0; dy <= h; dy += h) {
        for (int32_t dx = 0; dx <= h; dx += h) {
          if (x + dx >= width || y + dy >= height) continue;
          const std::size_t j = static_cast<std::size_t>(y + dy) * width + (x + dx);
          coarse.occupancy[i] |= fine.occupancy[j];
          coarse.ground_min_m[i] = std::min(coarse.ground_min_m[i], fine.ground_min_m[j]);
          coarse.ground_max_m[i] = std::max(coarse.ground_max_m[i], fine.ground_max_m[j]);
        }
      }
    }
  }
  return coarse;
}

}  // namespace

bool GlobalMapOptions::IsValid(std::string* why) const {
  return CheckPositive("cell_m", cell_m, why) && CheckPositive("z_bin_m", z_bin_m, why) &&
         CheckAtLeast("levels", levels, 1, "", why) &&
         (levels <= 12 || FailOption("levels", levels, "must be <= 12", why)) &&
         CheckPositive("max_cells_million", max_cells_million, why);
}

int GlobalMap::ZBin(double z_m) const {
  return static_cast<int>(std::floor((z_m - layout_.z0_m) / layout_.options.z_bin_m));
}

GlobalMap GlobalMap::Build(const PointCloud& points_map, const GlobalMapOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("global map options: " + why);
  const PointCloud points = FinitePoints(points_map);
  if (points.empty()) throw std::invalid_argument("global map: the map has no finite point");
  Eigen::AlignedBox2f box;
  for (const Eigen::Vector3f& p : points) box.extend(p.head<2>());
  GlobalMap map;
  Layout& layout = map.layout_;
  layout.options = options;
  layout.origin_x_m = box.min().x();
  layout.origin_y_m = box.min().y();
  layout.z0_m = FloorZ(points);
  const double width = std::floor(box.sizes().x() / options.cell_m) + 1.0;
  const double height = std::floor(box.sizes().y() / options.cell_m) + 1.0;
  if (width * height > options.max_cells_million * 1e6) {
    std::ostringstream os;
    os << "global map: the map spans " << box.sizes().x() << " m x " << box.sizes().y()
       << " m, " << width * height / 1e6 << " million cells of " << options.cell_m
       << " m, more than max_cells_million = " << options.max_cells_million;
    throw std::invalid_argument(os.str());
  }
  layout.width = static_cast<int32_t>(width);
  layout.height = static_cast<int32_t>(height);
  layout.num_points = points.size();

  Level base = EmptyLevel(static_cast<std::size_t>(layout.width) * layout.height);
  const float inv_cell = static_cast<float>(1.0 / options.cell_m);
  for (const Eigen::Vector3f& p : points) {
    const int bin = map.ZBin(p.z());
    if (bin < 0) continue;
    const int32_t x = std::min(layout.width - 1, static_cast<int32_t>((p.x() - layout.origin_x_m) *
                                                                      inv_cell));
    const int32_t y = std::min(layout.height - 1, static_cast<int32_t>((p.y() - layout.origin_y_m) *
                                                                       inv_cell));
    const std::size_t i = static_cast<std::size_t>(y) * layout.width + x;
    base.ground_min_m[i] = std::min(base.ground_min_m[i], p.z());
    base.ground_max_m[i] = base.ground_min_m[i];
    if (bin >= kZBins) {
      ++layout.num_points_above;
      continue;
    }
    base.occupancy[i] |= uint64_t{1} << bin;
  }
  map.levels_.push_back(std::move(base));
  for (int k = 1; k < options.levels; ++k) {
    map.levels_.push_back(Coarsen(map.levels_.back(), layout.width, layout.height, 1 << (k - 1)));
  }
  return map;
}

std::size_t GlobalMap::MemoryBytes() const {
  std::size_t bytes = sizeof(*this);
  for (const Level& level : levels_) {
    bytes += level.occupancy.capacity() * sizeof(uint64_t) +
             (level.ground_min_m.capacity() + level.ground_max_m.capacity()) * sizeof(float);
  }
  return bytes;
}

}  // namespace hylo::localization
