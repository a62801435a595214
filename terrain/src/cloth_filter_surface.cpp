#include "hylo/terrain/cloth_filter_surface.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <unordered_map>
#include <utility>

#include "hylo/common/check.h"

namespace hylo::terrain::cloth {
namespace {
constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
constexpr int kNeighbourCol[4] = {1, -1, 0, 0};
constexpr int kNeighbourRow[4] = {0, 0, 1, -1};
}  // namespace

InvertedSurface RasterizeInvertedSurface(const ClothGrid& grid, const PointCloud& points_inverted,
                                         ClothHoleFill hole_fill) {
  InvertedSurface surface;
  surface.height_m.assign(grid.Size(), kUnknown);
  std::vector<double> best_distance2(grid.Size(), std::numeric_limits<double>::infinity());
  for (const Eigen::Vector3f& p : points_inverted) {
    const Eigen::Vector2d cell = (p.head<2>().cast<double>() - grid.origin_xy) / grid.resolution_m;
    const int col = static_cast<int>(std::lround(cell.x()));
    const int row = static_cast<int>(std::lround(cell.y()));
    if (!grid.Contains(col, row)) continue;
    const double distance2 = (cell - Eigen::Vector2d(col, row)).squaredNorm();
    const std::size_t index = grid.Index(col, row);
    if (distance2 < best_distance2[index]) {
      best_distance2[index] = distance2;
      surface.height_m[index] = p.z();
    }
  }
  switch (hole_fill) {
    case ClothHoleFill::kNeighbourMean:
      surface.num_filled_holes = FillHoles(grid, &surface.height_m);
      break;
    case ClothHoleFill::kNearest:
      surface.num_filled_holes = FillHolesFromNearest(grid, &surface.height_m);
      break;
    case ClothHoleFill::kReferenceScanline:
      surface.num_filled_holes = FillHolesAsReference(grid, &surface.height_m);
      break;
  }
  return surface;
}

// Nearest-source propagation (a Dijkstra sweep over the 8-neighbour grid): every particle
// remembers the known particle its value comes from and passes it on while that source is
// nearer than what the neighbour has. Exact but for rare cells in the Voronoi corners, where a
// source one cell farther may win; far below the cloth's resolution.
std::size_t FillHolesFromNearest(const ClothGrid& grid, std::vector<double>* height_m) {
  HYLO_CHECK(height_m != nullptr && height_m->size() == grid.Size(), "one height per particle");
  std::vector<double>& height = *height_m;
  const std::size_t count = height.size();
  std::vector<std::size_t> source(count, count);
  std::vector<int64_t> best_distance2(count, std::numeric_limits<int64_t>::max());
  using Entry = std::pair<int64_t, std::size_t>;  // (squared distance in cells, particle)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (std::size_t i = 0; i < count; ++i) {
    if (std::isnan(height[i])) continue;
    source[i] = i;
    best_distance2[i] = 0;
    queue.push({0, i});
  }
  HYLO_CHECK(!queue.empty(), "no point inside the cloth grid");
  while (!queue.empty()) {
    const auto [distance2, i] = queue.top();
    queue.pop();
    if (distance2 > best_distance2[i]) continue;  // a nearer source got here first
    const std::size_t from = source[i];
    const int from_col = static_cast<int>(from % grid.cols);
    const int from_row = static_cast<int>(from / grid.cols);
    const int col = static_cast<int>(i % grid.cols);
    const int row = static_cast<int>(i / grid.cols);
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        const int c = col + dc, r = row + dr;
        if ((dc == 0 && dr == 0) || !grid.Contains(c, r)) continue;
        const std::size_t j = grid.Index(c, r);
        const int64_t d2 =
            int64_t(c - from_col) * (c - from_col) + int64_t(r - from_row) * (r - from_row);
        if (d2 >= best_distance2[j]) continue;
        best_distance2[j] = d2;
        source[j] = from;
        queue.push({d2, j});
      }
    }
  }
  std::size_t filled = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if (source[i] == i) continue;
    height[i] = height[source[i]];
    ++filled;
  }
  return filled;
}

