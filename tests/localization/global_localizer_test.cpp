// Global localizer on small synthetic maps with known answers: a yard without symmetry (found
// from any heading, no guess), two identical yards side by side (ambiguous, nothing accepted),
// a view of a place not in the map (never accepted), a vehicle standing beside the mapped
// ground (refused), bad input and invalid options; and the
// GlobalMap raster it searches.
#include "hylo/localization/global_localizer.h"

#include <gtest/gtest.h>

#include <limits>
#include <sstream>
#include <stdexcept>

#include "hylo/common/check.h"
#include "hylo/localization/global_map.h"
#include "registration/synthetic_scene.h"

namespace hylo::localization {
namespace {

using namespace registration::synthetic_scene;

constexpr double kSensorHeightM = 1.0;  // IMU above the vehicle's ground

// A 60 m x 40 m site: ground, a boundary wall of changing height, and boxes placed so that no
// rotation or shift maps the site onto itself. Views sample the ground sparser than the rest
// (a lidar's rings thin out on the ground with range; ground alone fits everywhere).
PointCloud Site(float spacing_m, uint32_t seed, float ground_spacing_m) {
  std::mt19937 rng(seed);
  PointCloud cloud;
  AddRectangle({0, 0, 0}, {60, 0, 0}, {0, 40, 0}, ground_spacing_m, &rng, &cloud);
  AddRectangle({0, 40, 0}, {60, 0, 0}, {0, 0, 3}, spacing_m, &rng, &cloud);
  AddRectangle({0, 0, 0}, {0, 40, 0}, {0, 0, 2}, spacing_m, &rng, &cloud);
  AddRectangle({60, 0, 0}, {0, 25, 0}, {0, 0, 4}, spacing_m, &rng, &cloud);
  AddBox({8, 6, 0}, {2, 1, 2.5f}, spacing_m, &rng, &cloud);
  AddBox({20, 28, 0}, {1, 3, 1.5f}, spacing_m, &rng, &cloud);
  AddBox({33, 9, 0}, {3, 1.5f, 1}, spacing_m, &rng, &cloud);
  AddBox({45, 30, 0}, {1.5f, 1.5f, 4}, spacing_m, &rng, &cloud);
  AddBox({50, 12, 0}, {1, 4, 2}, spacing_m, &rng, &cloud);
  AddBox({14, 18, 0}, {4, 1, 3}, spacing_m, &rng, &cloud);
  AddBox({38, 22, 0}, {1, 1, 1.2f}, spacing_m, &rng, &cloud);
  AddBox({27, 4, 0}, {1.2f, 2.5f, 3.5f}, spacing_m, &rng, &cloud);
  return cloud;
}

// What a sensor at `T_map_imu` sees of `world`: points within `range_m`, in the IMU frame.
PointCloud View(const PointCloud& world, const Eigen::Isometry3d& T_map_imu, double range_m,
                uint32_t seed) {
  PointCloud near;
  for (const Eigen::Vector3f& p : world) {
    if ((p.cast<double>() - T_map_imu.translation()).head<2>().norm() <= range_m) {
      near.push_back(p);
    }
  }
  return InBody(near, T_map_imu, 0.01, seed);
}

// Every refined hypothesis, for failure messages.
std::string Hypotheses(const GlobalLocalizationResult& r) {
  std::ostringstream os;
  os << r.message;
  for (const GlobalHypothesis& h : r.hypotheses) {
    if (!h.refined) continue;
    const Eigen::Vector3d t = h.T_refined.translation();
    os << "\n  (" << t.x() << ", " << t.y() << ", " << t.z() << ") yaw "
       << std::atan2(h.T_refined(1, 0), h.T_refined(0, 0)) / kDeg << " score " << h.score
       << (h.passes ? " passes" : " fails") << ": inliers " << h.inlier_ratio << " plane fitness "
       << h.plane_fitness_m2 << " fitness " << h.fitness_m2 << " ground support "
       << h.ground_support;
  }
  return os.str();
}

GlobalLocalizerOptions SmallSiteOptions() {
  GlobalLocalizerOptions options;
  options.max_range_m = 25.0;
  return options;
}

class GlobalLocalizerTest : public ::testing::Test {
 protected:
  GlobalLocalizerTest()
      : points_(Site(0.1f, 1, 0.1f)),
        tree_(Tree(points_)),
        global_map_(GlobalMap::Build(points_, GlobalMapOptions())),
        localizer_(SmallSiteOptions(), IcpInitializerOptions()) {}
  PointCloud points_;
  std::unique_ptr<mapping::IkdTree> tree_;
  GlobalMap global_map_;
  GlobalLocalizer localizer_;
};

TEST_F(GlobalLocalizerTest, FindsTheVehicleFromAnyHeadingWithoutAGuess) {
  const PointCloud world = Site(0.15f, 2, 0.3f);  // another sampling of the same place
  for (const Eigen::Isometry3d& truth :
       {Pose(12.3, 11.7, kSensorHeightM, 37.0), Pose(40.6, 17.2, kSensorHeightM, -121.0),
        Pose(25.1, 33.4, kSensorHeightM, 178.0)}) {
    const GlobalLocalizationResult r = localizer_.Localize(
        View(world, truth, 25.0, 3), Eigen::Matrix3d::Identity(), global_map_, *tree_);
    ASSERT_EQ(r.status, GlobalStatus::kAccepted) << Hypotheses(r);
    EXPECT_LT(TranslationError(r.T_map_imu, truth), 0.05) << r.message;
    EXPECT_LT(RotationErrorDeg(r.T_map_imu, truth), 0.5) << r.message;
    EXPECT_GE(r.num_passing, 1);
    ASSERT_FALSE(r.hypotheses.empty());
    EXPECT_GE(r.hypotheses.front().score, r.hypotheses.back().score);
    EXPECT_GT(r.stats.nodes_scored, 0u);
    EXPECT_NEAR(r.stats.sensor_height_m, kSensorHeightM, 0.1);
  }
}

TEST_F(GlobalLocalizerTest, ATiltedImuIsLevelledByTheGivenRotation) {
  // The IMU is mounted pitched by 8 deg; gravity (R_level) says so.
  const Eigen::Matrix3d R_tilt =
      Eigen::AngleAxisd(8.0 * kDeg, Eigen::Vector3d::UnitY()).toRotationMatrix();
  Eigen::Isometry3d truth = Pose(18.4, 24.9, kSensorHeightM, 63.0);
  truth.linear() = truth.linear() * R_tilt;
  const GlobalLocalizationResult r =
      localizer_.Localize(View(Site(0.15f, 2, 0.3f), truth, 25.0, 4),
                          LevellingRotation(truth.linear()), global_map_, *tree_);
  ASSERT_EQ(r.status, GlobalStatus::kAccepted) << r.message;
  EXPECT_LT(TranslationError(r.T_map_imu, truth), 0.05);
  EXPECT_LT(RotationErrorDeg(r.T_map_imu, truth), 0.5);
}

TEST(GlobalLocalizer, TwoIdenticalYardsAreAmbiguousNotGuessed) {
  // The same yard twice, 40 m apart: a view of one of them fits both.
  const PointCloud yard = Yard(0.1f, 1);
  PointCloud twins = yard;
  for (const Eigen::Vector3f& p : yard) twins.push_back(p + Eigen::Vector3f(40.f, 0.f, 0.f));
  const auto tree = Tree(twins);
  const GlobalMap global_map = GlobalMap::Build(twins, GlobalMapOptions());
  GlobalLocalizerOptions options = SmallSiteOptions();
  options.max_range_m = 14.0;  // the view stays inside one yard
  const GlobalLocalizer localizer(options, IcpInitializerOptions());
  const Eigen::Isometry3d truth = Pose(2.0, -3.0, kSensorHeightM, 25.0);
  const GlobalLocalizationResult r = localizer.Localize(
      View(Yard(0.15f, 2), truth, 14.0, 5), Eigen::Matrix3d::Identity(), global_map, *tree);
  EXPECT_EQ(r.status, GlobalStatus::kAmbiguous) << r.message;
  EXPECT_GE(r.num_passing, 2) << r.message;
  EXPECT_NE(r.message.find("ambiguous"), std::string::npos) << r.message;
}

TEST_F(GlobalLocalizerTest, APlaceNotInTheMapIsNeverAccepted) {
  // Another yard altogether (the ICP initializer tests' yard, moved onto this site's extent).
  const Eigen::Isometry3d truth = Pose(0.5, 0.5, kSensorHeightM, 10.0);
  PointCloud elsewhere;
  for (const Eigen::Vector3f& p : Yard(0.15f, 7)) elsewhere.push_back(p);
  const GlobalLocalizationResult r = localizer_.Localize(
      View(elsewhere, truth, 25.0, 6), Eigen::Matrix3d::Identity(), global_map_, *tree_);
  EXPECT_TRUE(r.status == GlobalStatus::kNotFound || r.status == GlobalStatus::kAmbiguous)
      << r.message;
  EXPECT_FALSE(r.hypotheses.empty()) << "the search ran and found look-alikes: " << r.message;
}

// A vehicle parked where the map holds no ground (a yard mapped from outside: its walls and
// boxes seen from afar, its floor never driven): the map's structures fit its view, but the
// ground it stands on is not in the map, so the pose is refused, though it is the true one.
TEST_F(GlobalLocalizerTest, AVehicleBesideTheMappedGroundIsNotAccepted) {
  const Eigen::Isometry3d truth = Pose(40.6, 17.2, kSensorHeightM, -121.0);
  const Eigen::Vector2f at = truth.translation().head<2>().cast<float>();
  PointCloud map;  // the site without its floor within 9 m, but for a few returns under the
                   // vehicle (the search needs some ground in its cell to stand a pose there)
  for (const Eigen::Vector3f& p : points_) {
    const Eigen::Vector2f d = p.head<2>() - at;
    const bool floor = p.z() < 0.05f && d.norm() < 9.f && d.cwiseAbs().maxCoeff() > 0.75f;
    if (!floor) map.push_back(p);
  }
  const auto tree = Tree(map);
  const GlobalMap global_map = GlobalMap::Build(map, GlobalMapOptions());
  const PointCloud view = View(Site(0.15f, 2, 0.3f), truth, 25.0, 8);

  GlobalLocalizerOptions without_gate = SmallSiteOptions();
  without_gate.min_ground_support = 0.0;
  const GlobalLocalizationResult fits =
      GlobalLocalizer(without_gate, IcpInitializerOptions())
          .Localize(view, Eigen::Matrix3d::Identity(), global_map, *tree);
  ASSERT_EQ(fits.status, GlobalStatus::kAccepted) << Hypotheses(fits);
  EXPECT_LT(TranslationError(fits.T_map_imu, truth), 0.05) << fits.message;

  const GlobalLocalizationResult r =
      localizer_.Localize(view, Eigen::Matrix3d::Identity(), global_map, *tree);
  // Not accepted: not found, or ambiguous when a wrong place passes every gate while the
  // refused true pose explains more of the view (a refused pose still blocks a worse one).
  EXPECT_TRUE(r.status == GlobalStatus::kNotFound || r.status == GlobalStatus::kAmbiguous)
      << Hypotheses(r);
  EXPECT_NE(r.message.find("ground support"), std::string::npos) << r.message;
  bool true_pose_refined = false;  // ... and judged there, on its ground support
  for (const GlobalHypothesis& h : r.hypotheses) {
    if (!h.refined || TranslationError(h.T_refined, truth) > 0.1) continue;
    true_pose_refined = true;
    EXPECT_LT(h.ground_support, SmallSiteOptions().min_ground_support);
  }
  EXPECT_TRUE(true_pose_refined) << Hypotheses(r);
}

TEST_F(GlobalLocalizerTest, BadInputIsReportedNotThrown) {
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  const GlobalLocalizationResult empty = localizer_.Localize({}, I, global_map_, *tree_);
  EXPECT_EQ(empty.status, GlobalStatus::kBadInput);
  EXPECT_FALSE(empty.message.empty());
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const PointCloud all_nan(500, Eigen::Vector3f(nan, 0.f, nan));
  EXPECT_EQ(localizer_.Localize(all_nan, I, global_map_, *tree_).status, GlobalStatus::kBadInput);
  const GlobalLocalizationResult no_map =
      localizer_.Localize(View(points_, Pose(12, 12, 1, 0), 25.0, 7), I, GlobalMap(), *tree_);
  EXPECT_EQ(no_map.status, GlobalStatus::kBadInput);
  EXPECT_NE(no_map.message.find("empty map"), std::string::npos) << no_map.message;
}

TEST(GlobalLocalizer, InvalidOptionsNameTheField) {
  GlobalLocalizerOptions options;
  options.max_range_m = options.min_range_m;
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("max_range_m"), std::string::npos) << why;
  options = GlobalLocalizerOptions();
  options.min_score = 0.0;
  EXPECT_THROW(GlobalLocalizer(options, IcpInitializerOptions()), InternalError);
  options = GlobalLocalizerOptions();
  options.judge_max_points = 10;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("judge_max_points"), std::string::npos) << why;
}

