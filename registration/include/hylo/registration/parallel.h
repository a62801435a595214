#pragma once
// Loops over independent items (one scan point each) on more than one core, with results that
// do not depend on the number of threads: every item writes only its own outputs, and whatever
// is summed afterwards is summed in item order by the caller. A loop runs in parallel only
// inside ThreadLimit::Run, on at most its number of threads; anywhere else (a background worker,
// a test, a tool) it runs on the calling thread alone, so nothing is parallel by surprise.

#include <cstddef>
#include <functional>
#include <memory>

namespace hylo::registration {

/// The threads a pipeline's hot loops may use. oneTBB underneath (a task arena of that size).
class ThreadLimit {
 public:
  /// `threads`: >= 1, or 0 for every core of the machine; no more than the cores are used.
  explicit ThreadLimit(int threads);
  ~ThreadLimit();
  ThreadLimit(const ThreadLimit&) = delete;
  ThreadLimit& operator=(const ThreadLimit&) = delete;

  /// The resolved number of threads, 1 .. the cores.
  int threads() const { return threads_; }

  /// Runs `work` on the calling thread; ParallelFor inside it (on this thread, not nested in
  /// another ParallelFor) uses up to threads() threads.
  void Run(const std::function<void()>& work) const;

 private:
  struct Arena;
  int threads_ = 1;
  std::unique_ptr<Arena> arena_;  // null for one thread
};

/// Calls body(begin, end) on consecutive ranges that together cover [0, n) exactly once, in
/// parallel inside ThreadLimit::Run and as body(0, n) elsewhere. The ranges may run in any order
/// and at once: body must write only to the outputs of its own items.
void ParallelFor(std::size_t n,
                 const std::function<void(std::size_t begin, std::size_t end)>& body);

/// The threads a ParallelFor here may use: ThreadLimit::threads() inside its Run, 1 elsewhere.
/// For work split into that many parts whose result does not depend on the split.
int ParallelThreads();

/// Calls task(t) for t = 0 .. tasks-1, at once where threads allow (see ParallelFor).
void ParallelTasks(int tasks, const std::function<void(int task)>& task);

}  // namespace hylo::registration
