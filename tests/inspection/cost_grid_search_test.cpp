// Paths on the costmap: A* against Dijkstra on random costmaps, every path's steps legal (8
// neighbours, passable, no corner cut), the robot radius, and the options' validation.
#include "hylo/inspection/cost_grid_search.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace hylo::inspection {
namespace {

using terrain::CellClass;

terrain::GridGeometry Geometry(int width, int height, double res) {
  terrain::GridGeometry g;
  g.width = width;
  g.height = height;
  g.resolution_m = res;
  return g;
}

// A costmap with random lethal blobs, a few unknown cells and random costs.
struct RandomCostmap {
  terrain::GridGeometry geometry;
  std::vector<CellClass> classes;
  std::vector<float> cost;
};
RandomCostmap MakeCostmap(int width, int height, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  RandomCostmap m{Geometry(width, height, 0.2), {}, {}};
  m.classes.assign(m.geometry.NumCells(), CellClass::kFree);
  m.cost.assign(m.geometry.NumCells(), 0.f);
  for (std::size_t i = 0; i < m.cost.size(); ++i) {
    m.cost[i] = u(rng) * u(rng);
    m.classes[i] = u(rng) < 0.03f ? CellClass::kUnknown
                                   : (m.cost[i] < 0.3f ? CellClass::kFree : CellClass::kCost);
  }
  for (int blob = 0; blob < width * height / 60; ++blob) {
    const int c = static_cast<int>(u(rng) * width), r = static_cast<int>(u(rng) * height);
    const int len = 1 + static_cast<int>(u(rng) * 8);
    const bool along_x = u(rng) < 0.5f;
    for (int k = 0; k < len; ++k) {
      const int cc = along_x ? c + k : c, rr = along_x ? r : r + k;
      if (m.geometry.Contains(cc, rr)) m.classes[m.geometry.Index(cc, rr)] = CellClass::kLethal;
    }
  }
  return m;
}

// Every step of `path` is one the search may take.
void ExpectLegal(const CostGrid& grid, const GridPath& path) {
  const terrain::GridGeometry& g = grid.geometry();
  for (std::size_t k = 0; k < path.cells.size(); ++k) {
    ASSERT_TRUE(grid.Passable(path.cells[k]));
    if (k == 0) continue;
    const int c0 = g.Col(path.cells[k - 1]), r0 = g.Row(path.cells[k - 1]);
    const int c1 = g.Col(path.cells[k]), r1 = g.Row(path.cells[k]);
    ASSERT_LE(std::abs(c1 - c0), 1);
    ASSERT_LE(std::abs(r1 - r0), 1);
    ASSERT_NE(path.cells[k], path.cells[k - 1]);
    if (c1 != c0 && r1 != r0) {  // no corner cut
      EXPECT_TRUE(grid.Passable(g.Index(c1, r0)));
      EXPECT_TRUE(grid.Passable(g.Index(c0, r1)));
    }
  }
}

TEST(CostGrid, AStarFindsPathsAsCheapAsDijkstra) {
  int found = 0, unreachable = 0;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    const RandomCostmap m = MakeCostmap(70, 50, seed);
    const CostGrid grid(m.geometry, PassableCells(m.geometry, m.classes, 0.2), m.cost, 2.0);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<std::size_t> cell(0, m.geometry.NumCells() - 1);
    for (int source_trial = 0; source_trial < 4; ++source_trial) {
      std::size_t source = cell(rng);
      while (!grid.Passable(source)) source = cell(rng);
      const std::vector<double> dist = grid.Distances(source);
      for (int trial = 0; trial < 15; ++trial) {
        const std::size_t goal = cell(rng);
        const GridPath path = grid.ShortestPath(source, goal);
        if (!std::isfinite(dist[goal])) {
          EXPECT_FALSE(path.found());
          ++unreachable;
          continue;
        }
        ASSERT_TRUE(path.found());
        ++found;
        EXPECT_NEAR(path.cost, dist[goal], 1e-9 * (1.0 + dist[goal]));
        EXPECT_EQ(path.cells.front(), source);
        EXPECT_EQ(path.cells.back(), goal);
        ExpectLegal(grid, path);
        // The path's cost is the sum of its steps; its length is at most its cost.
        double sum = 0.0;
        for (std::size_t k = 1; k < path.cells.size(); ++k) {
          grid.ForEachStep(path.cells[k - 1], [&](std::size_t next, double step, double) {
            if (next == path.cells[k]) sum += step;
          });
        }
        EXPECT_NEAR(sum, path.cost, 1e-9 * (1.0 + sum));
        EXPECT_LE(path.length_m, path.cost + 1e-9);
      }
    }
  }
  EXPECT_GT(found, 200);
  EXPECT_GT(unreachable, 10);  // blocked cells and islands were exercised too
}

