// What the IESKF reports of the extrinsic it estimates online: nothing unless asked, then the
// state's T_imu_lidar against the one it first started from, with sigmas from its covariance
// in the report's convention (a correction applied on the left of the configured rotation).
#include <gtest/gtest.h>

#include <cmath>

#include "hylo/estimation/ieskf/ieskf.h"

namespace hylo::estimation {
namespace {

using namespace state_index;  // NOLINT

NavState StateWithExtrinsic(const lie::SE3d& T_imu_lidar) {
  NavState x;
  x.t_ns = 1'000'000'000;
  x.T_imu_lidar = T_imu_lidar;
  return x;
}

TEST(IeskfCalibration, NothingIsReportedUnlessTheFilterEstimatesTheExtrinsic) {
  EstimatorOptions options;
  Ieskf filter(options, ImuOptions());
  filter.Initialize(StateWithExtrinsic(lie::SE3d()), StateCovariance::Identity());
  const OnlineCalibration c = filter.Calibration();
  EXPECT_FALSE(c.extrinsic_rotation_estimated);
  EXPECT_FALSE(c.extrinsic_translation_estimated);
  EXPECT_FALSE(c.time_offset_estimated);
}

// A restart carries the estimate on (the supervisor passes the filter's own state back): the
// correction is still measured from the first start's extrinsic, the configuration's.
TEST(IeskfCalibration, ACorrectionIsMeasuredFromTheFirstStartsExtrinsic) {
  EstimatorOptions options;
  options.ieskf.online_extrinsic = true;
  Ieskf filter(options, ImuOptions());
  const lie::SE3d configured(lie::SO3d::Exp(Eigen::Vector3d(0.3, -0.2, 1.0)),
                             Eigen::Vector3d(0.1, 0.0, 0.25));
  StateCovariance P = StateCovariance::Identity() * 1e-4;
  // Right-perturbation sigmas of 1, 2 and 3 degrees about the extrinsic's own axes.
  const Eigen::Vector3d sigma_right_rad = Eigen::Vector3d(1.0, 2.0, 3.0) * M_PI / 180.0;
  P.block<3, 3>(kExtrinsicRotation, kExtrinsicRotation) =
      sigma_right_rad.cwiseAbs2().asDiagonal();
  P.block<3, 3>(kExtrinsicTranslation, kExtrinsicTranslation).diagonal() =
      Eigen::Vector3d(0.01, 0.02, 0.03).cwiseAbs2();
  filter.Initialize(StateWithExtrinsic(configured), P);
  OnlineCalibration c = filter.Calibration();
  ASSERT_TRUE(c.extrinsic_rotation_estimated && c.extrinsic_translation_estimated);
  EXPECT_LT(c.extrinsic_rotation_correction_rad.norm(), 1e-12);
  EXPECT_LT(c.extrinsic_translation_correction_m.norm(), 1e-12);
  EXPECT_NEAR(c.extrinsic_translation_sigma_m.z(), 0.03, 1e-12);
  // The sigmas turned into the IMU frame: the same total, the same as R·Σ·Rᵀ's diagonal.
  EXPECT_NEAR(c.extrinsic_rotation_sigma_rad.squaredNorm(), sigma_right_rad.squaredNorm(), 1e-12);
  const Eigen::Matrix3d R = configured.so3().Matrix();
  const Eigen::Matrix3d turned = R * sigma_right_rad.cwiseAbs2().asDiagonal() * R.transpose();
  EXPECT_NEAR(c.extrinsic_rotation_sigma_rad.x(), std::sqrt(turned(0, 0)), 1e-12);

  const Eigen::Vector3d rotation_correction(0.01, -0.02, 0.005);
  const Eigen::Vector3d translation_correction(0.02, -0.01, 0.0);
  const lie::SE3d estimated(lie::SO3d::Exp(rotation_correction) * configured.so3(),
                            configured.translation() + translation_correction);
  filter.Initialize(StateWithExtrinsic(estimated), P);
  c = filter.Calibration();
  EXPECT_LT((c.extrinsic_rotation_correction_rad - rotation_correction).norm(), 1e-12);
  EXPECT_LT((c.extrinsic_translation_correction_m - translation_correction).norm(), 1e-12);
}

}  // namespace
}  // namespace hylo::estimation
