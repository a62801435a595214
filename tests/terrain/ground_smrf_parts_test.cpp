// SMRF's parts on small grids: the octagon morphology against brute force, the membrane and
// tangent-plane inpainting against surfaces they must reproduce, the progressive filter on shapes
// whose answer is known, and the raster's interpolation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "hylo/common/check.h"
#include "hylo/terrain/ground_smrf_dem.h"
#include "hylo/terrain/ground_smrf_inpaint.h"
#include "hylo/terrain/ground_smrf_morphology.h"
#include "hylo/terrain/ground_smrf_raster.h"

namespace hylo::terrain::smrf {
namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

// Offset (dc, dr) is in H(a) + V(a) + D1(b) + D2(b) when some s, t in [-b, b] leave a
// remainder within the square of half-side a.
bool OctagonContains(const Octagon& o, int dc, int dr) {
  for (int s = -o.diagonal; s <= o.diagonal; ++s) {
    for (int t = -o.diagonal; t <= o.diagonal; ++t) {
      if (std::abs(dc - s - t) <= o.axis && std::abs(dr - s + t) <= o.axis) return true;
    }
  }
  return false;
}

std::vector<float> BruteForce(int cols, int rows, const Octagon& o, const std::vector<float>& z,
                              bool erode) {
  const int reach = o.axis + 2 * o.diagonal;
  std::vector<float> out(z.size());
  for (int row = 0; row < rows; ++row) {
    for (int col = 0; col < cols; ++col) {
      float best =
          erode ? std::numeric_limits<float>::infinity() : -std::numeric_limits<float>::infinity();
      for (int dr = -reach; dr <= reach; ++dr) {
        for (int dc = -reach; dc <= reach; ++dc) {
          const int c = col + dc, r = row + dr;
          if (c < 0 || r < 0 || c >= cols || r >= rows || !OctagonContains(o, dc, dr)) continue;
          const float v = z[static_cast<std::size_t>(r) * cols + c];
          best = erode ? std::min(best, v) : std::max(best, v);
        }
      }
      out[static_cast<std::size_t>(row) * cols + col] = best;
    }
  }
  return out;
}

std::vector<float> RandomGrid(int cols, int rows, std::mt19937* rng) {
  std::uniform_real_distribution<float> u(-5.f, 5.f);
  std::vector<float> z(static_cast<std::size_t>(cols) * rows);
  for (float& v : z) v = u(*rng);
  return z;
}

TEST(SmrfMorphology, OctagonReachesTheRadiusAlongTheAxesAndIsSolid) {
  for (int k = 1; k <= 30; ++k) {
    const Octagon o = OctagonForRadius(k);
    EXPECT_EQ(o.axis + 2 * o.diagonal, k);
    EXPECT_GE(o.axis, 1);
    // Along the diagonal within 0.71 cells of the disk's radius (radius 2: a 5 x 5 square).
    EXPECT_NEAR(std::sqrt(2.0) * (o.axis + o.diagonal), k, k == 2 ? 0.83 : 0.71) << k;
    for (int d = -k; d <= k; ++d) EXPECT_TRUE(OctagonContains(o, d, 0)) << k << " " << d;
  }
  EXPECT_THROW(OctagonForRadius(0), InternalError);
}

TEST(SmrfMorphology, ErosionAndDilationMatchBruteForce) {
  std::mt19937 rng(7);
  const int sizes[][2] = {{1, 1}, {1, 9}, {9, 1}, {7, 13}, {25, 16}, {40, 3}};
  for (const auto& size : sizes) {
    for (int k = 1; k <= 9; ++k) {
      const int cols = size[0], rows = size[1];
      const Octagon o = OctagonForRadius(k);
      const std::vector<float> z = RandomGrid(cols, rows, &rng);
      std::vector<float> eroded = z, dilated = z;
      Erode(cols, rows, o, &eroded);
      Dilate(cols, rows, o, &dilated);
      EXPECT_EQ(eroded, BruteForce(cols, rows, o, z, true)) << cols << "x" << rows << " r" << k;
      EXPECT_EQ(dilated, BruteForce(cols, rows, o, z, false)) << cols << "x" << rows << " r" << k;
    }
  }
}

TEST(SmrfMorphology, OpeningIsBelowTheSurfaceAndIdempotent) {
  std::mt19937 rng(3);
  const int cols = 31, rows = 22;
  const std::vector<float> z = RandomGrid(cols, rows, &rng);
  for (int k = 1; k <= 6; ++k) {
    std::vector<float> once = z;
    Open(cols, rows, OctagonForRadius(k), &once);
    std::vector<float> twice = once;
    Open(cols, rows, OctagonForRadius(k), &twice);
    EXPECT_EQ(once, twice);
    for (std::size_t i = 0; i < z.size(); ++i) ASSERT_LE(once[i], z[i]);
  }
}

Raster Flat(int cols, int rows, float z) {
  Raster raster = CoveringRaster({0, 0}, {cols - 0.5, rows - 0.5}, 1.0);
  std::fill(raster.z.begin(), raster.z.end(), z);
  return raster;
}

TEST(SmrfProgressiveFilter, FlagsABuildingNarrowerThanTheWindowOnly) {
  Raster surface = Flat(60, 60, 0.f);
  for (int row = 10; row < 20; ++row) {  // 10 x 10 m, 6 m high
    for (int col = 10; col < 20; ++col) surface.z[surface.Index(col, row)] = 6.f;
  }
  for (int row = 30; row < 60; ++row) {  // 30 x 30 m plateau at the corner
    for (int col = 30; col < 60; ++col) surface.z[surface.Index(col, row)] = 6.f;
  }
  const std::vector<uint8_t> object = ProgressiveFilter(surface, 0.15, 8);
  EXPECT_TRUE(object[surface.Index(15, 15)]);
  EXPECT_TRUE(object[surface.Index(10, 10)]);
  EXPECT_FALSE(object[surface.Index(45, 45)]);  // wider than 2 x 8 cells: terrain
  EXPECT_FALSE(object[surface.Index(5, 40)]);
  EXPECT_FALSE(object[surface.Index(40, 5)]);
}

// The surface continues flat beyond the border: a slope rising to the edge of the data is not
// a raised object there (with the windows cut at the border it was, by slope x radius).
TEST(SmrfProgressiveFilter, SlopesRunningOffTheGridAreNotFlagged) {
  Raster surface = Flat(50, 40, 0.f);
  for (int row = 0; row < surface.rows; ++row) {
    for (int col = 0; col < surface.cols; ++col) {
      surface.z[surface.Index(col, row)] = 0.7f * col + 0.3f * row;  // 35 deg along x
    }
  }
  const std::vector<uint8_t> object = ProgressiveFilter(surface, 0.15, 12);
  // Only the highest corner may go: continued flat along both edges it is the convex corner
  // of a plateau, which an opening rounds off.
  EXPECT_LE(std::count(object.begin(), object.end(), 1), 1);
  EXPECT_FALSE(object[surface.Index(surface.cols - 2, surface.rows - 2)]);
}

TEST(SmrfInpaint, ReproducesAPlaneAcrossAGap) {
  Raster raster = CoveringRaster({0, 0}, {79.5, 49.5}, 1.0);
  for (int row = 0; row < raster.rows; ++row) {
    for (int col = 0; col < raster.cols; ++col) {
      const bool gap = col >= 20 && col < 50 && row >= 10 && row < 35;
      raster.z[raster.Index(col, row)] = gap ? kNan : 0.3f * col - 0.1f * row + 5.f;
    }
  }
  EXPECT_EQ(InpaintMembrane(&raster), 30u * 25u);
  double worst = 0;
  for (int row = 0; row < raster.rows; ++row) {
    for (int col = 0; col < raster.cols; ++col) {
      const double truth = 0.3 * col - 0.1 * row + 5.0;
      worst = std::max(worst, std::abs(raster.z[raster.Index(col, row)] - truth));
    }
  }
  EXPECT_LT(worst, 0.02) << "a plane is harmonic: the membrane must reproduce it";
}

TEST(SmrfInpaint, StaysWithinTheKnownRangeAndKeepsKnownCells) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  Raster raster = CoveringRaster({0, 0}, {63.5, 40.5}, 1.0);
  std::vector<float> known(raster.Size(), kNan);
  for (std::size_t i = 0; i < raster.Size(); ++i) {
    if (u(rng) < 0.1f) known[i] = raster.z[i] = 10.f * u(rng);
  }
  InpaintMembrane(&raster);
  for (std::size_t i = 0; i < raster.Size(); ++i) {
    if (!std::isnan(known[i])) {
      ASSERT_EQ(raster.z[i], known[i]);
    }
    ASSERT_GE(raster.z[i], -1e-4f);  // maximum principle
    ASSERT_LE(raster.z[i], 10.f + 1e-4f);
  }
}

