// Zero-velocity updates (standstill.h): the IMU test on synthetic samples (white noise at the
// datasheet's density is rest for every grade; vibration, a start and a moving estimate are
// not), on a real IMU in a moving vehicle (never rest), and both back-ends held still in a
// corridor whose scans barely see motion along it.
#include "hylo/estimation/standstill.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>

#include "hylo/estimation/estimator.h"
#include "hylo/estimation/estimator_options.h"
#include "hylo/estimation/imu_options.h"
#include "hylo/estimation/initial_uncertainty.h"
#include "hylo/registration/brute_force_search.h"
#include "test_data.h"

namespace hylo::estimation {
namespace {

constexpr double kGravity = 9.81;
constexpr int64_t kImuPeriodNs = 5'000'000;  // 200 Hz

ImuOptions ImuWithDensities(double gyro_density, double accel_density) {
  ImuOptions imu;
  imu.rate_hz = 200.0;
  imu.noise.gyro_noise_density = gyro_density;
  imu.noise.accel_noise_density = accel_density;
  return imu;
}

// Samples of a level IMU at rest from t0 to t1 with white noise at `imu`'s densities, plus
// `extra_accel(t_s)` on the accelerometer (vibration, a start).
template <class ExtraAccel>
std::vector<ImuSample> Samples(const ImuOptions& imu, int64_t t0_ns, int64_t t1_ns,
                               std::mt19937* rng, ExtraAccel extra_accel) {
  std::normal_distribution<double> unit(0.0, 1.0);
  const double sqrt_rate = std::sqrt(imu.rate_hz);
  const double sa = imu.noise.accel_noise_density * sqrt_rate;
  const double sg = imu.noise.gyro_noise_density * sqrt_rate;
  std::vector<ImuSample> samples;
  for (int64_t t = t0_ns; t <= t1_ns; t += kImuPeriodNs) {
    ImuSample s;
    s.t_ns = t;
    s.accel_imu = Eigen::Vector3d(sa * unit(*rng), sa * unit(*rng), kGravity + sa * unit(*rng)) +
                  extra_accel(1e-9 * static_cast<double>(t));
    s.gyro_imu = Eigen::Vector3d(sg * unit(*rng), sg * unit(*rng), sg * unit(*rng));
    samples.push_back(s);
  }
  return samples;
}

std::vector<ImuSample> RestSamples(const ImuOptions& imu, int64_t t0_ns, int64_t t1_ns,
                                   std::mt19937* rng) {
  return Samples(imu, t0_ns, t1_ns, rng, [](double) { return Eigen::Vector3d::Zero(); });
}

// Consumer MEMS to tactical grade: the range the simulator's scenarios draw from.
const std::pair<double, double> kGrades[] = {{3e-4, 3e-3}, {6.1e-5, 1.4e-3}, {2e-6, 5e-4}};

TEST(Standstill, WhiteNoiseAtTheDatasheetDensityIsRestForEveryGrade) {
  std::mt19937 rng(3);
  const StandstillOptions options;
  for (const auto& [gyro, accel] : kGrades) {
    const ImuOptions imu = ImuWithDensities(gyro, accel);
    double largest_ratio = 0.0;
    for (int trial = 0; trial < 200; ++trial) {
      const auto samples = RestSamples(imu, 0, 100'000'000, &rng);  // one 10 Hz scan interval
      const StandstillTest test = TestStandstill(samples, 0, 100'000'000, 0.0, imu, options);
      ASSERT_TRUE(test.at_rest) << "gyro density " << gyro << ", trial " << trial
                                << ": accel ratio " << test.accel_ratio << ", gyro ratio "
                                << test.gyro_ratio;
      EXPECT_EQ(test.samples, 21);
      largest_ratio = std::max({largest_ratio, test.accel_ratio, test.gyro_ratio});
    }
    // The largest of three axes' spreads over 21 samples stays near the datasheet's, well below
    // the threshold: a datasheet that understates the noise by half still passes.
    std::printf("gyro density %g: largest spread ratio in 200 intervals at rest %.2f\n", gyro,
                largest_ratio);
    EXPECT_LT(largest_ratio, 2.0);
  }
}

TEST(Standstill, VibrationAndAStartAreMotion) {
  std::mt19937 rng(4);
  const StandstillOptions options;
  for (const auto& [gyro, accel] : kGrades) {
    const ImuOptions imu = ImuWithDensities(gyro, accel);
    // A 0.3 m/s² vibration at 23 Hz, about what a vehicle's body shows on gravel.
    const auto vibration = Samples(imu, 0, 100'000'000, &rng, [](double t) {
      return Eigen::Vector3d(0.0, 0.0, 0.3 * std::sin(2.0 * M_PI * 23.0 * t));
    });
    EXPECT_FALSE(TestStandstill(vibration, 0, 100'000'000, 0.0, imu, options).at_rest);
    // Starting to drive: 0 to 1 m/s² forward over the interval.
    const auto start = Samples(imu, 0, 100'000'000, &rng,
                               [](double t) { return Eigen::Vector3d(10.0 * t, 0.0, 0.0); });
    EXPECT_FALSE(TestStandstill(start, 0, 100'000'000, 0.0, imu, options).at_rest);
  }
}

TEST(Standstill, AMovingEstimateIsNotStoppedByAQuietImu) {
  // Straight motion at constant speed reads like rest: the estimate's speed decides.
  std::mt19937 rng(5);
  const ImuOptions imu = ImuWithDensities(6.1e-5, 1.4e-3);
  const auto samples = RestSamples(imu, 0, 100'000'000, &rng);
  StandstillOptions options;
  EXPECT_TRUE(TestStandstill(samples, 0, 100'000'000, 0.05, imu, options).at_rest);
  EXPECT_FALSE(TestStandstill(samples, 0, 100'000'000, 1.5, imu, options).at_rest);
  EXPECT_FALSE(TestStandstill(samples, 0, 100'000'000, NAN, imu, options).at_rest);
}

TEST(Standstill, NeedsSamplesAnImuAndTheOption) {
  std::mt19937 rng(6);
  ImuOptions imu = ImuWithDensities(6.1e-5, 1.4e-3);
  const auto samples = RestSamples(imu, 0, 100'000'000, &rng);
  StandstillOptions options;
  // Only the samples inside the interval count: 15-20 ms holds three.
  const StandstillTest few = TestStandstill(samples, 10'000'000, 20'000'000, 0.0, imu, options);
  EXPECT_EQ(few.samples, 3);
  EXPECT_FALSE(few.at_rest);
  options.enabled = false;
  EXPECT_FALSE(TestStandstill(samples, 0, 100'000'000, 0.0, imu, options).at_rest);
  options.enabled = true;
  imu.enabled = false;
  EXPECT_FALSE(TestStandstill(samples, 0, 100'000'000, 0.0, imu, options).at_rest);
  // A datasheet without noise: no spread is small enough.
  imu = ImuWithDensities(0.0, 1.4e-3);
  EXPECT_FALSE(TestStandstill(samples, 0, 100'000'000, 0.0, imu, options).at_rest);
}

TEST(Standstill, OptionsNameTheBrokenField) {
  std::string why;
  EXPECT_TRUE(StandstillOptions{}.IsValid(&why));
  StandstillOptions o;
  o.max_spread_ratio = 0.5;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("max_spread_ratio"), std::string::npos) << why;
  o = StandstillOptions{};
  o.max_speed_mps = NAN;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("max_speed_mps"), std::string::npos) << why;
  o = StandstillOptions{};
  o.velocity_noise_mps = 0.0;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("velocity_noise_mps"), std::string::npos) << why;
  o = StandstillOptions{};
  o.min_samples = 2;
  EXPECT_FALSE(o.IsValid(&why));
  EXPECT_NE(why.find("min_samples"), std::string::npos) << why;
  EstimatorOptions estimator;
  estimator.standstill.min_samples = 2;
  EXPECT_FALSE(estimator.IsValid(&why));
  EXPECT_NE(why.find("standstill.min_samples"), std::string::npos) << why;
}

