// The site's equipment as inspection targets in another frame: a translation keeps every
// field, a quarter-turn about z swaps a box's x and y sizes and turns view azimuths with it,
// and every target of the fixed site is a valid one.
#include "hylo/sim_io/equipment_targets_io.h"

#include <gtest/gtest.h>

#include <cmath>

namespace hylo::sim {
namespace {

EquipmentTarget Cabinet() {
  EquipmentTarget e;
  e.id = "cabinet_1";
  e.centre_m = {10.0, 20.0, 1.5};
  e.box_size_m = {4.0, 1.0, 3.0};
  e.view_azimuth_deg = 0.0;
  e.view_tolerance_deg = 60.0;
  return e;
}

TEST(EquipmentAsTargets, TranslationKeepsSizesAndDirections) {
  const Eigen::Isometry3d T(Eigen::Translation3d(-5.0, -5.0, -1.0));
  const std::vector<inspection::Target> t = EquipmentAsTargets({Cabinet()}, T);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_EQ(t[0].id, "cabinet_1");
  EXPECT_TRUE(t[0].position.isApprox(Eigen::Vector3d(5.0, 15.0, 0.5)));
  EXPECT_TRUE(t[0].box_size_m.isApprox(Eigen::Vector3d(4.0, 1.0, 3.0)));
  EXPECT_NEAR(t[0].view_azimuth_deg, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(t[0].view_tolerance_deg, 60.0);
}

TEST(EquipmentAsTargets, QuarterTurnSwapsBoxAxesAndTurnsAzimuth) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const std::vector<inspection::Target> t = EquipmentAsTargets({Cabinet()}, T);
  ASSERT_EQ(t.size(), 1u);
  EXPECT_TRUE(t[0].position.isApprox(Eigen::Vector3d(-20.0, 10.0, 1.5)));
  EXPECT_NEAR(t[0].box_size_m.x(), 1.0, 1e-9);
  EXPECT_NEAR(t[0].box_size_m.y(), 4.0, 1e-9);
  EXPECT_NEAR(t[0].box_size_m.z(), 3.0, 1e-9);
  // East of the cabinet in the site is north of it in the turned frame.
  EXPECT_NEAR(t[0].view_azimuth_deg, 90.0, 1e-9);
}

TEST(EquipmentAsTargets, EveryTargetOfTheSiteIsValidInATurnedFrame) {
  const Site site = BuildSite(1, TerrainOptions());
  const std::vector<EquipmentTarget> equipment = EquipmentTargets(site, SessionId::kA);
  ASSERT_GT(equipment.size(), 10u);
  Eigen::Isometry3d T(Eigen::Translation3d(3.0, -7.0, 0.5));
  T.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (const inspection::Target& t : EquipmentAsTargets(equipment, T)) {
    std::string why;
    EXPECT_TRUE(t.IsValid(&why)) << t.id << ": " << why;
  }
}

}  // namespace
}  // namespace hylo::sim