TEST(SmrfInpaint, OneKnownCellFillsEverythingAndNoneIsAnError) {
  Raster raster = CoveringRaster({0, 0}, {9.5, 6.5}, 1.0);
  raster.z[raster.Index(3, 4)] = 2.5f;
  InpaintMembrane(&raster);
  for (const float z : raster.z) EXPECT_NEAR(z, 2.5f, 1e-5f);
  Raster empty = CoveringRaster({0, 0}, {3, 3}, 1.0);
  EXPECT_THROW(InpaintMembrane(&empty), InternalError);
}

TEST(SmrfInpaint, TangentPlanesReproduceAPlaneAndKeepKnownCells) {
  Raster raster = CoveringRaster({0, 0}, {79.5, 49.5}, 1.0);
  for (int row = 0; row < raster.rows; ++row) {
    for (int col = 0; col < raster.cols; ++col) {
      const bool gap = col >= 20 && col < 50 && row >= 10 && row < 35;
      raster.z[raster.Index(col, row)] = gap ? kNan : 0.3f * col - 0.1f * row + 5.f;
    }
  }
  const Raster known = raster;
  EXPECT_EQ(InpaintTangentPlanes(&raster), 30u * 25u);
  double worst = 0;
  for (int row = 0; row < raster.rows; ++row) {
    for (int col = 0; col < raster.cols; ++col) {
      const std::size_t i = raster.Index(col, row);
      if (!std::isnan(known.z[i])) {
        ASSERT_EQ(raster.z[i], known.z[i]);
      }
      worst = std::max(worst, std::abs(raster.z[i] - (0.3 * col - 0.1 * row + 5.0)));
    }
  }
  EXPECT_LT(worst, 0.02);
}

