// The planner on a small synthetic yard: a wall, a closed box around one target, a fenced
// island, a target out of range and one that must be seen from a given direction. Each gets
// the status it should, with its reason; the route visits every planned viewpoint on passable
// cells only. Also the visibility pieces (sight-line ends, view cone) and option validation.
#include "hylo/inspection/planner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace hylo::inspection {
namespace {

using terrain::CellClass;

// Points on the axis-aligned box [lo, hi]'s faces every `step` m.
void AddBoxSurface(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi, float step,
                   PointCloud* points) {
  for (float x = lo.x(); x <= hi.x() + 1e-4f; x += step)
    for (float y = lo.y(); y <= hi.y() + 1e-4f; y += step)
      for (float z = lo.z(); z <= hi.z() + 1e-4f; z += step) {
        const bool on_face = std::abs(x - lo.x()) < 1e-3f || std::abs(x - hi.x()) < 1e-3f ||
                             std::abs(y - lo.y()) < 1e-3f || std::abs(y - hi.y()) < 1e-3f ||
                             std::abs(z - lo.z()) < 1e-3f || std::abs(z - hi.z()) < 1e-3f;
        if (on_face) points->emplace_back(x, y, z);
      }
}

// 40 m x 30 m of flat ground at 0.2 m; a wall at x = 20 (y 0..22, 3 m high); a 2 m box
// closed on all sides around (30, 25, 1); an island x, y in [34, 40] x [0, 6] ringed by lethal
// cells with a 3 m wall on the ring.
struct Yard {
  terrain::GridMap grid;
  std::vector<CellClass> classes;
  PointCloud map;
};
Yard MakeYard() {
  terrain::GridGeometry g;
  g.resolution_m = 0.2;
  g.width = 200;
  g.height = 150;
  Yard yard{terrain::GridMap(g), std::vector<CellClass>(g.NumCells(), CellClass::kFree), {}};
  yard.grid.AddLayer(terrain::layers::kElevation, 0.f);
  yard.grid.AddLayer(terrain::layers::kCost, 0.1f);
  for (float x = 0.05f; x < 40.f; x += 0.1f)
    for (float y = 0.05f; y < 30.f; y += 0.1f) yard.map.emplace_back(x, y, 0.f);
  AddBoxSurface({20.f, 0.f, 0.f}, {20.2f, 22.f, 3.f}, 0.05f, &yard.map);
  AddBoxSurface({29.f, 24.f, 0.f}, {31.f, 26.f, 2.f}, 0.05f, &yard.map);
  for (int r = 0; r < g.height; ++r) {
    for (int c = 0; c < g.width; ++c) {
      const Eigen::Vector2d p = g.CentreLocal(c, r);
      const bool ring = (std::abs(p.x() - 33.5) < 0.25 && p.y() < 6.6) ||
                        (std::abs(p.y() - 6.5) < 0.25 && p.x() > 33.3);
      const bool box = p.x() > 29 && p.x() < 31 && p.y() > 24 && p.y() < 26;
      const bool wall = p.x() > 19.9 && p.x() < 20.3 && p.y() < 22.1;
      if (ring || box || wall) yard.classes[g.Index(c, r)] = CellClass::kLethal;
    }
  }
  AddBoxSurface({33.4f, 0.f, 0.f}, {33.6f, 6.6f, 3.f}, 0.05f, &yard.map);
  AddBoxSurface({33.4f, 6.4f, 0.f}, {40.f, 6.6f, 3.f}, 0.05f, &yard.map);
  return yard;
}

Target Point(const std::string& id, double x, double y, double z) {
  Target t;
  t.id = id;
  t.position = {x, y, z};
  return t;
}

class PlannerYardTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    yard_ = new Yard(MakeYard());
    targets_ = new std::vector<Target>{Point("open", 10, 10, 1.5), Point("in_box", 30, 25, 1.0),
                                       Point("island", 37, 3, 1.5), Point("far", 120, 10, 1.5)};
    Target facing_north = Point("north_face", 10, 25, 2.0);
    facing_north.view_azimuth_deg = 90.0;
    facing_north.view_tolerance_deg = 20.0;
    facing_north.max_range_m = 4.0;
    targets_->push_back(facing_north);
    Target cabinet = Point("cabinet", 15, 5, 1.0);
    cabinet.box_size_m = {1.0, 0.6, 2.0};
    targets_->push_back(cabinet);
    plan_ = new InspectionPlan(
        PlanInspection(yard_->map, yard_->grid, yard_->classes, *targets_, {2.0, 2.0}, {}));
  }
  static void TearDownTestSuite() {
    delete plan_;
    delete targets_;
    delete yard_;
  }
  const TargetPlan& Of(const std::string& id) const {
    for (std::size_t i = 0; i < targets_->size(); ++i)
      if ((*targets_)[i].id == id) return plan_->targets[i];
    throw std::runtime_error("no target " + id);
  }
  static Yard* yard_;
  static std::vector<Target>* targets_;
  static InspectionPlan* plan_;
};
Yard* PlannerYardTest::yard_ = nullptr;
std::vector<Target>* PlannerYardTest::targets_ = nullptr;
InspectionPlan* PlannerYardTest::plan_ = nullptr;

