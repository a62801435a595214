#pragma once
// Work that must happen in order but need not happen on the caller's thread: one thread runs
// the posted jobs first in, first out. A job that throws stops nothing: its error is handed to
// the next Ask, whose future carries it. The queue is bounded: when the thread cannot keep up,
// Post waits for room rather than let the jobs (and what they hold) pile up.

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <thread>
#include <utility>

namespace hylo::localization {

class SerialWorker {
 public:
  /// `on_thread` false: each job runs inside Post or Ask, on the caller's thread. At most
  /// `max_queued` (>= 1) jobs wait at a time. The thread runs `niceness_below` steps of
  /// niceness below the constructing thread (best effort; 0: at its priority).
  SerialWorker(bool on_thread, std::size_t max_queued, int niceness_below);
  /// Runs the jobs still queued, then joins.
  ~SerialWorker();
  SerialWorker(const SerialWorker&) = delete;
  SerialWorker& operator=(const SerialWorker&) = delete;

  /// Queues `job` after every job posted before it.
  void Post(std::function<void()> job);

  /// Queues `job` and returns the future of its result (or of the error of a job before it).
  template <typename Job>
  auto Ask(Job job) -> std::shared_future<decltype(job())> {
    using Result = decltype(job());
    auto task = std::make_shared<std::packaged_task<Result()>>([this, job = std::move(job)]() {
      if (failed_) std::rethrow_exception(std::exchange(failed_, nullptr));
      return job();
    });
    std::shared_future<Result> result = task->get_future().share();
    Post([task] { (*task)(); });
    return result;
  }

 private:
  void Run(const std::function<void()>& job);
  void Loop(int starter_niceness, int niceness_below);

  const std::size_t max_queued_;
  std::mutex mutex_;
  std::condition_variable wake_;            // a job or the end, for the thread
  std::condition_variable room_;            // room in the queue, for Post
  std::deque<std::function<void()>> jobs_;  // under mutex_
  bool stopping_ = false;                   // under mutex_
  std::exception_ptr failed_;               // only touched by the jobs' thread
  std::thread thread_;                      // last: started once the rest exists
};

}  // namespace hylo::localization