// A ridge (an embankment, a hilltop) whose top cells are unknown: the membrane cannot rise
// above the gap's rim, the tangent planes continue the flanks towards the top.
TEST(SmrfInpaint, TangentPlanesRebuildARidgeTheMembraneFlattens) {
  const auto ridge = [](int col) { return 10.0 - 0.5 * std::abs(col - 40); };
  Raster raster = CoveringRaster({0, 0}, {80.5, 30.5}, 1.0);
  for (int row = 0; row < raster.rows; ++row) {
    for (int col = 0; col < raster.cols; ++col) {
      const bool gap = std::abs(col - 40) < 8;
      raster.z[raster.Index(col, row)] = gap ? kNan : static_cast<float>(ridge(col));
    }
  }
  Raster membrane = raster;
  InpaintMembrane(&membrane);
  InpaintTangentPlanes(&raster);
  const float rim = static_cast<float>(ridge(32));
  // The top is 4 m above the rim. The flanks' gradients at the rim are read off the
  // membrane, which is flat inside the gap, so they are underestimated there and the planes
  // bring back most of the height, never more than there is.
  for (int row = 0; row < raster.rows; ++row) {
    for (const int col : {36, 40}) {
      const float z = raster.z[raster.Index(col, row)];
      EXPECT_LE(membrane.z[membrane.Index(col, row)], rim + 1e-3f);
      EXPECT_GT(z, rim + 0.55 * (ridge(col) - rim)) << "col " << col << " row " << row;
      EXPECT_LT(z, ridge(col) + 0.05) << "col " << col << " row " << row;
    }
  }
}

