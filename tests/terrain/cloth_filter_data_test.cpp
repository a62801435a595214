// The cloth simulation filter on real data, skipped visibly when ../shared/data is absent:
// the ISPRS filter-test samples (type I / II / total error and kappa next to the CSF paper's
// published figures) and the reference implementation's split of csf_sample.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <unordered_set>
#include <vector>

#include "benchmarks/isprs_eval.h"
#include "hylo/io/cloud_io.h"
#include "hylo/terrain/cloth_filter.h"
#include "test_data.h"

namespace hylo::terrain {
namespace {

// Regression bounds on the ISPRS mean total error over the 7 samples, %. One parameter set for
// all samples (no per-file tuning). Measured: 6.09 with the defaults (RI 3) and 5.32 with RI 1
// (the paper's setting for rugged terrain); 6.59 / 6.19 before the slope post-processing left
// alone particles the cloth spans by more than slope_max_cloth_gap_m (samp21's bridge) and the
// low-outlier test used a fraction of a 30 m neighbourhood (samp41's multipath cluster); 7.19 /
// 6.71 before the distance to the cloth was measured to its surface. The paper reports 4.38 for
// these 7 samples with GR/RI/ST chosen per sample. What is left (type I / type II per sample,
// see the printed table): samp11 type I on its steep slopes and samp61 type I along embankments
// (ridges 1-8 m high that the cloth spans, floating more than the gap limit above them),
// samp52 type I on its steep eastern slope and along the data's upper edge plus type II from
// low vegetation. The bounds sit ~10 % above the measured figures so that a change making the
// filter worse fails, without flapping on harmless reorderings. A finer, stiffer cloth with the
// nearest fill (FineCloth below) meets the published mean: 4.25 %.
constexpr double kIsprsMeanTotalBoundDefaultsPercent = 6.7;
constexpr double kIsprsMeanTotalBoundRuggedPercent = 5.9;
// Agreement with the reference implementation's split of csf_sample when run as that release
// runs (its hole filling and its dT^2-twice gravity). Target 98 %; measured 99.65 %.
constexpr double kCsfSampleMinAgreement = 0.99;

using isprs::Confusion;
using isprs::KeyOf;
using isprs::PointKey;
using isprs::PointKeyHash;

Confusion EvaluateIsprsSample(const std::string& name, const ClothFilterOptions& options) {
  const isprs::Sample sample = isprs::LoadSample(name);
  const ClothFilterResult result = FilterGround(sample.points, options);
  EXPECT_TRUE(result.ok) << name << ": " << result.message;
  return isprs::Score(sample, result.labels);
}

struct IsprsSample {
  std::string name;
  double published_total_percent;  ///< CSF paper, Zhang et al. 2016
};
const std::vector<IsprsSample>& IsprsSamples() {
  static const std::vector<IsprsSample> samples = {
      {"samp11", 12.01}, {"samp21", 3.42}, {"samp31", 1.61}, {"samp41", 5.14},
      {"samp51", 3.08},  {"samp52", 3.93}, {"samp61", 1.49}};
  return samples;
}

/// Prints the table and returns the total error per sample (%, in IsprsSamples() order).
std::vector<double> PrintIsprsTable(const char* title, const ClothFilterOptions& options) {
  std::vector<double> totals;
  double sum_published = 0;
  std::printf("ISPRS, %s\nsample   typeI%%  typeII%%  total%%  kappa%%  | CSF paper total%%\n",
              title);
  for (const IsprsSample& sample : IsprsSamples()) {
    const Confusion c = EvaluateIsprsSample(sample.name, options);
    std::printf("%-7s %7.2f %8.2f %7.2f %7.2f  | %6.2f\n", sample.name.c_str(), 100 * c.TypeI(),
                100 * c.TypeII(), 100 * c.Total(), 100 * c.Kappa(), sample.published_total_percent);
    totals.push_back(100 * c.Total());
    sum_published += sample.published_total_percent;
  }
  double sum_total = 0;
  for (const double total : totals) sum_total += total;
  std::printf("mean    %24.2f  | %6.2f (paper, these 7; 4.39 over all 15)\n",
              sum_total / totals.size(), sum_published / totals.size());
  return totals;
}

double Mean(const std::vector<double>& values) {
  double sum = 0;
  for (const double v : values) sum += v;
  return sum / values.size();
}

// The target: the CSF paper's mean total error over these 7 samples (its GR/RI/ST
// chosen per sample), reached here with one setting for all of them.
constexpr double kPublishedMeanTotalPercent = 4.38;

// A cloth twice as fine as the point spacing allows on the rural samples (0.15 points/m^2),
// stiff (RI 6: the closed-form constraint factor is within 12 % of rigid), each particle landing
// at the height of the nearest measured particle (the paper's nearest-point definition; the
// neighbour mean ramps a building's edge into a slope the fine cloth slides down). Chosen among
// 15 settings (GR 1 with RI 1-3, GR 0.5 with RI 1-10, mean or nearest fill) on these same 7
// samples, so the figure is optimistic; leaving each sample out in turn and choosing on the
// other 6 picks this setting (or RI 10) every time, and the held-out errors average 4.27 %.
ClothFilterOptions FineCloth() {
  ClothFilterOptions options;
  options.cloth_resolution_m = 0.5;
  options.rigidness = 6;
  options.hole_fill = ClothHoleFill::kNearest;
  return options;
}

// One parameter set for every sample: the paper tuned GR/RI/ST per sample for its table.
TEST(ClothFilterIsprs, ErrorsPerSampleNextToThePublishedOnes) {
  HYLO_REQUIRE_DATA("isprs/samp11-utm.pcd");
  const std::vector<double> defaults = PrintIsprsTable("defaults (GR 1, RI 3, ST on)", {});
  ClothFilterOptions rugged;
  rugged.rigidness = 1;
  const std::vector<double> soft =
      PrintIsprsTable("rugged-terrain setting (GR 1, RI 1, ST on)", rugged);
  const std::vector<double> fine = PrintIsprsTable(
      "fine cloth for sparse airborne data (GR 0.5, RI 6, nearest fill, ST on)", FineCloth());
  RecordProperty("isprs_mean_total_error_defaults_percent", std::to_string(Mean(defaults)));
  RecordProperty("isprs_mean_total_error_ri1_percent", std::to_string(Mean(soft)));
  RecordProperty("isprs_mean_total_error_fine_percent", std::to_string(Mean(fine)));
  EXPECT_LE(Mean(defaults), kIsprsMeanTotalBoundDefaultsPercent);
  EXPECT_LE(Mean(soft), kIsprsMeanTotalBoundRuggedPercent);
  EXPECT_LE(Mean(fine), kPublishedMeanTotalPercent);
  // What the gap test and the outlier fraction fixed, against the paper's own per-sample figure
  // (its GR/RI/ST chosen for that sample; ours one setting): samp21's bridge (6.0 / 5.7 %
  // before) with both settings, samp41's multipath cluster (4.5 % before) with RI 1.
  const std::size_t samp21 = 1, samp41 = 3;
  EXPECT_LE(defaults[samp21], IsprsSamples()[samp21].published_total_percent);
  EXPECT_LE(soft[samp21], IsprsSamples()[samp21].published_total_percent);
  EXPECT_LE(soft[samp41], IsprsSamples()[samp41].published_total_percent);
}

// The reference implementation's split of csf_sample (rigidness 3, slope smoothing, GR 1,
// hcc 0.5, 500 iterations, dT 0.65 = the defaults), run with the two reference-release
// behaviours that our defaults deliberately do not follow (see ClothFilterOptions): the row/
// column hole filling, gravity scaled by dT^2 twice and the vertical point-to-cloth distance.
// With our defaults it agrees 97.6 %.
TEST(ClothFilterCsfSample, AgreesWithTheReferenceSplit) {
  HYLO_REQUIRE_DATA("csf_sample/sample.ply");
  const io::CloudFile cloud = io::ReadCloud(testing::DataPath("csf_sample/sample.ply"));
  std::unordered_set<PointKey, PointKeyHash> reference_ground;
  FILE* file = std::fopen(testing::DataPath("csf_sample/groundPoints_CSFmatlab.txt").c_str(), "r");
  ASSERT_NE(file, nullptr);
  double x, y, z;
  while (std::fscanf(file, "%lf %lf %lf", &x, &y, &z) == 3)
    reference_ground.insert(KeyOf({x, y, z}));
  std::fclose(file);
  ClothFilterOptions options;
  options.rigidness = 3;
  options.slope_smoothing = true;
  options.cloth_resolution_m = 1.0;
  options.class_threshold_m = 0.5;
  options.max_iterations = 500;
  options.time_step = 0.65;
  options.hole_fill = ClothHoleFill::kReferenceScanline;
  options.class_distance_along_normal = false;
  options.gravity = 0.2 * options.time_step * options.time_step;
  options.slope_max_cloth_gap_m = std::numeric_limits<double>::infinity();
  const ClothFilterResult result = FilterGround(cloud.positions, options);
  ASSERT_TRUE(result.ok) << result.message;
  std::size_t agree = 0;
  for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
    const bool reference = reference_ground.count(KeyOf(cloud.positions[i])) > 0;
    agree += reference == (result.labels[i] == GroundLabel::kGround);
  }
  const double agreement = double(agree) / cloud.positions.size();
  std::printf("csf_sample: %zu points, reference ground %zu, ours %zu, agreement %.2f %%\n",
              cloud.positions.size(), reference_ground.size(), result.num_ground, 100 * agreement);
  RecordProperty("csf_sample_agreement_percent", std::to_string(100 * agreement));
  EXPECT_GE(agreement, kCsfSampleMinAgreement);
}

}  // namespace
}  // namespace hylo::terrain