TEST(CostGrid, DijkstraStoppedEarlyStillSettlesTheWantedCells) {
  const RandomCostmap m = MakeCostmap(60, 60, 3);
  const CostGrid grid(m.geometry, PassableCells(m.geometry, m.classes, 0.0), m.cost, 1.0);
  std::size_t source = 0;
  while (!grid.Passable(source)) ++source;
  const std::vector<double> full = grid.Distances(source);
  const std::vector<std::size_t> wanted = {m.geometry.Index(30, 30), m.geometry.Index(5, 50),
                                           m.geometry.Index(59, 1)};
  const std::vector<double> early = grid.Distances(source, wanted);
  for (const std::size_t w : wanted) EXPECT_EQ(early[w], full[w]);
}

TEST(CostGrid, NoDiagonalStepThroughTheCornerOfABlockedCell) {
  // . X
  // . .   a diagonal from (0,0) to (1,1) would pass the lethal cell's corner: 2 steps instead.
  const terrain::GridGeometry g = Geometry(2, 2, 1.0);
  std::vector<CellClass> classes(4, CellClass::kFree);
  classes[g.Index(1, 1)] = CellClass::kFree;
  classes[g.Index(0, 1)] = CellClass::kLethal;
  const CostGrid grid(g, PassableCells(g, classes, 0.0), std::vector<float>(4, 0.f), 0.0);
  const GridPath path = grid.ShortestPath(g.Index(0, 0), g.Index(1, 1));
  ASSERT_TRUE(path.found());
  EXPECT_EQ(path.cells.size(), 3u);
  EXPECT_DOUBLE_EQ(path.length_m, 2.0);
}

TEST(PassableCells, KeepTheRobotRadiusFromLethalCellsButNotFromUnknownOnes) {
  const terrain::GridGeometry g = Geometry(11, 11, 0.1);
  std::vector<CellClass> classes(g.NumCells(), CellClass::kFree);
  classes[g.Index(5, 5)] = CellClass::kLethal;
  classes[g.Index(0, 0)] = CellClass::kUnknown;
  const std::vector<uint8_t> passable = PassableCells(g, classes, 0.3);
  for (int r = 0; r < 11; ++r) {
    for (int c = 0; c < 11; ++c) {
      const double d = 0.1 * std::hypot(c - 5, r - 5);
      const bool expected = d > 0.3 + 1e-9 && !(c == 0 && r == 0);
      EXPECT_EQ(passable[g.Index(c, r)] != 0, expected) << c << " " << r;
    }
  }
  EXPECT_TRUE(passable[g.Index(1, 0)]);  // next to the unknown cell
}

TEST(SearchOptions, ValidationNamesTheField) {
  SearchOptions o;
  std::string why;
  EXPECT_TRUE(o.IsValid(&why)) << why;
  o.robot_radius_m = -0.1;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("robot_radius_m = -0.1"), std::string::npos) << why;
  o = SearchOptions();
  o.cost_weight = std::nan("");
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("cost_weight"), std::string::npos) << why;
}

}  // namespace
}  // namespace hylo::inspection