TEST(SmrfInpaint, TangentPlanesOfOneKnownCellAreFlatAndNoneIsAnError) {
  Raster raster = CoveringRaster({0, 0}, {9.5, 6.5}, 1.0);
  raster.z[raster.Index(3, 4)] = 2.5f;
  InpaintTangentPlanes(&raster);
  for (const float z : raster.z) EXPECT_NEAR(z, 2.5f, 1e-5f);
  Raster empty = CoveringRaster({0, 0}, {3, 3}, 1.0);
  EXPECT_THROW(InpaintTangentPlanes(&empty), InternalError);
}

// One point per cell at a random place in it, on `terrain`; flags all clear.
struct DemCase {
  Raster minimum;
  std::vector<Eigen::Vector2f> offsets;
  std::vector<uint8_t> low, object;
  smrf::DemInput Input(double readmit_within_m) const {
    DemInput in;
    in.minimum = &minimum;
    in.lowest_offset_m = &offsets;
    in.low_outlier = &low;
    in.object = &object;
    in.readmit_within_m = readmit_within_m;
    return in;
  }
};
template <class Terrain>
DemCase SampleOnePointPerCell(int cols, int rows, const Terrain& terrain) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  PointCloud points;
  for (int row = 0; row < rows; ++row) {
    for (int col = 0; col < cols; ++col) {
      const float x = col + u(rng), y = row + u(rng);
      points.emplace_back(x, y, static_cast<float>(terrain(x, y)));
    }
  }
  DemCase c;
  c.minimum = CoveringRaster({0, 0}, {cols - 0.5, rows - 0.5}, 1.0);
  FillMinimumSurface(points, &c.minimum, &c.offsets);
  c.low.assign(c.minimum.Size(), 0);
  c.object.assign(c.minimum.Size(), 0);
  return c;
}

// On a 30 % slope a cell's lowest point is anywhere in it, up to 0.2 m (half a cell along
// each axis times the slope) off the height at the cell centre; moved along the DEM's slope it
// is much closer. The slope comes from the DEM of the raw minima, whose bias makes it wrong by
// a few per cent cell to cell, so some error is left.
TEST(SmrfDem, GroundCellsStandAtTheirCentresOnASlope) {
  const auto terrain = [](double x, double y) { return 0.3 * x + 0.1 * y; };
  const DemCase c = SampleOnePointPerCell(40, 30, terrain);
  const Dem dem = BuildDem(c.Input(0.5));
  double raw_sum2 = 0, dem_sum2 = 0;
  int cells = 0;
  for (int row = 1; row + 1 < c.minimum.rows; ++row) {
    for (int col = 1; col + 1 < c.minimum.cols; ++col) {
      const double truth = terrain(col + 0.5, row + 0.5);
      raw_sum2 += std::pow(c.minimum.z[c.minimum.Index(col, row)] - truth, 2);
      dem_sum2 += std::pow(dem.z.z[dem.z.Index(col, row)] - truth, 2);
      ++cells;
    }
  }
  const double raw_rms = std::sqrt(raw_sum2 / cells), dem_rms = std::sqrt(dem_sum2 / cells);
  std::printf("RMS to the cell centres' heights: raw %.3f m, centred %.3f m\n", raw_rms, dem_rms);
  EXPECT_GT(raw_rms, 0.08);
  EXPECT_LT(dem_rms, 0.3 * raw_rms);
  EXPECT_EQ(dem.num_readmitted_cells, 0u);
  EXPECT_EQ(dem.rounds, 2);  // the raw one, then the centred one, which admits nothing
}