std::size_t FillHoles(const ClothGrid& grid, std::vector<double>* height_m) {
  HYLO_CHECK(height_m != nullptr && height_m->size() == grid.Size(), "one height per particle");
  std::vector<double>& height = *height_m;
  std::vector<std::size_t> frontier;
  for (std::size_t i = 0; i < height.size(); ++i) {
    if (!std::isnan(height[i])) frontier.push_back(i);
  }
  HYLO_CHECK(!frontier.empty(), "no point inside the cloth grid");
  std::size_t filled = 0;
  std::vector<uint8_t> queued(height.size(), 0);
  while (!frontier.empty()) {
    // The next ring: unknown particles touching the current frontier.
    std::vector<std::size_t> ring;
    for (const std::size_t i : frontier) {
      const int col = static_cast<int>(i % grid.cols);
      const int row = static_cast<int>(i / grid.cols);
      for (int k = 0; k < 4; ++k) {
        const int c = col + kNeighbourCol[k];
        const int r = row + kNeighbourRow[k];
        if (!grid.Contains(c, r)) continue;
        const std::size_t j = grid.Index(c, r);
        if (std::isnan(height[j]) && !queued[j]) {
          queued[j] = 1;
          ring.push_back(j);
        }
      }
    }
    // Mean of known neighbours, computed for the whole ring before writing any, so the
    // result does not depend on the visiting order.
    std::vector<double> values(ring.size(), 0.0);
    for (std::size_t n = 0; n < ring.size(); ++n) {
      const int col = static_cast<int>(ring[n] % grid.cols);
      const int row = static_cast<int>(ring[n] / grid.cols);
      double sum = 0.0;
      int count = 0;
      for (int k = 0; k < 4; ++k) {
        const int c = col + kNeighbourCol[k];
        const int r = row + kNeighbourRow[k];
        if (!grid.Contains(c, r) || std::isnan(height[grid.Index(c, r)])) continue;
        sum += height[grid.Index(c, r)];
        ++count;
      }
      values[n] = sum / count;  // count >= 1: the particle touches the frontier
    }
    for (std::size_t n = 0; n < ring.size(); ++n) height[ring[n]] = values[n];
    filled += ring.size();
    frontier.swap(ring);
  }
  return filled;
}

namespace {

// For every particle of a line (`count` particles, the k-th at index first + k * stride), the
// height of the first measured particle after it (`forward`) or before it (otherwise) on that
// line; NaN when there is none.
void ScanLine(const std::vector<double>& measured, std::size_t first, std::size_t stride, int count,
              bool forward, std::vector<double>* found) {
  double last = kUnknown;
  for (int k = 0; k < count; ++k) {
    const int step = forward ? count - 1 - k : k;
    const std::size_t i = first + static_cast<std::size_t>(step) * stride;
    (*found)[i] = last;
    if (!std::isnan(measured[i])) last = measured[i];
  }
}

}  // namespace

