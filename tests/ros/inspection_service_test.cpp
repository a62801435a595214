// ~plan_inspection without a master: where the route starts (the request's pose, the current
// pose, or a refusal), the route as a nav_msgs/Path, and the service's planning on a small
// yard in shifted map-frame coordinates (the route starts and ends at the start, goes around
// the wall, and a start off the costmap is refused with the reason).
#include "inspection_service.h"

#include <gtest/gtest.h>
#include <tf2/utils.h>

#include <cmath>

#include "hylo/io/costmap_io.h"
#include "inspection_yard.h"
#include "ros_messages.h"
#include "test_data.h"

namespace hylo::rosnode {
namespace {

TEST(ResolveStart, MapFrameUsesTheRequestEmptyFrameTheCurrentPose) {
  std::string why;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() << 1000.5, 2000.25, 50.0;
  const auto given = ResolveStart("map", {3.0, 4.0}, pose, "map", &why);
  ASSERT_TRUE(given);
  EXPECT_EQ(*given, Eigen::Vector2d(3.0, 4.0));
  const auto current = ResolveStart("", {3.0, 4.0}, pose, "map", &why);
  ASSERT_TRUE(current);
  EXPECT_EQ(*current, Eigen::Vector2d(1000.5, 2000.25));
  EXPECT_FALSE(ResolveStart("", {3.0, 4.0}, std::nullopt, "map", &why));
  EXPECT_NE(why.find("no valid pose"), std::string::npos) << why;
  EXPECT_FALSE(ResolveStart("odom", {3.0, 4.0}, pose, "map", &why));
  EXPECT_NE(why.find("frame 'odom', expected 'map'"), std::string::npos) << why;
}

TEST(ToPathMsg, CornersFaceTheNextOne) {
  const nav_msgs::Path path =
      ToPathMsg({{0.0, 0.0}, {2.0, 0.0}, {2.0, 3.0}}, "map", ros::Time(12, 0));
  EXPECT_EQ(path.header.frame_id, "map");
  ASSERT_EQ(path.poses.size(), 3u);
  const double yaw[] = {0.0, M_PI / 2, M_PI / 2};
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(path.poses[i].header.frame_id, "map");
    EXPECT_DOUBLE_EQ(path.poses[i].pose.position.z, 0.0);
    EXPECT_NEAR(tf2::getYaw(path.poses[i].pose.orientation), yaw[i], 1e-12) << i;
  }
  EXPECT_DOUBLE_EQ(path.poses[2].pose.position.y, 3.0);
}

TEST(InspectionService, PlansAroundTheWallFromTheStartAndBack) {
  const Eigen::Vector3d offset(1000.0, 2000.0, 50.0);
  const testing::InspectionYard yard =
      testing::WriteInspectionYard(testing::ScratchDir("ros_inspection_service"), offset);
  const InspectionService service(yard.map, yard.costmap_dir, yard.targets, {});
  EXPECT_EQ(service.num_targets(), 2u);
  std::vector<Eigen::Vector2d> route;
  std::string summary;
  const Eigen::Vector2d start = offset.head<2>() + Eigen::Vector2d(2.0, 2.0);
  ASSERT_TRUE(service.Plan(start, &route, &summary)) << summary;
  EXPECT_NE(summary.find("2 of 2 targets planned"), std::string::npos) << summary;
  ASSERT_GE(route.size(), 4u);
  EXPECT_LT((route.front() - start).norm(), 0.2);
  EXPECT_LT((route.back() - start).norm(), 0.2);
  // Around the wall's end (y = 14), never through it (x 12..12.2 below y 14).
  bool east_of_wall = false;
  for (std::size_t i = 0; i + 1 < route.size(); ++i) {
    const Eigen::Vector2d a = route[i] - offset.head<2>(), b = route[i + 1] - offset.head<2>();
    east_of_wall |= a.x() > 12.2;
    for (double s = 0.0; s <= 1.0; s += 0.01) {
      const Eigen::Vector2d p = a + s * (b - a);
      EXPECT_FALSE(p.x() > 11.8 && p.x() < 12.4 && p.y() < 14.2)
          << "route crosses the wall at (" << p.x() << ", " << p.y() << ")";
    }
  }
  EXPECT_TRUE(east_of_wall);
  EXPECT_FALSE(service.Plan(offset.head<2>() + Eigen::Vector2d(500.0, 5.0), &route, &summary));
  EXPECT_NE(summary.find("in the map frame"), std::string::npos) << summary;
}

TEST(InspectionService, MissingFileIsNamed) {
  try {
    InspectionService("/nonexistent/map.pcd", "/nonexistent/costmap", "/nonexistent/t.csv", {});
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace hylo::rosnode
