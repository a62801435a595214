// Localization on real scans without IMU: a prior map is built from the
// even-numbered BALM scans at their reference poses, the odd-numbered scans are localized in
// it (no-IMU mode) from a perturbed first pose, and every pose is compared with poses.csv.
// No alignment: the prior map is in the reference frame, so the error is absolute. The same
// run with the whole world moved to UTM-sized coordinates must give the same result (the prior
// map keeps a local origin; float positions far from zero would lose centimetres).
#include <gtest/gtest.h>

#include <cmath>

#include "hylo/logs/log_reader.h"
#include "hylo/logs/scan_folder.h"
#include "hylo/mapping/prior_map.h"
#include "hylo/odometry/odometry_pipeline.h"
#include "hylo/run/session.h"
#include "test_data.h"

namespace hylo::estimation {
namespace {

const io::StampedPose* PoseAt(const std::vector<io::StampedPose>& poses, int64_t t_ns) {
  for (const io::StampedPose& p : poses) {
    if (p.t_ns == t_ns) return &p;
  }
  return nullptr;
}

class BalmLocalization : public ::testing::TestWithParam<Eigen::Vector3d> {};

TEST_P(BalmLocalization, OddScansInAMapOfTheEvenScans) {
  HYLO_REQUIRE_DATA("balm_scans/poses.csv");
  const std::string dir = hylo::testing::DataPath("balm_scans");
  const Eigen::Vector3d world_offset = GetParam();
  std::vector<io::StampedPose> reference = logs::ReadScanFolderPoses(dir);
  for (io::StampedPose& p : reference) p.position += world_offset;
  logs::LogReadOptions read;
  read.imu_topic.clear();
  auto log = logs::OpenLog(dir, read);
  std::vector<LidarScan> odd;
  std::vector<Eigen::Vector3d> map_world;
  logs::LogMessage message;
  for (std::size_t index = 0; log->Next(&message);) {
    if (message.kind != logs::LogMessage::Kind::kScan) continue;
    if (index++ % 2 == 1) {
      odd.push_back(std::move(message.scan));
      continue;
    }
    const io::StampedPose* pose = PoseAt(reference, message.scan.t_ns);
    ASSERT_NE(pose, nullptr);
    const Eigen::Isometry3d T_world_lidar = pose->T_world_body();
    for (const auto& p : message.scan.points) {
      map_world.push_back(T_world_lidar * p.position_lidar.cast<double>());
    }
  }
  ASSERT_GE(odd.size(), 9u);
  odometry::OdometryPipelineOptions options;
  options.imu.enabled = false;
  options.preprocess.scan_voxel_m = 0.3;
  // Odd scans are 1 s apart and the hand-held sensor turns up to ~60 deg in that time.
  options.estimator.no_imu.yaw_search_deg = 90.0;
  options.estimator.ieskf.max_iterations = 10;
  options.localization.update_after_s = -1.0;
  // Without IMU at 1 Hz the constant-velocity prediction is often tens of degrees off: every
  // scan that fits the map badly is registered again by the initializer around the
  // prediction (a wider yaw sweep), then refined by the usual update.
  options.localization.lost_after_scans = 1;
  options.localization.icp.yaw_range_deg = 45.0;
  run::Session session(options);
  const io::StampedPose* first = PoseAt(reference, odd.front().t_ns);
  ASSERT_NE(first, nullptr);
  Eigen::Isometry3d guess_world = first->T_world_body();
  guess_world.translation() += Eigen::Vector3d(0.8, -0.6, 0.1);
  guess_world.linear() = Eigen::AngleAxisd(10.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()) *
                         guess_world.linear();
  session.SetPriorMap(map_world, mapping::PriorMapOptions(), guess_world);

  for (LidarScan& scan : odd) session.AddScan(std::move(scan));
  session.Finish();
  ASSERT_FALSE(session.failed()) << session.pipeline().message();
  const std::vector<odometry::ScanResult>& results = session.results();
  ASSERT_EQ(results.size(), odd.size());
  double sum_sq_m = 0.0, sum_sq_deg = 0.0;
  for (std::size_t i = 0; i < results.size(); ++i) {
    const io::StampedPose* ref = PoseAt(reference, results[i].t_ns);
    ASSERT_NE(ref, nullptr);
    const Eigen::Isometry3d est = mapping::PoseToWorld(
        Eigen::Isometry3d(results[i].state.T_map_lidar().Matrix()), session.origin_world());
    const Eigen::Isometry3d truth = ref->T_world_body();
    const double e = (est.translation() - truth.translation()).norm();
    const double a = Eigen::AngleAxisd(est.linear().transpose() * truth.linear()).angle() *
                     180.0 / M_PI;
    std::printf("  odd scan %zu: %.4f m, %.3f deg, %zu matches, health inliers %.3f\n", i, e, a,
                results[i].update.num_matches, results[i].health.inlier_ratio);
    sum_sq_m += e * e;
    sum_sq_deg += a * a;
  }
  const double rmse_m = std::sqrt(sum_sq_m / results.size());
  const double rmse_deg = std::sqrt(sum_sq_deg / results.size());
  std::printf("balm localization, %zu odd scans: RMSE %.4f m, %.4f deg (target 0.02 m, 0.2 deg)\n",
              results.size(), rmse_m, rmse_deg);
  EXPECT_LE(rmse_m, 0.02);
  EXPECT_LE(rmse_deg, 0.2);
}

INSTANTIATE_TEST_SUITE_P(
    WorldOffsets, BalmLocalization,
    ::testing::Values(Eigen::Vector3d::Zero(), Eigen::Vector3d(512345.0, 4212345.0, 120.0)),
    [](const auto& info) { return info.param.isZero() ? "AsRecorded" : "UtmSized"; });

}  // namespace
}  // namespace hylo::estimation
