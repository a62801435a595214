// The measurement queue sorts, drops and counts bad stamps one message at a time.
#include "hylo/odometry/measurement_queue.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace hylo::odometry {
namespace {

constexpr int64_t kMs = 1'000'000;

ImuSample Imu(int64_t t_ns) {
  ImuSample s;
  s.t_ns = t_ns;
  return s;
}

LidarScan Scan(int64_t start_ns, int64_t end_ns) {
  LidarScan scan;
  scan.t_ns = start_ns;
  scan.end_t_ns = end_ns;
  return scan;
}

TEST(MeasurementQueue, SortsImuAndReleasesAScanOnlyWhenCovered) {
  MeasurementQueue queue(MeasurementQueueOptions{});
  for (int64_t t : {0, 10, 5, 20, 15}) queue.AddImu(Imu(t * kMs));
  queue.AddScan(Scan(0, 30 * kMs));
  MeasurementGroup group;
  EXPECT_FALSE(queue.Pop(&group));  // IMU ends at 20 ms < 30 ms
  queue.AddImu(Imu(25 * kMs));
  queue.AddImu(Imu(30 * kMs));
  queue.AddImu(Imu(35 * kMs));
  ASSERT_TRUE(queue.Pop(&group));
  ASSERT_EQ(group.imu.size(), 7u);  // 0..30 ms inclusive
  for (std::size_t i = 1; i < group.imu.size(); ++i) {
    EXPECT_LT(group.imu[i - 1].t_ns, group.imu[i].t_ns);
  }
  EXPECT_EQ(group.imu.back().t_ns, 30 * kMs);
  EXPECT_EQ(queue.pending_imu(), 1u);  // 35 ms stays for the next scan
}

TEST(MeasurementQueue, DropsDuplicatesAndStaleDataButKeepsTheRest) {
  MeasurementQueue queue(MeasurementQueueOptions{});
  for (int64_t t = 0; t <= 100; t += 5) queue.AddImu(Imu(t * kMs));
  queue.AddImu(Imu(50 * kMs));  // duplicate
  queue.AddScan(Scan(0, 40 * kMs));
  queue.AddScan(Scan(50 * kMs, 90 * kMs));
  queue.AddScan(Scan(50 * kMs, 90 * kMs));  // duplicate
  MeasurementGroup group;
  ASSERT_TRUE(queue.Pop(&group));
  queue.AddImu(Imu(20 * kMs));        // older than what was handed out: stale
  queue.AddScan(Scan(-10 * kMs, 0));  // started before the handed-out scan: stale
  ASSERT_TRUE(queue.Pop(&group));
  EXPECT_EQ(group.scan.t_ns, 50 * kMs);
  const QueueCounters& c = queue.counters();
  EXPECT_EQ(c.imu_duplicates, 1u);
  EXPECT_EQ(c.imu_stale, 1u);
  EXPECT_EQ(c.scan_duplicates, 1u);
  EXPECT_EQ(c.scan_stale, 1u);
  EXPECT_EQ(queue.pending_imu(), 2u);  // 95 and 100 ms: one bad stamp cleared nothing
}

TEST(MeasurementQueue, AContinuousStretchOfImuStopsAtASilenceAndIsHandedOut) {
  MeasurementQueue queue(MeasurementQueueOptions{});
  for (int64_t t : {10, 20, 30, 40, 300, 310, 320}) queue.AddImu(Imu(t * kMs));
  // From a state at 5 ms, silences of at most 50 ms, up to 400 ms: 10-40 ms, not past the
  // 260 ms silence.
  std::vector<ImuSample> stretch = queue.PopContinuousImu(5 * kMs, 400 * kMs, 50 * kMs);
  ASSERT_EQ(stretch.size(), 4u);
  EXPECT_EQ(stretch.back().t_ns, 40 * kMs);
  // The next stretch cannot begin after a silence from where the last one ended either.
  EXPECT_TRUE(queue.PopContinuousImu(40 * kMs, 400 * kMs, 50 * kMs).empty());
  // From a state after the silence, up to 310 ms.
  stretch = queue.PopContinuousImu(290 * kMs, 310 * kMs, 50 * kMs);
  ASSERT_EQ(stretch.size(), 2u);
  EXPECT_EQ(stretch.front().t_ns, 300 * kMs);
  EXPECT_EQ(queue.pending_imu(), 1u);
  queue.AddImu(Imu(305 * kMs));  // older than what was handed out: stale
  EXPECT_EQ(queue.counters().imu_stale, 1u);
  EXPECT_EQ(queue.pending_imu(), 1u);
}

TEST(MeasurementQueue, CountsImuGaps) {
  MeasurementQueue queue(MeasurementQueueOptions{});
  for (int64_t t : {0, 5, 10, 200, 205}) queue.AddImu(Imu(t * kMs));
  EXPECT_EQ(queue.counters().imu_gaps, 1u);
  EXPECT_EQ(queue.counters().longest_imu_gap_ns, 190 * kMs);
}

TEST(MeasurementQueue, ScansAreReleasedWhenTheImuStops) {
  MeasurementQueueOptions options;
  options.max_imu_wait_ns = 100 * kMs;
  MeasurementQueue queue(options);
  for (int64_t t = 0; t <= 100; t += 5) queue.AddImu(Imu(t * kMs));
  queue.AddScan(Scan(50 * kMs, 140 * kMs));  // ends after the last IMU sample
  MeasurementGroup group;
  EXPECT_FALSE(queue.Pop(&group));  // the IMU may only be late
  queue.AddScan(Scan(150 * kMs, 240 * kMs));
  EXPECT_FALSE(queue.Pop(&group));  // silent for 50 ms: a dropout is waited out
  queue.AddScan(Scan(250 * kMs, 340 * kMs));
  ASSERT_TRUE(queue.Pop(&group));  // silent for 150 ms: stopped, the lidar goes on
  EXPECT_EQ(group.scan.t_ns, 50 * kMs);
  ASSERT_TRUE(queue.Pop(&group));
  EXPECT_EQ(group.scan.t_ns, 150 * kMs);
  EXPECT_TRUE(group.imu.empty());
  EXPECT_FALSE(queue.Pop(&group));  // the newest scan waits for the next one (or the IMU)
  EXPECT_EQ(queue.counters().scans_past_imu, 2u);
  queue.AddImu(Imu(345 * kMs));  // the IMU is back: the newest scan is covered again
  ASSERT_TRUE(queue.Pop(&group));
  EXPECT_EQ(group.scan.t_ns, 250 * kMs);
  EXPECT_EQ(queue.counters().scans_past_imu, 2u);
}

TEST(MeasurementQueue, NonFiniteAndClippedImuSamplesAreDroppedAndCounted) {
  MeasurementQueueOptions options;
  options.accel_range_mps2 = 160.0;
  options.gyro_range_radps = 35.0;
  MeasurementQueue queue(options);
  ImuSample nan = Imu(5 * kMs);
  nan.gyro_imu.x() = std::nan("");
  ImuSample clipped = Imu(10 * kMs);
  clipped.accel_imu.z() = -160.0;
  ImuSample spinning = Imu(15 * kMs);
  spinning.gyro_imu.y() = 35.0;
  for (const ImuSample& s : {Imu(0), nan, clipped, spinning, Imu(20 * kMs)}) queue.AddImu(s);
  EXPECT_EQ(queue.counters().imu_non_finite, 1u);
  EXPECT_EQ(queue.counters().imu_saturated, 2u);
  EXPECT_EQ(queue.pending_imu(), 2u);
}

TEST(MeasurementQueue, WithoutImuScansAreReleasedInOrder) {
  MeasurementQueueOptions options;
  options.use_imu = false;
  MeasurementQueue queue(options);
  queue.AddScan(Scan(200 * kMs, 200 * kMs));
  queue.AddScan(Scan(100 * kMs, 100 * kMs));
  MeasurementGroup group;
  ASSERT_TRUE(queue.Pop(&group));
  EXPECT_EQ(group.scan.t_ns, 100 * kMs);
  ASSERT_TRUE(queue.Pop(&group));
  EXPECT_EQ(group.scan.t_ns, 200 * kMs);
  EXPECT_FALSE(queue.Pop(&group));
}

}  // namespace
}  // namespace hylo::odometry
