// The node's bounded hand-over queue: late / out-of-order messages counted and dropped, the
// oldest scan dropped when full, nothing lost or reordered otherwise.

#include "input_queue.h"

#include <gtest/gtest.h>

#include <thread>

namespace hylo::rosnode {
namespace {

using std::chrono::milliseconds;

LidarScan Scan(int64_t t_ns) {
  LidarScan scan;
  scan.t_ns = t_ns;
  scan.end_t_ns = t_ns + 100;
  return scan;
}

ImuSample Imu(int64_t t_ns) {
  ImuSample sample;
  sample.t_ns = t_ns;
  return sample;
}

InputQueueOptions ReleaseAll() {
  InputQueueOptions options;
  options.wait_for_imu = false;
  return options;
}

TEST(InputQueue, OutOfOrderAndDuplicateMessagesAreCountedAndDropped) {
  InputQueue queue(ReleaseAll());
  EXPECT_TRUE(queue.PushScan(Scan(100)));
  EXPECT_FALSE(queue.PushScan(Scan(100)));  // duplicate
  EXPECT_FALSE(queue.PushScan(Scan(50)));   // older
  EXPECT_TRUE(queue.PushScan(Scan(200)));
  EXPECT_TRUE(queue.PushImu(Imu(10)));
  EXPECT_FALSE(queue.PushImu(Imu(5)));
  EXPECT_TRUE(queue.PushImu(Imu(20)));
  std::vector<ImuSample> imu;
  std::vector<LidarScan> scans;
  ASSERT_TRUE(queue.Pop(&imu, &scans, milliseconds(0)));
  ASSERT_EQ(scans.size(), 2u);
  EXPECT_EQ(scans[0].t_ns, 100);
  EXPECT_EQ(scans[1].t_ns, 200);
  ASSERT_EQ(imu.size(), 2u);
  EXPECT_EQ(imu[1].t_ns, 20);
  const InputCounters c = queue.counters();
  EXPECT_EQ(c.scans_received, 4u);
  EXPECT_EQ(c.scans_out_of_order, 2u);
  EXPECT_EQ(c.imu_received, 3u);
  EXPECT_EQ(c.imu_out_of_order, 1u);
  EXPECT_EQ(c.scans_dropped_full, 0u);
}

TEST(InputQueue, FullQueueDropsTheOldestAndStaysBounded) {
  InputQueueOptions options = ReleaseAll();
  options.max_scans = 3;
  options.max_imu = 10;
  InputQueue queue(options);
  for (int i = 1; i <= 8; ++i) queue.PushScan(Scan(i * 100));
  for (int i = 1; i <= 25; ++i) queue.PushImu(Imu(i));
  std::vector<ImuSample> imu;
  std::vector<LidarScan> scans;
  ASSERT_TRUE(queue.Pop(&imu, &scans, milliseconds(0)));
  ASSERT_EQ(scans.size(), 3u);
  EXPECT_EQ(scans.front().t_ns, 600);  // the newest three survive
  EXPECT_EQ(scans.back().t_ns, 800);
  ASSERT_EQ(imu.size(), 10u);
  EXPECT_EQ(imu.front().t_ns, 16);
  const InputCounters c = queue.counters();
  EXPECT_EQ(c.scans_dropped_full, 5u);
  EXPECT_EQ(c.imu_dropped_full, 15u);
  EXPECT_EQ(c.max_scans_waiting, 3u);
  EXPECT_EQ(c.max_imu_waiting, 10u);
}

TEST(InputQueue, PopWakesOnAScanFromAnotherThreadAndEndsAfterClose) {
  InputQueue queue({});
  std::thread producer([&queue] {
    for (int i = 1; i <= 20; ++i) {
      queue.PushImu(Imu(i));
      if (i % 5 == 0) queue.PushScan(Scan(i));
    }
    queue.Close();
  });
  std::vector<ImuSample> imu;
  std::vector<LidarScan> scans;
  while (queue.Pop(&imu, &scans, milliseconds(50))) {
  }
  producer.join();
  ASSERT_EQ(imu.size(), 20u);
  ASSERT_EQ(scans.size(), 4u);
  for (std::size_t i = 1; i < imu.size(); ++i) EXPECT_LT(imu[i - 1].t_ns, imu[i].t_ns);
  EXPECT_FALSE(queue.PushScan(Scan(1000)));  // closed
}

// With an IMU, a scan waits until the IMU passes its end, and IMU samples wait for scans
// beyond the first one after the released scan: each stream waits here, bounded.
TEST(InputQueue, ScansWaitForTheImuAndImuWaitsForScans) {
  InputQueueOptions options;
  options.max_imu = 50;
  InputQueue queue(options);
  std::vector<ImuSample> imu;
  std::vector<LidarScan> scans;
  queue.PushScan(Scan(1000));  // ends at 1100
  for (int t = 0; t <= 1000; t += 100) queue.PushImu(Imu(t));
  queue.Pop(&imu, &scans, milliseconds(0));
  EXPECT_TRUE(scans.empty()) << "the IMU has not reached the scan's end";
  EXPECT_TRUE(imu.empty()) << "no scan released: the IMU waits with it";
  queue.PushImu(Imu(1150));
  queue.PushImu(Imu(1250));
  queue.Pop(&imu, &scans, milliseconds(0));
  ASSERT_EQ(scans.size(), 1u);
  ASSERT_FALSE(imu.empty());
  EXPECT_EQ(imu.front().t_ns, 0);
  EXPECT_EQ(imu.back().t_ns, 1150) << "up to the first sample at or after the scan end";
  // The lidar stalls: the IMU keeps arriving and stays bounded here.
  for (int t = 1300; t < 1300 + 100 * 200; t += 100) queue.PushImu(Imu(t));
  imu.clear();
  queue.Pop(&imu, &scans, milliseconds(0));
  EXPECT_TRUE(imu.empty());
  EXPECT_EQ(queue.counters().max_imu_waiting, 50u);
  EXPECT_GT(queue.counters().imu_dropped_full, 100u);
}

TEST(InputQueue, InvalidOptionsNameTheField) {
  InputQueueOptions options;
  options.max_scans = 0;
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("max_scans"), std::string::npos);
  EXPECT_THROW(InputQueue{options}, std::invalid_argument);
}

}  // namespace
}  // namespace hylo::rosnode