// The IMU samples of an Ouster capture (pcap of Ethernet/IPv4/UDP; a legacy IMU packet is a
// 48-byte UDP payload: three u64 stamps in ns, accel xyz in g, gyro xyz in deg/s, as float32).
std::vector<ImuSample> ReadOusterImu(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const auto read = [&bytes](std::size_t at, auto* value) {
    std::memcpy(value, bytes.data() + at, sizeof(*value));  // little-endian, as recorded
  };
  std::vector<ImuSample> samples;
  constexpr std::size_t kGlobalHeader = 24, kRecordHeader = 16, kUdpPayloadAt = 14 + 20 + 8;
  for (std::size_t at = kGlobalHeader; at + kRecordHeader <= bytes.size();) {
    uint32_t length = 0;
    read(at + 8, &length);
    const std::size_t packet = at + kRecordHeader;
    at = packet + length;
    if (at > bytes.size() || length != kUdpPayloadAt + 48) continue;
    uint64_t accel_ns = 0;
    float values[6];
    read(packet + kUdpPayloadAt + 8, &accel_ns);
    read(packet + kUdpPayloadAt + 24, &values);
    ImuSample s;
    s.t_ns = static_cast<int64_t>(accel_ns);
    s.accel_imu = 9.80665 * Eigen::Vector3d(values[0], values[1], values[2]);
    s.gyro_imu = (M_PI / 180.0) * Eigen::Vector3d(values[3], values[4], values[5]);
    samples.push_back(s);
  }
  return samples;
}

