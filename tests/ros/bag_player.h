#pragma once
// Plays a bag to ROS topics from the test process, paced by the steady clock at the bag's
// receive times. The integration tests use it instead of `rosbag play`: in full suite runs that
// player stalled for good a fraction of a second into the bag now and then (its main loop
// asleep, the bag no longer read), and its keyboard handling reads stdin, where a space pauses
// it for good. Here the node still gets real ROS messages over TCP, as from a driver.

#include <ros/ros.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <mutex>
#include <string>
#include <thread>

namespace hylo::testing {

class BagPlayer {
 public:
  /// Starts playing `bag_path` (PointCloud2 on /points, Imu on /imu, as `hylo simulate` writes
  /// them) on the same topics, on a thread of its own. Publishing begins once both topics have
  /// a subscriber, or after `connect_timeout` without.
  BagPlayer(ros::NodeHandle& nh, const std::string& bag_path,
            std::chrono::milliseconds connect_timeout);
  /// Stops early if still playing.
  ~BagPlayer();
  BagPlayer(const BagPlayer&) = delete;
  BagPlayer& operator=(const BagPlayer&) = delete;

  /// Waits up to `timeout` for the end of the bag. False with why (timeout, with how far the
  /// replay got; or the bag's read error).
  bool Wait(std::chrono::milliseconds timeout, std::string* error);

 private:
  void Play(std::chrono::milliseconds connect_timeout);
  /// Sleeps until `deadline` unless stopped first; false when stopped.
  bool SleepUntil(std::chrono::steady_clock::time_point deadline);

  std::string bag_path_;
  ros::Publisher points_, imu_;
  std::mutex mutex_;
  std::condition_variable changed_;
  bool stop_ = false;      // guarded by mutex_
  bool finished_ = false;  // guarded by mutex_
  std::string error_;      // guarded by mutex_
  std::atomic<std::size_t> published_{0};
  std::thread thread_;
};

}  // namespace hylo::testing
