// ICP initializer on synthetic scenes (ground, walls, boxes): acceptance from a near guess,
// recovery by the search from a far one, and every rejection path: empty / NaN input, empty
// map, a flat plane (yaw and x/y unobservable), a partial overlap whose fitness alone would
// pass, a sparse map that the plane fitness gate does not mind, invalid options.
#include "hylo/localization/icp_initializer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>

#include "hylo/common/check.h"
#include "hylo/mapping/ikd_tree.h"
#include "hylo/registration/brute_force_search.h"
#include "hylo/registration/voxel_filter.h"
#include "icp_initializer_internal.h"
#include "registration/synthetic_scene.h"

namespace hylo::localization {
namespace {

using namespace registration::synthetic_scene;

class IcpInitializerTest : public ::testing::Test {
 protected:
  IcpInitializerTest()
      : tree_(Tree(Yard(0.1f, 1))),
        map_(*tree_),
        truth_(Pose(1.0, -2.0, 0.6, 35.0)),
        scan_(InBody(Yard(0.4f, 2), truth_, 0.01, 3)) {}
  std::unique_ptr<mapping::IkdTree> tree_;
  const registration::NeighborSearch& map_;
  Eigen::Isometry3d truth_;
  PointCloud scan_;
};

TEST_F(IcpInitializerTest, NearGuessIsAcceptedWithoutSearch) {
  const IcpInitializer initializer;
  const IcpInitializerResult r =
      initializer.Initialize(scan_, map_, truth_ * Pose(0.3, -0.2, 0.1, 4.0));
  ASSERT_TRUE(r.accepted) << r.message;
  EXPECT_EQ(r.hypotheses_tried, 1);
  EXPECT_EQ(r.accepted_hypothesis, 0);
  EXPECT_LT(TranslationError(r.T_map_imu, truth_), 0.02);
  EXPECT_LT(RotationErrorDeg(r.T_map_imu, truth_), 0.2);
  EXPECT_LT(r.fitness_score_m2, 0.01);
  EXPECT_LT(r.plane_fitness_m2, initializer.options().plane_fitness_threshold_m2);
  EXPECT_GT(r.inlier_ratio, 0.95);
  EXPECT_GT(r.constraint, initializer.options().min_constraint);
}

TEST_F(IcpInitializerTest, FarGuessIsRecoveredByTheSearch) {
  IcpInitializerOptions options;
  options.search_enabled = false;
  const Eigen::Isometry3d guess = Pose(-1.8, 1.5, 0.0, -28.0) * truth_;
  const IcpInitializerResult direct = IcpInitializer(options).Initialize(scan_, map_, guess);
  const IcpInitializerResult r = IcpInitializer().Initialize(scan_, map_, guess);
  ASSERT_TRUE(r.accepted) << r.message;
  EXPECT_LT(TranslationError(r.T_map_imu, truth_), 0.02);
  EXPECT_LT(RotationErrorDeg(r.T_map_imu, truth_), 0.2);
  if (!direct.accepted) {  // the case this test is about: the guess alone fails
    EXPECT_GT(r.hypotheses_tried, 1);
    EXPECT_GE(r.accepted_hypothesis, 0);
  }
  EXPECT_EQ(r.num_accepted_distinct, 1);
}

TEST_F(IcpInitializerTest, EmptyAndNanScansAreRejectedWithAMessage) {
  const IcpInitializer initializer;
  const Eigen::Isometry3d guess = truth_;
  const IcpInitializerResult empty = initializer.Initialize({}, map_, guess);
  EXPECT_FALSE(empty.accepted);
  EXPECT_NE(empty.message.find("finite scan points"), std::string::npos) << empty.message;
  EXPECT_TRUE(empty.T_map_imu.isApprox(guess));
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const PointCloud all_nan(500, Eigen::Vector3f(nan, 0.f, nan));
  const IcpInitializerResult r = initializer.Initialize(all_nan, map_, guess);
  EXPECT_FALSE(r.accepted);
  EXPECT_EQ(r.num_source_points, 0u);
}

TEST_F(IcpInitializerTest, NanPointsAmongGoodOnesAreSkipped) {
  PointCloud scan = scan_;
  for (std::size_t i = 0; i < scan.size(); i += 7) scan[i].x() = std::nanf("");
  const IcpInitializerResult r = IcpInitializer().Initialize(scan, map_, truth_);
  ASSERT_TRUE(r.accepted) << r.message;
  EXPECT_LT(TranslationError(r.T_map_imu, truth_), 0.02);
}

TEST_F(IcpInitializerTest, EmptyMapAndNonFiniteGuessAreRejected) {
  const IcpInitializer initializer;
  const registration::BruteForceSearch empty_map({});
  const IcpInitializerResult no_map = initializer.Initialize(scan_, empty_map, truth_);
  EXPECT_FALSE(no_map.accepted);
  EXPECT_NE(no_map.message.find("map is empty"), std::string::npos) << no_map.message;
  Eigen::Isometry3d bad = truth_;
  bad.translation().x() = std::nan("");
  const IcpInitializerResult r = initializer.Initialize(scan_, map_, bad);
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.message.find("not finite"), std::string::npos) << r.message;
}

TEST(IcpInitializerDegenerate, FlatPlaneIsReportedNotAccepted) {
  // Only ground: yaw and x/y are free, so ICP "converges" with a perfect fitness wherever it
  // starts. The constraint gate must refuse it (and the search then finds only such poses).
  std::mt19937 rng(5);
  PointCloud ground;
  AddRectangle({-20, -20, 0}, {40, 0, 0}, {0, 40, 0}, 0.1f, &rng, &ground);
  PointCloud patch;
  AddRectangle({-8, -8, 0}, {16, 0, 0}, {0, 16, 0}, 0.3f, &rng, &patch);
  const Eigen::Isometry3d truth = Pose(2, 1, 0.6, 20);
  const PointCloud scan = InBody(patch, truth, 0.005, 6);
  const IcpInitializerResult r =
      IcpInitializer().Initialize(scan, *Tree(ground), Pose(2.5, 1, 0.6, 30));
  EXPECT_FALSE(r.accepted) << r.message;
  EXPECT_LT(r.best_fitness_score_m2, 0.01);  // the fitness alone would have accepted
  EXPECT_LT(r.best_plane_fitness_m2, IcpInitializerOptions().plane_fitness_threshold_m2);
  EXPECT_LT(r.best_constraint, IcpInitializerOptions().min_constraint);
  EXPECT_NE(r.message.find("constraint"), std::string::npos) << r.message;
}

TEST_F(IcpInitializerTest, PartialOverlapWithLowFitnessIsRejected) {
  // Half the scan sees structures the map does not hold (3 m farther than any map surface):
  // the matched half fits perfectly, so the range-limited fitness is low; the inlier ratio
  // is not.
  PointCloud scan = scan_;
  std::mt19937 rng(9);
  PointCloud unknown;
  AddRectangle({-15, -15, 8}, {30, 0, 0}, {0, 30, 0}, 0.2f, &rng, &unknown);
  for (const Eigen::Vector3f& p : InBody(unknown, truth_, 0.0, 1)) scan.push_back(p);
  IcpInitializerOptions options;
  options.search_enabled = false;
  const IcpInitializerResult r = IcpInitializer(options).Initialize(scan, map_, truth_);
  EXPECT_FALSE(r.accepted) << r.message;
  EXPECT_LT(r.best_fitness_score_m2, 0.01);
  EXPECT_LT(r.best_plane_fitness_m2, options.plane_fitness_threshold_m2);
  EXPECT_LT(r.best_inlier_ratio, options.min_inlier_ratio);
}

// A sparse map (the yard's ground on a 0.25 m grid, its walls and boxes at 0.25 m): the right
// pose lies between the map's points, so the paper's nearest-point fitness exceeds its 0.01 m^2
// there, while the distance to the map's planes does not depend on the spacing. A pose 10 cm
// too high (and 15 cm along x) is still refused by the plane fitness.
TEST(IcpInitializerSparseMap, TheGateDoesNotDependOnTheMapSpacing) {
  PointCloud sparse;
  for (float y = -15.f; y <= 15.f; y += 0.25f) {
    for (float x = -15.f; x <= 15.f; x += 0.25f) sparse.emplace_back(x, y, 0.f);
  }
  for (const Eigen::Vector3f& p : Yard(0.25f, 4)) {
    if (p.z() > 0.05f) sparse.push_back(p);
  }
  const auto tree = Tree(sparse);
  const Eigen::Isometry3d truth = Pose(1.0, -2.0, 0.6, 35.0);
  const PointCloud scan = InBody(Yard(0.05f, 5), truth, 0.01, 6);
  IcpInitializerOptions options;
  options.search_enabled = false;
  const IcpInitializerResult r = IcpInitializer(options).Initialize(scan, *tree, truth);
  ASSERT_TRUE(r.accepted) << r.message;
  EXPECT_GT(r.fitness_score_m2, 0.01) << "the paper's gate would have refused the right pose";
  EXPECT_LT(TranslationError(r.T_map_imu, truth), 0.05);
  // The measures themselves, without ICP moving the pose: right, and off.
  const PointCloud fine = registration::UniformSample(scan, static_cast<float>(options.fine_voxel_m));
  const internal::PoseQuality at_truth = internal::MeasureQuality(fine, *tree, truth, options);
  EXPECT_GT(at_truth.fitness_score_m2, 0.01);
  EXPECT_LT(at_truth.plane_fitness_m2, 0.25 * options.plane_fitness_threshold_m2);
  const internal::PoseQuality off =
      internal::MeasureQuality(fine, *tree, Pose(0.15, 0.0, 0.1, 0.0) * truth, options);
  EXPECT_GT(off.plane_fitness_m2, options.plane_fitness_threshold_m2);
}

TEST(IcpInitializerOptions, IsValidNamesTheField) {
  std::string why;
  EXPECT_TRUE(IcpInitializerOptions().IsValid(&why)) << why;
  IcpInitializerOptions o;
  o.min_inlier_ratio = 1.5;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("min_inlier_ratio = 1.5"), std::string::npos) << why;
  o = IcpInitializerOptions();
  o.coarse_voxel_m = 0.1;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("coarse_voxel_m"), std::string::npos) << why;
  o = IcpInitializerOptions();
  o.fine_icp.max_iterations = 0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("fine_icp.max_iterations"), std::string::npos) << why;
  o = IcpInitializerOptions();
  o.plane_fitness_threshold_m2 = 0.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("plane_fitness_threshold_m2"), std::string::npos) << why;
  o = IcpInitializerOptions();
  o.fitness_threshold_m2 = -1.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("fitness_threshold_m2"), std::string::npos) << why;
  o = IcpInitializerOptions();
  o.yaw_step_deg = 0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_THROW(IcpInitializer{o}, InternalError);
}

TEST(IcpInitializerGravity, GuessLevelsTheMeasuredUpDirection) {
  // An IMU pitched by 10 deg and rolled by -5 deg measures "up" in its own frame.
  const Eigen::Matrix3d R_true = (Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                                  Eigen::AngleAxisd(10 * kDeg, Eigen::Vector3d::UnitY()) *
                                  Eigen::AngleAxisd(-5 * kDeg, Eigen::Vector3d::UnitX()))
                                     .toRotationMatrix();
  const Eigen::Vector3d force_imu = R_true.transpose() * Eigen::Vector3d(0, 0, 9.81);
  const Eigen::Isometry3d T = GuessFromGravity(Eigen::Vector3d(1, 2, 3), 0.3, force_imu);
  EXPECT_LT((T.linear() * force_imu.normalized() - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
  EXPECT_TRUE(T.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_THROW(GuessFromGravity(Eigen::Vector3d::Zero(), 0.0, Eigen::Vector3d::Zero()),
               InternalError);
}

}  // namespace
}  // namespace hylo::localization
