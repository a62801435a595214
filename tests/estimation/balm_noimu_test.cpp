// Real scans without IMU (no-IMU mode: constant-velocity model, no deskewing) through the
// same pipeline, against the reference poses of the BALM benchmark scans (data README).
#include <gtest/gtest.h>

#include <cmath>

#include "hylo/estimation/odometry_pipeline.h"
#include "hylo/io/log_reader.h"
#include "hylo/io/scan_folder.h"
#include "test_data.h"
#include "estimation/param_printers.h"

namespace hylo::estimation {
namespace {

// One case per back-end. Issue 5's target is 2 cm / 0.2 deg RMSE; it is NOT met yet:
// measured IESKF 0.053 m / 1.87 deg, smoother 0.076 m / 2.56 deg (the same scans, 8, 9, 11,
// 12 and 19, with large hand-held rotations, do not converge in either; the others drift by
// 1.5-4 cm). The bounds below guard what works today against regressions; the per-scan
// figures are printed on every run.
struct BalmCase {
  Estimator::Backend backend;
  double max_rmse_m, max_rmse_deg;  // regression guards, not the target
};
void PrintTo(const BalmCase& c, std::ostream* os) { *os << ToString(c.backend); }

class BalmScansNoImu : public ::testing::TestWithParam<BalmCase> {};

TEST_P(BalmScansNoImu, PosesStayNearTheReferenceTargetNotYetMet) {
  HYLO_REQUIRE_DATA("balm_scans/poses.csv");
  const std::string dir = hylo::testing::DataPath("balm_scans");
  OdometryPipelineOptions options;
  options.estimator.backend = GetParam().backend;
  options.estimator.use_imu = false;
  options.preprocess.scan_voxel_m = 0.3f;
  options.map.voxel_size_m = 0.3f;
  // A hand-held sensor sampled at 2 Hz turns up to ~30 deg between scans (poses.csv).
  options.estimator.ieskf.no_imu_yaw_search_deg = 60.0;
  options.estimator.ieskf.max_iterations = 10;
  options.estimator.sliding_window.no_imu_yaw_search_deg = 60.0;
  options.estimator.sliding_window.max_iterations = 10;
  // As many plane searches per scan as the IESKF's 10 iterations; no wall-time cut in a test.
  options.estimator.sliding_window.association_rounds = 10;
  options.estimator.sliding_window.max_solver_time_s = 10.0;
  OdometryPipeline pipeline(options);
  io::LogReadOptions read;
  read.imu_topic.clear();
  auto log = io::OpenLog(dir, read);
  io::LogMessage message;
  std::vector<ScanResult> results;
  while (log->Next(&message)) {
    if (message.kind != io::LogMessage::Kind::kScan) continue;
    pipeline.AddScan(std::move(message.scan));
    pipeline.Process(&results);
  }
  pipeline.Process(&results, true);
  const std::vector<io::StampedPose> reference = io::ReadScanFolderPoses(dir);
  ASSERT_GE(results.size(), 18u);
  std::size_t compared = 0;
  double sum_sq_m = 0.0, sum_sq_deg = 0.0;
  Eigen::Isometry3d T_ref_est = Eigen::Isometry3d::Identity();
  for (const ScanResult& r : results) {
    const io::StampedPose* ref = nullptr;
    for (const io::StampedPose& p : reference) {
      if (p.t_ns == r.t_ns) ref = &p;
    }
    ASSERT_NE(ref, nullptr) << "no reference pose at " << r.t_ns;
    const Eigen::Isometry3d est(r.state.T_map_lidar().Matrix());
    if (compared == 0) T_ref_est = ref->T_world_body() * est.inverse();  // align the first pose
    const Eigen::Isometry3d aligned = T_ref_est * est;
    const Eigen::Isometry3d truth = ref->T_world_body();
    const double e = (aligned.translation() - truth.translation()).norm();
    const double a = Eigen::AngleAxisd(aligned.linear().transpose() * truth.linear()).angle();
    std::printf("  scan %2zu: %.4f m, %.3f deg, %d iterations, %zu matches%s\n", compared, e,
                a * 180.0 / M_PI, r.update.iterations, r.update.num_matches,
                r.update.message.empty() ? "" : (", " + r.update.message).c_str());
    sum_sq_m += e * e;
    sum_sq_deg += std::pow(a * 180.0 / M_PI, 2);
    ++compared;
  }
  const double rmse_m = std::sqrt(sum_sq_m / compared);
  const double rmse_deg = std::sqrt(sum_sq_deg / compared);
  std::printf("%s, balm_scans, %zu scans: RMSE %.4f m, %.4f deg\n",
              ToString(GetParam().backend).c_str(), compared, rmse_m, rmse_deg);
  EXPECT_LE(rmse_m, GetParam().max_rmse_m);
  EXPECT_LE(rmse_deg, GetParam().max_rmse_deg);
}

INSTANTIATE_TEST_SUITE_P(
    Backends, BalmScansNoImu,
    ::testing::Values(BalmCase{Estimator::Backend::kIeskf, 0.08, 2.5},
                      BalmCase{Estimator::Backend::kSlidingWindow, 0.10, 3.0}),
    [](const auto& info) { return ToString(info.param.backend); });

}  // namespace
}  // namespace hylo::estimation