TEST_F(PlannerYardTest, EachTargetGetsItsStatusAndReason) {
  EXPECT_EQ(Of("open").status, TargetStatus::kPlanned);
  EXPECT_EQ(Of("cabinet").status, TargetStatus::kPlanned);
  EXPECT_EQ(Of("north_face").status, TargetStatus::kPlanned);
  EXPECT_EQ(Of("in_box").status, TargetStatus::kOccluded);
  EXPECT_NE(Of("in_box").reason.find("blocks every sight line"), std::string::npos)
      << Of("in_box").reason;
  EXPECT_GT(Of("in_box").candidate_cells, 1000u);
  EXPECT_EQ(Of("island").status, TargetStatus::kUnreachable);
  EXPECT_NE(Of("island").reason.find("none reachable"), std::string::npos) << Of("island").reason;
  EXPECT_EQ(Of("far").status, TargetStatus::kOccluded);
  EXPECT_NE(Of("far").reason.find("15.0 m"), std::string::npos) << Of("far").reason;
  EXPECT_EQ(plan_->summary.planned, 3u);
  EXPECT_EQ(plan_->summary.occluded, 2u);
  EXPECT_EQ(plan_->summary.unreachable, 1u);
}

TEST_F(PlannerYardTest, ViewpointsRespectRangeDirectionAndTheWall) {
  InspectionOptions defaults;
  for (std::size_t i = 0; i < targets_->size(); ++i) {
    const TargetPlan& t = plan_->targets[i];
    if (t.status != TargetStatus::kPlanned) continue;
    SCOPED_TRACE((*targets_)[i].id);
    const TargetShape shape = ShapeOf((*targets_)[i], defaults.visibility);
    EXPECT_TRUE(InViewCone(shape, t.camera));
    EXPECT_TRUE(std::isfinite(plan_->reach_cost[t.view_cell]));
    EXPECT_NEAR(t.camera.z(), defaults.visibility.camera_height_m, 1e-6);
  }
  const TargetPlan& north = Of("north_face");
  const Eigen::Vector3d d = north.camera - (*targets_)[4].position;
  EXPECT_LE(std::abs(std::atan2(d.y(), d.x()) * 180.0 / M_PI - 90.0), 20.0 + 1e-6);
  // The start is west of the wall: "open" is seen from this side.
  EXPECT_LT(Of("open").camera.x(), 20.0);
}

TEST_F(PlannerYardTest, TheRouteVisitsEveryViewpointOnPassableCellsAndReturns) {
  const InspectionPlan& p = *plan_;
  ASSERT_FALSE(p.route_cells.empty());
  EXPECT_EQ(p.route_cells.front(), p.start_cell);
  EXPECT_EQ(p.route_cells.back(), p.start_cell);  // closed by default
  std::set<std::size_t> on_route(p.route_cells.begin(), p.route_cells.end());
  for (const std::size_t c : p.route_cells) EXPECT_TRUE(p.passable[c]);
  std::set<int> orders;
  double legs = 0.0;
  for (const RouteStop& s : p.stops) legs += s.leg_length_m;
  for (const TargetPlan& t : p.targets) {
    if (t.status != TargetStatus::kPlanned) {
      EXPECT_EQ(t.order, 0);
      continue;
    }
    EXPECT_TRUE(on_route.count(t.view_cell));
    EXPECT_EQ(p.stops[t.stop].cell, t.view_cell);
    EXPECT_TRUE(orders.insert(t.order).second);
  }
  EXPECT_EQ(orders, (std::set<int>{1, 2, 3}));
  EXPECT_LE(legs, p.summary.route_length_m + 1e-9);  // the return leg is not a stop's
  ASSERT_GE(p.waypoints.size(), 2u);
  // Every straight segment between corners stays on passable cells: sampled every 5 mm, each
  // sample nudged 1 mm to either side so that a segment through a cell corner checks both.
  const terrain::GridGeometry& g = yard_->grid.geometry();
  for (std::size_t k = 1; k < p.waypoints.size(); ++k) {
    const Eigen::Vector2d a = p.waypoints[k - 1].xy, b = p.waypoints[k].xy;
    const Eigen::Vector2d normal = Eigen::Vector2d(a.y() - b.y(), b.x() - a.x()).normalized();
    const int samples = 1 + static_cast<int>((b - a).norm() / 0.005);
    for (int i = 0; i <= samples; ++i) {
      for (const double side : {-1e-3, 1e-3}) {
        const Eigen::Vector2d q = a + (b - a) * (double(i) / samples) + side * normal;
        const auto cell = g.CellOfLocal(q.x(), q.y());
        ASSERT_TRUE(cell);
        EXPECT_TRUE(p.passable[g.Index(cell->x(), cell->y())]) << "segment " << k;
      }
    }
  }
  int stops_marked = 0;
  for (const Waypoint& w : p.waypoints) stops_marked += w.stop >= 0;
  EXPECT_EQ(stops_marked, static_cast<int>(p.stops.size()));
}

