#include "bag_player.h"

#include <algorithm>
#include <exception>
#include <limits>
#include <memory>
#include <utility>

#include "hylo/logs/bag_reader.h"
#include "hylo/logs/pointcloud2.h"
#include "hylo/logs/ros_bridge.h"

namespace hylo::testing {

BagPlayer::BagPlayer(ros::NodeHandle& nh, const std::string& bag_path,
                     std::chrono::milliseconds connect_timeout)
    : bag_path_(bag_path),
      points_(nh.advertise<sensor_msgs::PointCloud2>("/points", 100)),
      imu_(nh.advertise<sensor_msgs::Imu>("/imu", 1000)),
      thread_([this, connect_timeout] { Play(connect_timeout); }) {}

BagPlayer::~BagPlayer() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

bool BagPlayer::SleepUntil(std::chrono::steady_clock::time_point deadline) {
  std::unique_lock<std::mutex> lock(mutex_);
  return !changed_.wait_until(lock, deadline, [this] { return stop_; });
}

void BagPlayer::Play(std::chrono::milliseconds connect_timeout) {
  std::string error;
  try {
    const std::unique_ptr<logs::LogReader> reader = logs::OpenBag(bag_path_, logs::LogReadOptions());
    const auto connect_deadline = std::chrono::steady_clock::now() + connect_timeout;
    while (points_.getNumSubscribers() == 0 || imu_.getNumSubscribers() == 0) {
      if (std::chrono::steady_clock::now() > connect_deadline) break;
      if (!SleepUntil(std::chrono::steady_clock::now() + std::chrono::milliseconds(50))) return;
    }
    // Receive times, as the bag orders its records: a sample's stamp, a scan's end.
    logs::LogMessage message;
    std::chrono::steady_clock::time_point start;
    int64_t first_t_ns = 0;
    int64_t latest_t_ns = std::numeric_limits<int64_t>::min();
    while (reader->Next(&message)) {
      const bool is_imu = message.kind == logs::LogMessage::Kind::kImu;
      const int64_t t_ns = is_imu ? message.imu.t_ns : message.scan.end_t_ns;
      if (latest_t_ns == std::numeric_limits<int64_t>::min()) {
        start = std::chrono::steady_clock::now();
        first_t_ns = t_ns;
      }
      latest_t_ns = std::max(latest_t_ns, t_ns);
      if (!SleepUntil(start + std::chrono::nanoseconds(latest_t_ns - first_t_ns))) return;
      if (is_imu) {
        imu_.publish(logs::ros_bridge::ToRos(message.imu, "imu"));
      } else {
        logs::PointCloud2Message cloud =
            logs::EncodePointCloud2(message.scan, reader->time_convention());
        cloud.frame_id = "lidar";
        points_.publish(logs::ros_bridge::ToRos(std::move(cloud)));
      }
      ++published_;
    }
  } catch (const std::exception& e) {
    error = e.what();
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    finished_ = true;
    error_ = error;
  }
  changed_.notify_all();
}

bool BagPlayer::Wait(std::chrono::milliseconds timeout, std::string* error) {
  std::unique_lock<std::mutex> lock(mutex_);
  if (!changed_.wait_for(lock, timeout, [this] { return finished_; })) {
    *error = "the bag did not play to its end within " + std::to_string(timeout.count()) + " ms (" +
             std::to_string(published_.load()) + " messages published)";
    return false;
  }
  if (!error_.empty()) {
    *error = "bag " + bag_path_ + ": " + error_;
    return false;
  }
  return true;
}

}  // namespace hylo::testing