TEST(Standstill, ARealImuInAMovingVehicleIsNeverAtRest) {
  // An Ouster OS1-128 driven at about 2.5 m/s (its reference poses: 0.25 m per 0.1 s frame),
  // 100 Hz IMU. The speed guard is left out (speed 0 given): the spread alone must say motion.
  // The densities are the noisiest the simulator draws (consumer MEMS), which favours rest.
  HYLO_REQUIRE_DATA("ouster/OS-1-128_v2.3.0_1024x10_lb_n3.pcap");
  const auto samples =
      ReadOusterImu(testing::DataPath("ouster/OS-1-128_v2.3.0_1024x10_lb_n3.pcap"));
  ASSERT_EQ(samples.size(), 30u);
  ImuOptions imu = ImuWithDensities(3e-4, 3e-3);
  imu.rate_hz = 100.0;
  double least_ratio = std::numeric_limits<double>::infinity();
  int intervals = 0;
  for (std::size_t first = 0; first + 10 <= samples.size(); ++first, ++intervals) {
    const StandstillTest test =
        TestStandstill(samples, samples[first].t_ns, samples[first + 9].t_ns, 0.0, imu, {});
    EXPECT_EQ(test.samples, 10);
    EXPECT_FALSE(test.at_rest) << "interval from sample " << first << ": accel ratio "
                               << test.accel_ratio << ", gyro ratio " << test.gyro_ratio;
    least_ratio = std::min(least_ratio, std::max(test.accel_ratio, test.gyro_ratio));
  }
  std::printf(
      "real IMU in motion: %d intervals of 0.1 s, the least of their larger spread "
      "ratios %.1f (threshold %.1f)\n",
      intervals, least_ratio, StandstillOptions{}.max_spread_ratio);
}

// A corridor along x (floor and two walls, 0.2 m grid): a scan fixes y, z and the rotation,
// but not x.
PointCloud Corridor() {
  PointCloud points;
  for (double x = -15.0; x <= 15.0; x += 0.2) {
    for (double s = -1.5; s <= 1.5; s += 0.2) {
      points.emplace_back(x, s, 0.0);
      points.emplace_back(x, -1.5, s + 1.5);
      points.emplace_back(x, 1.5, s + 1.5);
    }
  }
  return points;
}

constexpr int kScans = 30;