TEST(Planner, RejectsDuplicateIdsBadTargetsAndAStartOffTheMap) {
  const Yard yard = MakeYard();
  std::vector<Target> twice{Point("a", 5, 5, 1), Point("a", 6, 6, 1)};
  EXPECT_THROW(PlanInspection(yard.map, yard.grid, yard.classes, twice, {2, 2}, {}),
               std::invalid_argument);
  Target bad = Point("b", 5, 5, 1);
  bad.view_azimuth_deg = 10.0;  // without a tolerance
  try {
    PlanInspection(yard.map, yard.grid, yard.classes, {bad}, {2, 2}, {});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("target 'b'"), std::string::npos) << e.what();
  }
  try {
    PlanInspection(yard.map, yard.grid, yard.classes, {Point("c", 5, 5, 1)}, {-30, 2}, {});
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("from the nearest passable cell"), std::string::npos)
        << e.what();
  }
}

TEST(SightLineEnd, StopsWhereTheLineEntersTheTargetsOwnRegion) {
  VisibilityOptions o;
  Target t = Point("p", 0, 0, 0);
  TargetShape s = ShapeOf(t, o);
  const double r = o.target_radius_m + o.occupancy.BlockedReach();
  Eigen::Vector3d end;
  ASSERT_TRUE(SightLineEnd(s, 0, {10, 0, 0}, &end));
  EXPECT_NEAR(end.x(), r, 1e-9);
  EXPECT_FALSE(SightLineEnd(s, 0, {0.5 * r, 0, 0}, &end));  // the camera is inside
  t.box_size_m = {2, 2, 2};
  s = ShapeOf(t, o);
  ASSERT_EQ(s.num_samples, 9);
  ASSERT_TRUE(SightLineEnd(s, 1, {10, -0.5, -0.5}, &end));  // towards (-0.5, -0.5, -0.5)
  EXPECT_NEAR(end.x(), 1.0 + o.occupancy.BlockedReach(), 1e-9);
}

TEST(InViewCone, RangeAndDirection) {
  Target t = Point("p", 0, 0, 0);
  t.view_azimuth_deg = 180.0;
  t.view_tolerance_deg = 30.0;
  const TargetShape s = ShapeOf(t, VisibilityOptions());
  EXPECT_TRUE(InViewCone(s, {-5, 0, 1}));
  EXPECT_TRUE(InViewCone(s, {-5, 2.8, 0}));   // 29.2 deg off
  EXPECT_FALSE(InViewCone(s, {-5, 3.0, 0}));  // 31 deg off
  EXPECT_FALSE(InViewCone(s, {5, 0, 0}));
  EXPECT_FALSE(InViewCone(s, {-0.5, 0, 0}));  // closer than min_range_m
  EXPECT_FALSE(InViewCone(s, {-16, 0, 0}));   // beyond max_range_m
}

TEST(InspectionOptions, ValidationNamesTheSectionAndField) {
  InspectionOptions o;
  std::string why;
  EXPECT_TRUE(o.IsValid(&why)) << why;
  o.visibility.min_range_m = 20.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("visibility.min_range_m = 20"), std::string::npos) << why;
  o = InspectionOptions();
  o.visibility.occupancy.voxel_size_m = -1;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("visibility.occupancy.voxel_size_m = -1"), std::string::npos) << why;
  o = InspectionOptions();
  o.visibility.min_visible_fraction = 0.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("min_visible_fraction"), std::string::npos) << why;
  o = InspectionOptions();
  o.viewpoint.angle_weight = -1;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("viewpoint.angle_weight"), std::string::npos) << why;
  o = InspectionOptions();
  o.start_snap_radius_m = std::nan("");
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("start_snap_radius_m"), std::string::npos) << why;
}

TEST(Target, ValidationNamesTheField) {
  Target t = Point("t", 1, 2, 3);
  std::string why;
  EXPECT_TRUE(t.IsValid(&why)) << why;
  t.min_range_m = 5;
  t.max_range_m = 4;
  EXPECT_FALSE(t.IsValid(&why));
  EXPECT_NE(why.find("min_range_m = 5"), std::string::npos) << why;
  t = Point("t", 1, 2, 3);
  t.box_size_m = {1, -1, 1};
  EXPECT_FALSE(t.IsValid(&why));
  EXPECT_NE(why.find("box_size_m"), std::string::npos) << why;
  t = Point("t", 1, 2, 3);
  t.view_azimuth_deg = 0;
  t.view_tolerance_deg = 0;
  EXPECT_FALSE(t.IsValid(&why));
  EXPECT_NE(why.find("view_tolerance_deg = 0"), std::string::npos) << why;
  t = Point("", 1, 2, 3);
  EXPECT_FALSE(t.IsValid(&why));
  EXPECT_NE(why.find("id"), std::string::npos) << why;
}

}  // namespace
}  // namespace hylo::inspection
