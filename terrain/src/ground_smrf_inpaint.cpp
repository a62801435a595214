#include "hylo/terrain/ground_smrf_inpaint.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "hylo/common/check.h"

namespace hylo::terrain::smrf {
namespace {

// Relaxation per level: successive over-relaxation (Gauss-Seidel pushed 1.5 times as far).
// The coarse solution already carries the large-scale shape; the sweeps only remove the error
// of interpolating it up. A plane across a 30 x 25 cell gap comes back within 1.4 cm with 10
// sweeps (plain Gauss-Seidel needs 30 for 1.1 cm; 10 leave 6 cm).
constexpr int kSweepsPerLevel = 10;
constexpr float kOverRelaxation = 1.5f;

struct Grid {
  int cols = 0, rows = 0;
  std::vector<float> z;  // NaN = unknown
  std::size_t Index(int col, int row) const { return static_cast<std::size_t>(row) * cols + col; }
};

// Half the resolution: a coarse cell is the mean of the known cells among its (up to) four.
Grid Coarsen(const Grid& fine) {
  Grid coarse;
  coarse.cols = (fine.cols + 1) / 2;
  coarse.rows = (fine.rows + 1) / 2;
  coarse.z.assign(static_cast<std::size_t>(coarse.cols) * coarse.rows,
                  std::numeric_limits<float>::quiet_NaN());
  for (int row = 0; row < coarse.rows; ++row) {
    for (int col = 0; col < coarse.cols; ++col) {
      double sum = 0.0;
      int count = 0;
      for (int r = 2 * row; r < std::min(2 * row + 2, fine.rows); ++r) {
        for (int c = 2 * col; c < std::min(2 * col + 2, fine.cols); ++c) {
          const float v = fine.z[fine.Index(c, r)];
          if (std::isnan(v)) continue;
          sum += v;
          ++count;
        }
      }
      if (count > 0) coarse.z[coarse.Index(col, row)] = static_cast<float>(sum / count);
    }
  }
  return coarse;
}

// The coarse grid's value at the centre of fine cell (col, row), bilinear between coarse
// centres (fine cell c's centre is at coarse coordinate c / 2 - 0.25 in centre units).
float Prolong(const Grid& coarse, int col, int row) {
  const auto bracket = [](int fine, int count, int* i0, int* i1, float* w) {
    const float u = std::clamp(0.5f * fine - 0.25f, 0.f, static_cast<float>(count - 1));
    *i0 = std::min(static_cast<int>(u), count - 1);
    *i1 = std::min(*i0 + 1, count - 1);
    *w = u - *i0;
  };
  int c0, c1, r0, r1;
  float wx, wy;
  bracket(col, coarse.cols, &c0, &c1, &wx);
  bracket(row, coarse.rows, &r0, &r1, &wy);
  const float bottom =
      (1 - wx) * coarse.z[coarse.Index(c0, r0)] + wx * coarse.z[coarse.Index(c1, r0)];
  const float top = (1 - wx) * coarse.z[coarse.Index(c0, r1)] + wx * coarse.z[coarse.Index(c1, r1)];
  return (1 - wy) * bottom + wy * top;
}

// Over-relaxed Gauss-Seidel on the Laplace equation over the unknown cells, row-major.
void Relax(const std::vector<uint8_t>& known, Grid* grid) {
  const int cols = grid->cols, rows = grid->rows;
  float* z = grid->z.data();
  for (int sweep = 0; sweep < kSweepsPerLevel; ++sweep) {
    for (int row = 0; row < rows; ++row) {
      for (int col = 0; col < cols; ++col) {
        const std::size_t i = static_cast<std::size_t>(row) * cols + col;
        if (known[i]) continue;
        float sum = 0.f;
        int count = 0;
        if (col > 0) sum += z[i - 1], ++count;
        if (col + 1 < cols) sum += z[i + 1], ++count;
        if (row > 0) sum += z[i - cols], ++count;
        if (row + 1 < rows) sum += z[i + cols], ++count;
        if (count > 0) z[i] += kOverRelaxation * (sum / count - z[i]);
      }
    }
  }
}

// Fills `grid` (at least one known cell) and returns the number of cells filled.
std::size_t Fill(Grid* grid) {
  std::vector<uint8_t> known(grid->z.size());
  std::size_t num_unknown = 0;
  for (std::size_t i = 0; i < grid->z.size(); ++i) {
    known[i] = !std::isnan(grid->z[i]);
    num_unknown += !known[i];
  }
  if (num_unknown == 0) return 0;
  Grid coarse = Coarsen(*grid);
  Fill(&coarse);  // smaller than *grid: an unknown cell makes it at least 2 cells
  for (int row = 0; row < grid->rows; ++row) {
    for (int col = 0; col < grid->cols; ++col) {
      const std::size_t i = grid->Index(col, row);
      if (!known[i]) grid->z[i] = Prolong(coarse, col, row);
    }
  }
  Relax(known, grid);
  return num_unknown;
}

}  // namespace

std::size_t InpaintMembrane(Raster* raster) {
  HYLO_CHECK(raster != nullptr && raster->z.size() == raster->Size(), "one value per cell");
  const bool any_known =
      std::any_of(raster->z.begin(), raster->z.end(), [](float v) { return !std::isnan(v); });
  HYLO_CHECK(any_known, "inpainting needs at least one known cell");
  Grid grid{raster->cols, raster->rows, std::move(raster->z)};
  const std::size_t filled = Fill(&grid);
  raster->z = std::move(grid.z);
  return filled;
}

}  // namespace hylo::terrain::smrf
