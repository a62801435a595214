// The robust registration on a synthetic, deliberately asymmetric room: its basin over a grid
// of yaw, tilt and offset errors, the quality check that retries from yaw hypotheses, the
// adaptive threshold (KISS-ICP's model error) and the options' validation.
#include "hylo/estimation/robust_registration.h"

#include <gtest/gtest.h>

#include <cmath>

#include "hylo/mapping/map_manager.h"

namespace hylo::estimation {
namespace {

using lie::SE3d;
using lie::SO3d;

constexpr double kDeg = M_PI / 180.0;

// Points on an axis-aligned rectangle, `spacing` apart.
void AddFace(int fixed_axis, double fixed, Eigen::Vector2d lo, Eigen::Vector2d hi, double spacing,
             PointCloud* points) {
  const int a = (fixed_axis + 1) % 3, b = (fixed_axis + 2) % 3;
  for (double u = lo.x(); u <= hi.x() + 1e-9; u += spacing) {
    for (double v = lo.y(); v <= hi.y() + 1e-9; v += spacing) {
      Eigen::Vector3f p;
      p[fixed_axis] = static_cast<float>(fixed);
      p[a] = static_cast<float>(u);
      p[b] = static_cast<float>(v);
      points->push_back(p);
    }
  }
}

// A 14 m × 9 m room, 3.5 m high, with a low block, a partition and a pillar placed so that no
// rotation about z maps the scene onto itself.
PointCloud Scene(double spacing) {
  PointCloud p;
  AddFace(2, 0.0, {-7, -4.5}, {7, 4.5}, spacing, &p);
  AddFace(2, 3.5, {-7, -4.5}, {7, 4.5}, spacing, &p);
  AddFace(0, -7.0, {-4.5, 0}, {4.5, 3.5}, spacing, &p);
  AddFace(0, 7.0, {-4.5, 0}, {4.5, 3.5}, spacing, &p);
  AddFace(1, -4.5, {0, -7}, {3.5, 7}, spacing, &p);
  AddFace(1, 4.5, {0, -7}, {3.5, 7}, spacing, &p);
  AddFace(2, 1.2, {2, -3.5}, {5, -2}, spacing, &p);     // block top
  AddFace(0, 2.0, {-3.5, 0}, {-2, 1.2}, spacing, &p);   // block side
  AddFace(1, 1.0, {-4, 0}, {-1, 2.5}, spacing, &p);     // partition
  AddFace(0, -2.0, {-1.5, 0}, {-1, 3.5}, spacing, &p);  // pillar faces
  AddFace(1, -1.5, {-2.5, 0}, {-2, 3.5}, spacing, &p);
  return p;
}

class RobustRegistrationTest : public ::testing::Test {
 protected:
  RobustRegistrationTest()
      : map_(MapOptions()), planes_(map_, registration::PlaneMatcherOptions{}) {
    map_.AddScan(Scene(0.1), Eigen::Vector3f::Zero());
    // The scan: the same surfaces at another spacing (few points coincide with the map's),
    // in the sensor frame.
    const SE3d T_lidar_map = T_true_.Inverse();
    for (const Eigen::Vector3f& p : Scene(0.23)) {
      scan_.push_back((T_lidar_map * p.cast<double>()).cast<float>());
    }
  }
  static mapping::MapManagerOptions MapOptions() {
    mapping::MapManagerOptions o;
    o.voxel_size_m = 0.1;
    return o;
  }
  static RobustRegistrationOptions Enabled(double deviation_m) {
    RobustRegistrationOptions o;
    o.enabled = true;
    o.coarse_voxel_m = 0.6;  // the room is small: ~1k points in the subset
    o.initial_deviation_m = deviation_m;
    return o;
  }
  // The start `yaw_deg` about the map z axis, `tilt_deg` about a horizontal axis and
  // `offset_m` horizontally off the true pose.
  SE3d Start(double yaw_deg, double tilt_deg, double offset_m) const {
    const SO3d R = SO3d::Exp(tilt_deg * kDeg * Eigen::Vector3d(0.6, 0.8, 0.0)) *
                   SO3d::Exp(Eigen::Vector3d(0.0, 0.0, yaw_deg * kDeg)) * T_true_.so3();
    return SE3d(R, T_true_.translation() + offset_m * Eigen::Vector3d(0.8, -0.6, 0.0));
  }
  static double TranslationError(const SE3d& a, const SE3d& b) {
    return (a.translation() - b.translation()).norm();
  }
  static double RotationErrorDeg(const SE3d& a, const SE3d& b) {
    return (a.so3().Inverse() * b.so3()).Log().norm() / kDeg;
  }