// The opening flagged a 6 m wide ridge top and a roof 5 m above the ground: the ridge comes
// back ring by ring, the roof never.
TEST(SmrfDem, FlaggedRidgeCellsAreReadmittedARoofIsNot) {
  const auto ground = [](double x, double) { return 6.0 - 0.6 * std::abs(x - 30.0); };
  const auto roof = [](double x, double y) { return x > 45 && x < 55 && y > 10 && y < 20; };
  DemCase c = SampleOnePointPerCell(
      70, 30, [&](double x, double y) { return ground(x, y) + (roof(x, y) ? 5.0 : 0.0); });
  for (int row = 0; row < c.minimum.rows; ++row) {
    for (int col = 0; col < c.minimum.cols; ++col) {
      const double x = col + 0.5, y = row + 0.5;
      c.object[c.minimum.Index(col, row)] = std::abs(x - 30.0) < 6.0 || roof(x, y);
    }
  }
  const Dem dem = BuildDem(c.Input(0.5));
  EXPECT_GT(dem.rounds, 2);
  double worst_flank = 0, worst_crest = 0, worst_roof = 0;
  for (int row = 0; row < c.minimum.rows; ++row) {
    for (int col = 0; col < c.minimum.cols; ++col) {
      const std::size_t i = c.minimum.Index(col, row);
      const double x = col + 0.5, y = row + 0.5;
      const double error = std::abs(dem.z.z[i] - ground(x, y));
      if (roof(x, y)) {
        EXPECT_FALSE(dem.ground[i]) << col << ", " << row;
        worst_roof = std::max(worst_roof, error);
      } else {
        EXPECT_TRUE(dem.ground[i]) << col << ", " << row;
        (std::abs(x - 30.0) < 2.0 ? worst_crest : worst_flank) =
            std::max(std::abs(x - 30.0) < 2.0 ? worst_crest : worst_flank, error);
      }
    }
  }
  std::printf("worst DEM error: flanks %.3f m, crest %.3f m, under the roof %.3f m\n", worst_flank,
              worst_crest, worst_roof);
  EXPECT_LT(worst_flank, 0.1);
  EXPECT_LT(worst_crest, 0.25);  // a kink: its cells' slope is the mean of the two flanks'
  EXPECT_LT(worst_roof, 0.05);   // the ground under the roof is a plane
  EXPECT_EQ(dem.num_readmitted_cells, 12u * 30u);
}

TEST(SmrfRaster, MinimumSurfaceAndBilinearSample) {
  Raster raster = CoveringRaster({10, 20}, {13.9, 21.9}, 1.0);
  EXPECT_EQ(raster.cols, 4);
  EXPECT_EQ(raster.rows, 2);
  const PointCloud points = {
      {10.2f, 20.2f, 3.f}, {10.8f, 20.7f, 1.f}, {13.9f, 21.9f, 5.f}, {kNan, 0.f, 0.f}};
  EXPECT_EQ(FillMinimumSurface(points, &raster), 2u);
  EXPECT_EQ(raster.z[raster.Index(0, 0)], 1.f);
  EXPECT_EQ(raster.z[raster.Index(3, 1)], 5.f);  // the far corner falls in the last cell
  Raster plane = CoveringRaster({0, 0}, {9.5, 9.5}, 0.5);
  for (int row = 0; row < plane.rows; ++row) {
    for (int col = 0; col < plane.cols; ++col) {
      plane.z[plane.Index(col, row)] = 2.f * (col + 0.5f) * 0.5f + (row + 0.5f) * 0.5f;
    }
  }
  EXPECT_NEAR(plane.Sample(3.3, 4.1), 2 * 3.3 + 4.1, 1e-4);
  const Raster slope = SlopeOf(plane);
  EXPECT_NEAR(slope.z[slope.Index(5, 5)], std::sqrt(5.0), 1e-4);
  EXPECT_NEAR(slope.z[slope.Index(0, 0)], std::sqrt(5.0), 1e-4);  // one-sided at the border
}

}  // namespace
}  // namespace hylo::terrain::smrf
