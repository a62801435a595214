#include "hylo/localization/serial_worker.h"

#include <algorithm>

#include "thread_niceness.h"

namespace hylo::localization {

SerialWorker::SerialWorker(bool on_thread, std::size_t max_queued, int niceness_below)
    : max_queued_(std::max<std::size_t>(max_queued, 1)) {
  if (!on_thread) return;
  const int starter_niceness = ThisThreadsNiceness();
  thread_ = std::thread(
      [this, starter_niceness, niceness_below] { Loop(starter_niceness, niceness_below); });
}

SerialWorker::~SerialWorker() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void SerialWorker::Post(std::function<void()> job) {
  if (!thread_.joinable()) {
    Run(job);
    return;
  }
  {
    std::unique_lock<std::mutex> lock(mutex_);
    room_.wait(lock, [this] { return jobs_.size() < max_queued_; });
    jobs_.push_back(std::move(job));
  }
  wake_.notify_one();
}

void SerialWorker::Run(const std::function<void()>& job) {
  try {
    job();
  } catch (...) {
    if (!failed_) failed_ = std::current_exception();
  }
}

void SerialWorker::Loop(int starter_niceness, int niceness_below) {
  if (niceness_below > 0) LowerThisThreadsPriority(starter_niceness, niceness_below);
  for (;;) {
    std::function<void()> job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !jobs_.empty(); });
      if (jobs_.empty()) return;  // stopping, and every job has run
      job = std::move(jobs_.front());
      jobs_.pop_front();
    }
    room_.notify_one();
    Run(job);
  }
}

}  // namespace hylo::localization