  const SE3d T_true_{SO3d::Exp(Eigen::Vector3d(0.02, -0.03, 0.4)), Eigen::Vector3d(1.0, 0.5, 1.4)};
  mapping::MapManager map_;
  registration::PlaneMatcher planes_;
  PointCloud scan_;
};

TEST_F(RobustRegistrationTest, IcpConvergesFromAGridOfYawErrorsWithTiltAndOffset) {
  // The settings a learnt deviation of 6 m gives (what hand-held turns of 10-30° give at
  // ~20 m range): the first kernel is 2 m wide and the basin covers ±50° of yaw.
  PlaneIcpSettings settings;
  settings.gate_m = 18.0;
  settings.kernel_m = 2.0;
  for (int yaw = -50; yaw <= 50; yaw += 10) {
    for (const auto& [tilt, offset] : {std::pair{0.0, 0.0}, std::pair{8.0, 0.6}}) {
      const PlaneIcpResult r =
          AlignPointToPlane(scan_, Start(yaw, tilt, offset), planes_, settings);
      EXPECT_TRUE(r.converged) << "yaw " << yaw << ", tilt " << tilt << ", offset " << offset;
      EXPECT_LT(TranslationError(r.T_map_lidar, T_true_), 0.02)
          << "yaw " << yaw << ", tilt " << tilt << ", offset " << offset;
      EXPECT_LT(RotationErrorDeg(r.T_map_lidar, T_true_), 0.2)
          << "yaw " << yaw << ", tilt " << tilt << ", offset " << offset;
    }
  }
}

TEST_F(RobustRegistrationTest, RetriesFromYawHypothesesWhenTheInlierCheckFails) {
  // A narrow threshold (0.3 m: kernel 0.1 m) cannot pull in 55° of yaw by itself.
  RobustRegistrationOptions options = Enabled(0.3);
  const auto with_history = [this](const RobustRegistrationOptions& o) {
    RobustRegistration robust(o);
    for (int i = 0; i < 3; ++i) {  // accepted scans at the true pose fill the inlier history
      robust.Align(scan_, T_true_, planes_);
      robust.Observe(T_true_, T_true_);
    }
    return robust;
  };
  RobustRegistration robust = with_history(options);
  const RobustAlignment retried = robust.Align(scan_, Start(55.0, 0.0, 0.3), planes_);
  EXPECT_GT(retried.attempts, 1);
  EXPECT_TRUE(retried.passed);
  EXPECT_GT(retried.inlier_ratio, options.min_inlier_share * retried.reference_ratio);
  EXPECT_LT(TranslationError(retried.T_map_lidar, T_true_), 0.02);
  EXPECT_LT(RotationErrorDeg(retried.T_map_lidar, T_true_), 0.2);

  options.min_inlier_share = 0.0;  // the check off: the wrong basin is kept
  RobustRegistration unchecked = with_history(options);
  const RobustAlignment kept = unchecked.Align(scan_, Start(55.0, 0.0, 0.3), planes_);
  EXPECT_EQ(kept.attempts, 1);
  EXPECT_GT(RotationErrorDeg(kept.T_map_lidar, T_true_), 5.0);
}

TEST_F(RobustRegistrationTest, TriesEveryHypothesisOnTheFirstAlignment) {
  // Nothing to compare the first alignment with: the prediction, the 2 × 60/15 yaw hypotheses
  // (on the sparser subset) and the refinement of the best.
  RobustRegistration robust(Enabled(0.3));
  const RobustAlignment a = robust.Align(scan_, Start(-55.0, 0.0, 0.3), planes_);
  EXPECT_EQ(a.attempts, 10);
  EXPECT_TRUE(a.passed);
  EXPECT_LT(TranslationError(a.T_map_lidar, T_true_), 0.02);
  EXPECT_LT(RotationErrorDeg(a.T_map_lidar, T_true_), 0.2);
}

TEST_F(RobustRegistrationTest, LearnsTheMotionModelDeviationAsKissIcp) {
  RobustRegistration robust(Enabled(2.0));
  EXPECT_DOUBLE_EQ(robust.Deviation(), 2.0);
  robust.Align(scan_, T_true_, planes_);
  double max_range = 0.0;
  for (const Eigen::Vector3f& p : scan_) max_range = std::max<double>(max_range, p.norm());
  const SE3d off(SO3d::Exp(Eigen::Vector3d(0.0, 0.0, 10.0 * kDeg)), Eigen::Vector3d(0.3, 0, 0));
  robust.Observe(T_true_, T_true_ * off);
  // The subset keeps one point per voxel, so its farthest point is within a voxel of the
  // scan's.
  const double expected = 0.3 + 2.0 * max_range * std::sin(5.0 * kDeg);
  EXPECT_NEAR(robust.Deviation(), expected, 2.0 * std::sin(5.0 * kDeg) * 0.6 * std::sqrt(3.0));
  const double learnt = robust.Deviation();
  robust.Observe(T_true_, T_true_ * SE3d(SO3d(), Eigen::Vector3d(0.01, 0, 0)));  // below min
  EXPECT_DOUBLE_EQ(robust.Deviation(), learnt);
}

TEST(ModelDeviation, IsTheTranslationPlusTheChordAtMaximumRange) {
  EXPECT_DOUBLE_EQ(ModelDeviation(SE3d(SO3d(), Eigen::Vector3d(0.3, -0.4, 0.0)), 50.0), 0.5);
  const SE3d turn(SO3d::Exp(Eigen::Vector3d(0.0, 0.0, 60.0 * kDeg)), Eigen::Vector3d::Zero());
  EXPECT_NEAR(ModelDeviation(turn, 20.0), 20.0, 1e-9);  // 2 r sin(30°) = r
}

TEST(RobustRegistrationOptions, NamesTheFieldThatIsNotValid) {
  struct Case {
    const char* field;
    void (*breaks)(RobustRegistrationOptions*);
  };
  const Case cases[] = {
      {"coarse_voxel_m", [](RobustRegistrationOptions* o) { o->coarse_voxel_m = 0.0; }},
      {"max_iterations", [](RobustRegistrationOptions* o) { o->max_iterations = 0; }},
      {"initial_deviation_m", [](RobustRegistrationOptions* o) { o->initial_deviation_m = -1; }},
      {"min_deviation_m", [](RobustRegistrationOptions* o) { o->min_deviation_m = NAN; }},
      {"final_kernel_m", [](RobustRegistrationOptions* o) { o->final_kernel_m = 0.0; }},
      {"settle_fraction", [](RobustRegistrationOptions* o) { o->settle_fraction = 0.0; }},
      {"inlier_distance_m", [](RobustRegistrationOptions* o) { o->inlier_distance_m = INFINITY; }},
      {"min_inlier_share", [](RobustRegistrationOptions* o) { o->min_inlier_share = 1.5; }},
      {"inlier_history", [](RobustRegistrationOptions* o) { o->inlier_history = 0; }},
      {"retry_yaw_range_deg", [](RobustRegistrationOptions* o) { o->retry_yaw_range_deg = 200; }},
      {"retry_yaw_step_deg", [](RobustRegistrationOptions* o) { o->retry_yaw_step_deg = 0.0; }},
  };
  std::string why;
  EXPECT_TRUE(RobustRegistrationOptions{}.IsValid(&why)) << why;
  for (const Case& c : cases) {
    RobustRegistrationOptions o;
    c.breaks(&o);
    EXPECT_FALSE(o.IsValid(&why)) << c.field;
    EXPECT_EQ(why.rfind(c.field, 0), 0u) << why;
  }
}

}  // namespace
}  // namespace hylo::estimation
