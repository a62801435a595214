// The node reads the costmap files that `hylo traversability` writes (io::WriteMapServer)
// with map_server's semantics: classes, grid orientation and origin survive the round trip.

#include "costmap_grid.h"

#include <gtest/gtest.h>

#include <fstream>

#include "hylo/io/costmap_io.h"
#include "test_data.h"

namespace hylo::rosnode {
namespace {

using terrain::CellClass;

struct Fixture {
  terrain::GridMap grid;
  std::vector<CellClass> classes;
};

// 4 × 3 cells: lethal at (col 0, row 0) = the lowest-y row, unknown at (3, 2), a costly
// cell at (1, 1), everything else free.
Fixture MakeGrid() {
  terrain::GridGeometry g;
  g.origin_world = Eigen::Vector3d(1000.0, 2000.0, 50.0);
  g.corner_local = Eigen::Vector2d(-1.0, -0.5);
  g.resolution_m = 0.25;
  g.width = 4;
  g.height = 3;
  Fixture f{terrain::GridMap(g), std::vector<CellClass>(g.NumCells(), CellClass::kFree)};
  std::vector<float>& cost = f.grid.AddLayer(terrain::layers::kCost, 0.f);
  f.classes[g.Index(0, 0)] = CellClass::kLethal;
  cost[g.Index(0, 0)] = 1.f;
  f.classes[g.Index(3, 2)] = CellClass::kUnknown;
  f.classes[g.Index(1, 1)] = CellClass::kCost;
  cost[g.Index(1, 1)] = 0.6f;
  return f;
}

TEST(CostmapGrid, TrinaryRoundTripKeepsClassesOrientationAndOrigin) {
  const std::string dir = testing::ScratchDir("ros_costmap");
  const Fixture f = MakeGrid();
  io::WriteMapServer(dir + "/costmap.yaml", f.grid, f.classes);
  const OccupancyGridData grid = ReadMapServerMap(dir + "/costmap.yaml");
  ASSERT_EQ(grid.width, 4);
  ASSERT_EQ(grid.height, 3);
  EXPECT_DOUBLE_EQ(grid.resolution_m, 0.25);
  EXPECT_NEAR(grid.origin_x_m, 999.0, 1e-6);
  EXPECT_NEAR(grid.origin_y_m, 1999.5, 1e-6);
  ASSERT_EQ(grid.cells.size(), 12u);
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 4; ++col) {
      const int8_t cell = grid.cells[row * 4 + col];
      if (col == 0 && row == 0) {
        EXPECT_EQ(cell, 100) << "lethal";
      } else if (col == 3 && row == 2) {
        EXPECT_EQ(cell, -1) << "unknown";
      } else {
        EXPECT_EQ(cell, 0) << "free or traversable at a cost, col " << col << " row " << row;
      }
    }
  }
}

TEST(CostmapGrid, RawModeKeepsTheGradedCost) {
  const std::string dir = testing::ScratchDir("ros_costmap_raw");
  const Fixture f = MakeGrid();
  io::WriteMapServer(dir + "/costmap.yaml", f.grid, f.classes);
  std::ofstream(dir + "/raw.yaml") << "image: costmap.pgm\nresolution: 0.25\n"
                                      "origin: [0, 0, 0]\nmode: raw\n";
  const OccupancyGridData grid = ReadMapServerMap(dir + "/raw.yaml");
  const auto pixel = [&](int col, int row) {
    return static_cast<uint8_t>(grid.cells[row * 4 + col]);
  };
  EXPECT_EQ(pixel(0, 0), 0);    // lethal
  EXPECT_EQ(pixel(3, 2), 205);  // unknown
  EXPECT_EQ(pixel(2, 2), 254);  // free
  EXPECT_LT(pixel(1, 1), 254);  // costly: darker than free
  EXPECT_GT(pixel(1, 1), 200);
}

TEST(CostmapGrid, ErrorsNameTheFile) {
  const std::string dir = testing::ScratchDir("ros_costmap_bad");
  try {
    ReadMapServerMap(dir + "/missing.yaml");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.yaml"), std::string::npos) << e.what();
  }
  std::ofstream(dir + "/no_image.yaml") << "image: none.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n";
  EXPECT_THROW(ReadMapServerMap(dir + "/no_image.yaml"), std::runtime_error);
  std::ofstream(dir + "/bad_mode.yaml") << "image: x.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n"
                                           "mode: fancy\n";
  EXPECT_THROW(ReadMapServerMap(dir + "/bad_mode.yaml"), std::runtime_error);
  std::ofstream(dir + "/short.pgm", std::ios::binary) << "P5\n4 4\n255\nabc";
  std::ofstream(dir + "/short.yaml") << "image: short.pgm\nresolution: 0.1\norigin: [0, 0, 0]\n";
  EXPECT_THROW(ReadMapServerMap(dir + "/short.yaml"), std::runtime_error);
}

}  // namespace
}  // namespace hylo::rosnode
