#include "hylo/registration/parallel.h"

#include <tbb/blocked_range.h>
#include <tbb/info.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "hylo/common/check.h"

namespace hylo::registration {
namespace {

// The threads ParallelFor may use on this thread: set by ThreadLimit::Run for its duration.
// TBB's worker threads keep 1, so a loop nested in another runs serially in its task.
thread_local int t_allowed_threads = 1;

// Items per task: a scan point's neighbour search and plane fit take ~1 µs, so a task of a few
// hundred amortizes TBB's scheduling (~1 µs per task) while a 10 k point scan still splits
// into dozens of tasks for the threads to balance.
constexpr std::size_t kGrain = 256;

}  // namespace

struct ThreadLimit::Arena {
  explicit Arena(int threads) : arena(threads) {}
  mutable tbb::task_arena arena;
};

ThreadLimit::ThreadLimit(int threads) {
  HYLO_CHECK(threads >= 0);
  // More threads than cores would only wait for each other (and oneTBB warns that it has no
  // workers for them): a limit above the cores is the cores.
  const int cores = std::max(1, tbb::info::default_concurrency());
  threads_ = threads == 0 ? cores : std::min(threads, cores);
  if (threads_ > 1) arena_ = std::make_unique<Arena>(threads_);
}

ThreadLimit::~ThreadLimit() = default;

void ThreadLimit::Run(const std::function<void()>& work) const {
  if (arena_ == nullptr) {
    work();
    return;
  }
  arena_->arena.execute([&] {
    const int outer = t_allowed_threads;
    t_allowed_threads = threads_;
    try {
      work();
    } catch (...) {
      t_allowed_threads = outer;
      throw;
    }
    t_allowed_threads = outer;
  });
}

void ParallelFor(std::size_t n, const std::function<void(std::size_t, std::size_t)>& body) {
  if (n == 0) return;
  if (t_allowed_threads <= 1 || n < 2 * kGrain) {
    body(0, n);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, kGrain),
                    [&](const tbb::blocked_range<std::size_t>& r) { body(r.begin(), r.end()); });
}

int ParallelThreads() { return t_allowed_threads; }

void ParallelTasks(int tasks, const std::function<void(int)>& task) {
  if (tasks <= 0) return;
  if (t_allowed_threads <= 1 || tasks == 1) {
    for (int t = 0; t < tasks; ++t) task(t);
    return;
  }
  tbb::parallel_for(0, tasks, [&](int t) { task(t); });
}

}  // namespace hylo::registration
