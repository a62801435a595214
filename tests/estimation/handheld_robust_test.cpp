// Lidar-only odometry must hold on real hand-held data with one configuration: every stretch
// of the data README through both back-ends with the shipped config/presets/handheld_noimu.yaml, at
// the recorded 2 Hz and with every other scan dropped (1 Hz: the motion between two scans
// doubles, up to 69° and 1.1 m off the constant-velocity prediction). The bounds are the
// targets of the lidar-only path (ATE ≤ 3 cm after SE(3) alignment, no one-scan step off by
// more than 8 cm or 1°), not the measured figures: a run that loses track is off by metres
// and tens of degrees. Figures are in the README table (hylo_handheld_benchmark).
#include <gtest/gtest.h>

#include <cstdio>

#include "estimation/handheld_stretch.h"
#include "hylo/config/run_config.h"
#include "test_data.h"

namespace hylo::estimation {
namespace {

struct HandheldCase {
  std::string stretch;
  Estimator::Backend backend;
  int stride;
};

std::string CaseName(const HandheldCase& c) {
  return c.stretch + "_" + ToString(c.backend) + "_stride" + std::to_string(c.stride);
}
void PrintTo(const HandheldCase& c, std::ostream* os) { *os << CaseName(c); }

class HandheldStretch : public ::testing::TestWithParam<HandheldCase> {};

TEST_P(HandheldStretch, TracksWithinThreeCentimetresAndNoStepOffByMoreThanEightCmOrOneDegree) {
  const HandheldCase& c = GetParam();
  HYLO_REQUIRE_DATA(c.stretch + "/poses.csv");
  config::RunConfig run =
      config::LoadRunConfig(std::string(HYLO_SOURCE_DIR) + "/config/presets/handheld_noimu.yaml");
  run.pipeline.estimator.backend = c.backend;
  const hylo::testing::StretchRun r = hylo::testing::RunStretch(hylo::testing::DataPath(c.stretch),
                                                                run.PipelineOptions(), c.stride);
  for (const odometry::ScanResult& s : r.results) {
    const RobustAlignment& a = s.update.robust;
    std::printf(
        "  %.3f: %.1f ms, %zu matches, %d iterations; robust: deviation %.2f m, %d "
        "attempts, %d iterations, inliers %.2f of %zu (history %.2f)%s\n",
        s.t_ns * 1e-9, s.cpu_ms, s.update.num_matches, s.update.iterations, a.deviation_m,
        a.attempts, a.iterations, a.inlier_ratio, a.subset_points, a.reference_ratio,
        s.update.message.empty() ? "" : (", " + s.update.message).c_str());
  }
  std::printf(
      "%s: %zu scans, ATE %.2f cm / %.3f deg, worst step %.2f cm / %.3f deg, "
      "%zu retried\n",
      CaseName(c).c_str(), r.scans, 100.0 * r.ate.rmse_m, r.ate.rotation_rmse_deg,
      100.0 * r.worst_step_m, r.worst_step_deg, r.retried_scans);
  const std::size_t expected = (20 + c.stride - 1) / c.stride;
  ASSERT_EQ(r.scans, expected);
  ASSERT_TRUE(r.ate.ok) << r.ate.message;
  EXPECT_EQ(r.not_applied, 1u) << "only the first scan (empty map) goes without an update";
  EXPECT_LE(r.ate.rmse_m, 0.03);
  EXPECT_LE(r.worst_step_m, 0.08);
  EXPECT_LE(r.worst_step_deg, 1.0);
}

std::vector<HandheldCase> AllCases() {
  std::vector<HandheldCase> cases;
  for (const std::string& stretch : hylo::testing::HandheldStretches()) {
    for (Estimator::Backend b : {Estimator::Backend::kIeskf, Estimator::Backend::kSlidingWindow}) {
      for (int stride : {1, 2}) cases.push_back({stretch, b, stride});
    }
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(RealStretches, HandheldStretch, ::testing::ValuesIn(AllCases()),
                         [](const auto& info) { return CaseName(info.param); });

}  // namespace
}  // namespace hylo::estimation
