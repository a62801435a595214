#include "hylo/localization/serial_worker.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <future>
#include <stdexcept>
#include <vector>

namespace hylo::localization {
namespace {

// Read here with the system call itself rather than the library's ThisThreadsNiceness(): the
// test checks the library's lowering of a thread's priority, so it must not also trust the
// library's reading of it.
int ThisThreadsNicenessForTest() {
  return getpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)));
}

// Jobs run in the order they were posted, on a thread or on the caller's, and an answer waits
// for every job posted before it.
TEST(SerialWorker, RunsJobsInOrderAndAnAnswerFollowsThem) {
  for (const bool on_thread : {false, true}) {
    SerialWorker worker(on_thread, /*max_queued=*/8, /*niceness_below=*/0);
    std::vector<int> order;  // touched by the jobs alone until the answer is read
    for (int i = 0; i < 200; ++i) worker.Post([&order, i] { order.push_back(i); });
    const std::shared_future<std::size_t> count = worker.Ask([&order] { return order.size(); });
    ASSERT_EQ(count.get(), 200u) << "on_thread " << on_thread;
    for (int i = 0; i < 200; ++i) ASSERT_EQ(order[i], i) << "on_thread " << on_thread;
  }
}

// A job that throws stops nothing after it: the next answer carries its error, later ones do
// not.
TEST(SerialWorker, AJobsErrorReachesTheNextAnswerOnce) {
  for (const bool on_thread : {false, true}) {
    SerialWorker worker(on_thread, /*max_queued=*/8, /*niceness_below=*/0);
    int ran = 0;
    worker.Post([] { throw std::runtime_error("sweep unreadable"); });
    worker.Post([&ran] { ++ran; });
    const std::shared_future<int> first = worker.Ask([&ran] { return ran; });
    EXPECT_THROW(first.get(), std::runtime_error) << "on_thread " << on_thread;
    const std::shared_future<int> second = worker.Ask([&ran] { return ran; });
    EXPECT_EQ(second.get(), 1) << "on_thread " << on_thread;
  }
}

// Destroyed with jobs queued, the worker runs them first: what they fill is complete.
TEST(SerialWorker, DestructionRunsTheQueuedJobs) {
  std::vector<int> filled;
  {
    SerialWorker worker(/*on_thread=*/true, /*max_queued=*/8, /*niceness_below=*/0);
    for (int i = 0; i < 1000; ++i) worker.Post([&filled, i] { filled.push_back(i); });
  }
  EXPECT_EQ(filled.size(), 1000u);
}

// With the thread held on a job and the queue full, Post waits; it returns once the held job
// ends and there is room again, and the jobs still run in order.
TEST(SerialWorker, PostWaitsForRoomWhenTheQueueIsFull) {
  std::promise<void> release;
  const std::shared_future<void> released = release.get_future().share();
  std::vector<int> order;  // touched by the jobs alone until the answer is read
  SerialWorker worker(/*on_thread=*/true, /*max_queued=*/1, /*niceness_below=*/0);
  worker.Post([&order, released] {
    released.wait();
    order.push_back(0);
  });
  worker.Post([&order] { order.push_back(1); });  // fills the one place (once job 0 is taken)
  std::future<void> third = std::async(std::launch::async, [&worker, &order] {
    worker.Post([&order] { order.push_back(2); });
  });
  // A Post that did not wait would return at once; this one cannot until job 0 is released.
  EXPECT_EQ(third.wait_for(std::chrono::milliseconds(200)), std::future_status::timeout);
  release.set_value();
  third.get();
  EXPECT_EQ(worker.Ask([&order] { return order; }).get(), (std::vector<int>{0, 1, 2}));
}

// The worker's thread runs the asked steps below the thread that made it (Linux lets any
// thread lower its own priority); inline, the jobs run at the caller's, which is left alone.
TEST(SerialWorker, ItsThreadRunsTheAskedStepsBelowTheThreadThatMadeIt) {
  const int starter = ThisThreadsNicenessForTest();
  SerialWorker on_thread(/*on_thread=*/true, /*max_queued=*/8, /*niceness_below=*/5);
  EXPECT_EQ(on_thread.Ask([] { return ThisThreadsNicenessForTest(); }).get(),
            std::min(starter + 5, 19));
  SerialWorker in_line(/*on_thread=*/false, /*max_queued=*/8, /*niceness_below=*/5);
  EXPECT_EQ(in_line.Ask([] { return ThisThreadsNicenessForTest(); }).get(), starter);
  EXPECT_EQ(ThisThreadsNicenessForTest(), starter);
}

}  // namespace
}  // namespace hylo::localization