// The reference implementation (jianboqi/CSF) fills a particle without points with the height
// of the first measured particle found scanning its row towards +x, else towards -x, else its
// column towards -y, else towards +y. Under large gaps (water, occlusions) this extends the
// terrain at the gap's edge flat across it, so that the cloth rests there instead of sagging.
std::size_t FillHolesAsReference(const ClothGrid& grid, std::vector<double>* height_m) {
  HYLO_CHECK(height_m != nullptr && height_m->size() == grid.Size(), "one height per particle");
  const std::vector<double> measured = *height_m;
  std::vector<double> plus_x(grid.Size()), minus_x(grid.Size());
  std::vector<double> plus_y(grid.Size()), minus_y(grid.Size());
  for (int row = 0; row < grid.rows; ++row) {
    const std::size_t first = grid.Index(0, row);
    ScanLine(measured, first, 1, grid.cols, true, &plus_x);
    ScanLine(measured, first, 1, grid.cols, false, &minus_x);
  }
  for (int col = 0; col < grid.cols; ++col) {
    const std::size_t first = grid.Index(col, 0);
    ScanLine(measured, first, grid.cols, grid.rows, true, &plus_y);
    ScanLine(measured, first, grid.cols, grid.rows, false, &minus_y);
  }
  std::vector<double>& height = *height_m;
  std::size_t filled = 0;
  for (std::size_t i = 0; i < height.size(); ++i) {
    if (!std::isnan(measured[i])) continue;
    for (const std::vector<double>* scan : {&plus_x, &minus_x, &minus_y, &plus_y}) {
      if (std::isnan(height[i])) height[i] = (*scan)[i];
    }
    ++filled;
  }
  HYLO_CHECK(filled < height.size(), "no point inside the cloth grid");
  // Holes whose row and column hold no measured particle (a few points in a large, nearly
  // empty grid) take the nearest filled value.
  FillHolesFromNearest(grid, height_m);
  return filled;
}

// Low outliers (multipath returns, metres or tens of metres below the terrain, as in the ISPRS
// samples 31 and 41) are spikes in the inverted cloud: the cloth lands on them first and hangs
// there, tented over the terrain around them. Not in the paper; an addition of ours.
// A point is one when fewer than `min_support` other points of its 3x3 block of cells, or fewer
// than `max_fraction` of them, reach within `depth_m` of it (inverted: are no more than depth_m
// below it). The fraction catches clusters of multipath returns (samp41: ~30 points 30 m under
// a building) that support each other, and, unlike a count, it means the same at 0.2 and at
// 5 points/m^2. Counting uses one sorted height list per cell: a few binary searches per point.
std::vector<uint8_t> FindLowOutliers(const PointCloud& points_inverted, double cell_m,
                                     double depth_m, int min_support, double max_fraction) {
  HYLO_CHECK(cell_m > 0.0 && depth_m > 0.0 && min_support >= 1, "outlier parameters");
  HYLO_CHECK(max_fraction >= 0.0 && max_fraction < 1.0, "outlier fraction in [0, 1)");
  const auto key = [cell_m](float x, float y) {
    const int64_t cx = static_cast<int64_t>(std::floor(x / cell_m));
    const int64_t cy = static_cast<int64_t>(std::floor(y / cell_m));
    return std::make_pair(cx, cy);
  };
  // Shifted as unsigned: shifting a negative cell index left is undefined behaviour.
  const auto pack = [](int64_t cx, int64_t cy) {
    return static_cast<int64_t>((static_cast<uint64_t>(cx) << 32) ^
                                (static_cast<uint64_t>(cy) & 0xffffffffULL));
  };
  std::unordered_map<int64_t, std::vector<float>> heights;
  for (const Eigen::Vector3f& p : points_inverted) {
    const auto [cx, cy] = key(p.x(), p.y());
    heights[pack(cx, cy)].push_back(p.z());
  }
  for (auto& entry : heights) std::sort(entry.second.begin(), entry.second.end());
  std::vector<uint8_t> outlier(points_inverted.size(), 0);
  for (std::size_t i = 0; i < points_inverted.size(); ++i) {
    const Eigen::Vector3f& p = points_inverted[i];
    const auto [cx, cy] = key(p.x(), p.y());
    const float floor_z = static_cast<float>(p.z() - depth_m);
    int support = -1;  // the point itself is counted below, in both
    int others = -1;
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        const auto it = heights.find(pack(cx + dx, cy + dy));
        if (it == heights.end()) continue;
        const std::vector<float>& z = it->second;
        support += static_cast<int>(z.end() - std::lower_bound(z.begin(), z.end(), floor_z));
        others += static_cast<int>(z.size());
      }
    }
    outlier[i] = support < min_support || support < max_fraction * others;
  }
  return outlier;
}

}  // namespace hylo::terrain::cloth