TEST(GlobalMap, RasterHoldsTheGroundAndHeightProfileOfEachCell) {
  PointCloud points;
  std::mt19937 rng(1);
  AddRectangle({0, 0, 0}, {10, 0, 0}, {0, 10, 0}, 0.1f, &rng, &points);
  AddBox({4, 4, 0}, {1, 1, 2}, 0.1f, &rng, &points);
  const GlobalMap map = GlobalMap::Build(points, GlobalMapOptions());
  const GlobalMap::Layout& layout = map.layout();
  EXPECT_EQ(layout.num_points, points.size());
  EXPECT_GE(layout.width, 20);
  EXPECT_GE(layout.height, 20);
  EXPECT_EQ(map.num_levels(), GlobalMapOptions().levels);
  EXPECT_GT(map.MemoryBytes(), 0u);
  // Level 0: an open-ground cell holds the lowest bin only; the box's cells reach 2 m.
  const auto index = [&](double x, double y) {
    const int cx = static_cast<int>((x - layout.origin_x_m) / layout.options.cell_m);
    const int cy = static_cast<int>((y - layout.origin_y_m) / layout.options.cell_m);
    return static_cast<std::size_t>(cy) * layout.width + cx;
  };
  const GlobalMap::Level& level0 = map.level(0);
  EXPECT_NEAR(level0.ground_min_m[index(2.2, 2.2)], 0.0, 1e-3);
  EXPECT_EQ(__builtin_popcountll(level0.occupancy[index(2.2, 2.2)]), 1);
  EXPECT_GE(__builtin_popcountll(level0.occupancy[index(4.0, 4.5)]), 4);
  // Each coarser level bounds the finer one: its mask holds every finer mask of its block.
  const GlobalMap::Level& level1 = map.level(1);
  const std::size_t i = index(4.0, 4.5);
  EXPECT_EQ(level1.occupancy[i] & level0.occupancy[i], level0.occupancy[i]);
  EXPECT_LE(level1.ground_min_m[i], level0.ground_min_m[i]);
}

