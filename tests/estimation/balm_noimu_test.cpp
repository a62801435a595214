// Real scans without IMU (no-IMU mode: constant-velocity model, no deskewing) through the
// same pipeline, against the reference poses of the BALM benchmark scans (data README).
#include <gtest/gtest.h>

#include <cmath>

#include "hylo/config/run_config.h"
#include "hylo/logs/log_reader.h"
#include "hylo/logs/scan_folder.h"
#include "hylo/odometry/odometry_pipeline.h"
#include "hylo/run/session.h"
#include "test_data.h"
#include "estimation/param_printers.h"

namespace hylo::estimation {
namespace {

// One case per back-end, both from the shipped config/presets/handheld_noimu.yaml, so the figures are
// what `hylo map --config config/presets/handheld_noimu.yaml` gives. The target: 2 cm / 0.2 deg RMSE
// against the first pose. The data README notes the reference poses agree with scan-to-scan
// ICP within ~1.5 cm / 0.14 deg, so a drifting SLAM run sits near 2 cm by construction;
// measured 1.85 cm / 0.10 deg with either back-end (the robust registration starts every
// update in its basin; handheld_robust_test runs every stretch). Per-scan figures print.
struct BalmCase {
  Estimator::Backend backend;
};
void PrintTo(const BalmCase& c, std::ostream* os) { *os << ToString(c.backend); }

class BalmScansNoImu : public ::testing::TestWithParam<BalmCase> {};

TEST_P(BalmScansNoImu, PosesStayWithinTwoCentimetresAndPointTwoDegreesOfTheReference) {
  HYLO_REQUIRE_DATA("balm_scans/poses.csv");
  const std::string dir = hylo::testing::DataPath("balm_scans");
  const config::RunConfig run =
      config::LoadRunConfig(std::string(HYLO_SOURCE_DIR) + "/config/presets/handheld_noimu.yaml");
  odometry::OdometryPipelineOptions options = run.PipelineOptions();
  ASSERT_FALSE(options.imu.enabled);
  options.estimator.backend = GetParam().backend;
  run::Session session(options, run::SessionKeeps{true, false});
  logs::LogReadOptions read;
  read.imu_topic.clear();
  auto log = logs::OpenLog(dir, read);
  logs::LogMessage message;
  while (log->Next(&message)) {
    if (message.kind != logs::LogMessage::Kind::kScan) continue;
    session.AddScan(std::move(message.scan));
  }
  session.Finish();
  const std::vector<odometry::ScanResult>& results = session.results();
  const std::vector<io::StampedPose> reference = logs::ReadScanFolderPoses(dir);
  ASSERT_GE(results.size(), 18u);
  std::size_t compared = 0;
  double sum_sq_m = 0.0, sum_sq_deg = 0.0;
  Eigen::Isometry3d T_ref_est = Eigen::Isometry3d::Identity();
  for (const odometry::ScanResult& r : results) {
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
  EXPECT_LE(rmse_m, 0.02);
  EXPECT_LE(rmse_deg, 0.2);
}

INSTANTIATE_TEST_SUITE_P(
    Backends, BalmScansNoImu,
    ::testing::Values(BalmCase{Estimator::Backend::kIeskf},
                      BalmCase{Estimator::Backend::kSlidingWindow}),
    [](const auto& info) { return ToString(info.param.backend); });

}  // namespace
}  // namespace hylo::estimation