struct StillRun {
  double max_speed_mps = 0.0;  // the largest speed estimate after an update
  double max_offset_m = 0.0;   // the farthest the estimate moved along the corridor
  int standstill_updates = 0;
};

// The vehicle stands 1.5 m up in the corridor for 3 s, 10 scans a second; the estimate starts
// believing it moves at 8 cm/s along x (a stop the estimate has not caught up with). The scans
// barely constrain x (the 0.2 m grid's edges give them a little hold), so without the IMU's
// word the estimate swings along the corridor.
StillRun HoldStill(Estimator::Backend backend, bool standstill) {
  const PointCloud map = Corridor();
  const registration::BruteForceSearch search(map);
  const registration::PlaneMatcher planes(search, registration::PlaneMatcherOptions{});
  EstimatorOptions options;
  options.backend = backend;
  options.standstill.enabled = standstill;
  const ImuOptions imu = ImuWithDensities(6.1e-5, 1.4e-3);
  auto estimator = Estimator::Create(options, imu);
  NavState start;
  start.p_map_imu = Eigen::Vector3d(0.0, 0.0, 1.5);
  start.v_map_imu = Eigen::Vector3d(0.08, 0.0, 0.0);
  start.gravity_map = Eigen::Vector3d(0.0, 0.0, -kGravity);
  estimator->Initialize(start, InitialUncertainty().SlamCovariance());
  DeskewedScan scan;
  for (std::size_t i = 0; i < map.size(); i += 10) {
    scan.points_lidar.push_back(map[i] - Eigen::Vector3f(0.0f, 0.0f, 1.5f));
  }
  std::mt19937 rng(7);
  StillRun run;
  for (int k = 1; k <= kScans; ++k) {
    const int64_t t0 = (k - 1) * 100'000'000LL, t1 = k * 100'000'000LL;
    for (const ImuSample& s : RestSamples(imu, t0 + kImuPeriodNs, t1, &rng)) estimator->AddImu(s);
    scan.t_ns = t1;
    const UpdateSummary summary = estimator->Update(scan, planes);
    EXPECT_TRUE(summary.applied) << summary.message;
    EXPECT_TRUE(summary.degenerate) << "the corridor must hide x for this test to mean anything";
    run.standstill_updates += summary.standstill ? 1 : 0;
    run.max_speed_mps = std::max(run.max_speed_mps, estimator->state().v_map_imu.norm());
    run.max_offset_m = std::max(run.max_offset_m, std::abs(estimator->state().p_map_imu.x()));
  }
  return run;
}

class StandstillBackend : public ::testing::TestWithParam<Estimator::Backend> {};

TEST_P(StandstillBackend, HoldsStillWhatTheScansLetSwing) {
  const StillRun off = HoldStill(GetParam(), false);
  const StillRun on = HoldStill(GetParam(), true);
  std::printf(
      "[%s] 3 s at rest, without / with zero-velocity updates (%d of %d scans): largest "
      "speed %.4f / %.4f m/s, largest offset along the corridor %.4f / %.4f m\n",
      ToString(GetParam()).c_str(), on.standstill_updates, kScans, off.max_speed_mps,
      on.max_speed_mps, off.max_offset_m, on.max_offset_m);
  EXPECT_EQ(off.standstill_updates, 0);
  EXPECT_EQ(on.standstill_updates, kScans);
  // Measured: without, 0.14 (filter) and 0.07 m/s (smoother); with, below 0.008 m/s for both,
  // within the measurement's 0.01 m/s.
  EXPECT_GT(off.max_speed_mps, 0.05);
  EXPECT_LT(on.max_speed_mps, 0.015);
  // The first interval's propagation carries 8 mm before the first update; then it stays.
  EXPECT_LT(on.max_offset_m, 0.015);
}

INSTANTIATE_TEST_SUITE_P(BothBackends, StandstillBackend,
                         ::testing::Values(Estimator::Backend::kIeskf,
                                           Estimator::Backend::kSlidingWindow),
                         [](const auto& info) { return ToString(info.param); });

}  // namespace
}  // namespace hylo::estimation
