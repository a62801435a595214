// The node's example configuration and launch file stay loadable as the configuration grows.

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "hylo/config/run_config.h"

namespace hylo::rosnode {
namespace {

TEST(ExampleConfig, RosExampleLoadsWithItsFramesAndTopics) {
  const config::RunConfig config =
      config::LoadRunConfig(std::string(HYLO_SOURCE_DIR) + "/config/presets/ros_example.yaml");
  EXPECT_EQ(config.lidar.topic, "/velodyne_points");
  EXPECT_EQ(config.imu.topic, "/imu/data");
  EXPECT_EQ(config.output.map_frame, "map");
  EXPECT_EQ(config.output.odom_frame, "odom");
  EXPECT_EQ(config.output.base_frame, "base_link");
  EXPECT_NO_THROW(config.PipelineOptions());
}

TEST(ExampleConfig, LaunchFileSetsEveryNodeParameterItDeclares) {
  std::ifstream in(std::string(HYLO_SOURCE_DIR) + "/apps/ros/launch/hylo.launch");
  ASSERT_TRUE(in.good());
  std::stringstream text;
  text << in.rdbuf();
  for (const char* param : {"config", "prior_map", "initial_guess", "costmap", "inspection_map",
                            "inspection_costmap", "inspection_targets", "save_map_path"}) {
    EXPECT_NE(text.str().find("<param name=\"" + std::string(param) + "\""), std::string::npos)
        << param;
  }
  EXPECT_NE(text.str().find("pkg=\"hylo\" type=\"hylo_node\""), std::string::npos);
}

}  // namespace
}  // namespace hylo::rosnode
