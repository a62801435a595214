// The health topic's JSON: the state names the node documents, counters, NaN written as null.

#include "health.h"

#include <gtest/gtest.h>

namespace hylo::rosnode {
namespace {

using Status = odometry::OdometryPipeline::Status;

TEST(Health, StatesFollowThePipelineAndPendingRequests) {
  EXPECT_EQ(ToString(StateOf(Status::kInitializing, false)), "initialising");
  EXPECT_EQ(ToString(StateOf(Status::kRunning, false)), "localized");
  EXPECT_EQ(ToString(StateOf(Status::kLost, false)), "lost");
  EXPECT_EQ(ToString(StateOf(Status::kRunning, true)), "relocalizing");
  EXPECT_EQ(ToString(StateOf(Status::kLost, true)), "relocalizing");
  EXPECT_EQ(ToString(StateOf(Status::kFailed, true)), "failed");
}

TEST(Health, JsonCarriesFitnessMatchesStateAndLateMessages) {
  HealthReport report;
  report.state = HealthState::kLocalized;
  report.t_ns = 1'700'000'000'500'000'000;
  report.scan.fitness_m2 = 0.0125;
  report.scan.num_matches = 812;
  report.scan.inlier_ratio = 0.75;
  report.input.scans_out_of_order = 3;
  report.input.scans_dropped_full = 2;
  const std::string json = HealthJson(report);
  EXPECT_NE(json.find("\"state\":\"localized\""), std::string::npos) << json;
  EXPECT_NE(json.find("\"fitness_m2\":0.0125"), std::string::npos) << json;
  EXPECT_NE(json.find("\"matches\":812"), std::string::npos) << json;
  EXPECT_NE(json.find("\"scans_out_of_order\":3"), std::string::npos) << json;
  EXPECT_NE(json.find("\"scans_dropped_full\":2"), std::string::npos) << json;
  EXPECT_EQ(json.find('\n'), std::string::npos) << "one line";
  report.scan.fitness_m2 = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(HealthJson(report).find("\"fitness_m2\":null"), std::string::npos);
}

}  // namespace
}  // namespace hylo::rosnode