TEST(GlobalMap, RefusesNoPointsInvalidOptionsAndOversizedRasters) {
  EXPECT_THROW(GlobalMap::Build({}, GlobalMapOptions()), std::invalid_argument);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(GlobalMap::Build(PointCloud(10, Eigen::Vector3f(nan, nan, nan)), GlobalMapOptions()),
               std::invalid_argument);
  GlobalMapOptions options;
  options.cell_m = 0.0;
  EXPECT_THROW(GlobalMap::Build(PointCloud(1, Eigen::Vector3f::Zero()), options),
               std::invalid_argument);
  options = GlobalMapOptions();
  options.max_cells_million = 1.0;
  const PointCloud far_apart = {Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(1000, 1000, 0)};
  try {
    GlobalMap::Build(far_apart, options);
    FAIL() << "a 4 M-cell raster was built under a 1 M-cell limit";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("max_cells_million"), std::string::npos) << e.what();
  }
}

TEST(GlobalLocalizer, LevellingRotationKeepsRollAndPitchAndDropsYaw) {
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitZ()) *
                             Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()) *
                             Eigen::AngleAxisd(-0.05, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  const Eigen::Matrix3d level = LevellingRotation(R);
  EXPECT_NEAR(std::atan2(level(1, 0), level(0, 0)), 0.0, 1e-12);
  EXPECT_TRUE((Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitZ()) * level).isApprox(R, 1e-12));
}

}  // namespace
}  // namespace hylo::localization
