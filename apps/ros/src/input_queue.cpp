#include "input_queue.h"

#include <algorithm>
#include <stdexcept>

namespace hylo::rosnode {

bool InputQueueOptions::IsValid(std::string* why) const {
  if (max_scans < 1) {
    *why = "max_scans = " + std::to_string(max_scans) + ": must be >= 1";
    return false;
  }
  if (max_imu < 1) {
    *why = "max_imu = " + std::to_string(max_imu) + ": must be >= 1";
    return false;
  }
  return true;
}

InputQueue::InputQueue(const InputQueueOptions& options) : options_(options) {
  std::string why;
  if (!options_.IsValid(&why)) throw std::invalid_argument("InputQueueOptions: " + why);
}

bool InputQueue::PushScan(LidarScan scan) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closed_) return false;
    ++counters_.scans_received;
    if (scan.t_ns <= last_scan_t_ns_) {
      ++counters_.scans_out_of_order;
      return false;
    }
    last_scan_t_ns_ = scan.t_ns;
    if (scans_.size() >= options_.max_scans) {
      scans_.pop_front();
      ++counters_.scans_dropped_full;
    }
    scans_.push_back(std::move(scan));
    counters_.max_scans_waiting = std::max(counters_.max_scans_waiting, scans_.size());
  }
  ready_.notify_one();
  return true;
}

bool InputQueue::PushImu(const ImuSample& sample) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closed_) return false;
    ++counters_.imu_received;
    if (sample.t_ns <= last_imu_t_ns_) {
      ++counters_.imu_out_of_order;
      return false;
    }
    last_imu_t_ns_ = sample.t_ns;
    if (imu_.size() >= options_.max_imu) {
      imu_.pop_front();
      ++counters_.imu_dropped_full;
    }
    imu_.push_back(sample);
    counters_.max_imu_waiting = std::max(counters_.max_imu_waiting, imu_.size());
    // Only a sample that makes the oldest scan processable wakes the worker.
    if (scans_.empty() || !ScanReady(scans_.front())) return true;
  }
  ready_.notify_one();
  return true;
}

bool InputQueue::ScanReady(const LidarScan& scan) const {
  return !options_.wait_for_imu || last_imu_t_ns_ >= scan.end_t_ns;
}

bool InputQueue::Pop(std::vector<ImuSample>* imu, std::vector<LidarScan>* scans,
                     std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  ready_.wait_for(lock, timeout, [this] {
    return closed_ || notified_ || (!scans_.empty() && ScanReady(scans_.front()));
  });
  notified_ = false;
  const bool had_data = !scans_.empty() || !imu_.empty();
  const bool release_all = closed_ || !options_.wait_for_imu;
  while (!scans_.empty() && (release_all || ScanReady(scans_.front()))) {
    released_scan_end_ns_ = std::max(released_scan_end_ns_, scans_.front().end_t_ns);
    scans->push_back(std::move(scans_.front()));
    scans_.pop_front();
  }
  // The samples up to the released scans' end and the first one at or after it, which the
  // pipeline needs to close the last scan's IMU interval.
  while (!imu_.empty() && (release_all || released_imu_t_ns_ < released_scan_end_ns_)) {
    released_imu_t_ns_ = imu_.front().t_ns;
    imu->push_back(imu_.front());
    imu_.pop_front();
  }
  return !closed_ || had_data;
}

void InputQueue::Close() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
  }
  ready_.notify_all();
}

void InputQueue::Notify() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    notified_ = true;
  }
  ready_.notify_all();
}

InputCounters InputQueue::counters() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return counters_;
}

}  // namespace hylo::rosnode
