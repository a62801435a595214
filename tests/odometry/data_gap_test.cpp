// Gaps in the data are told from the observed scan rate, whatever that rate is.
#include "hylo/odometry/data_gap.h"

#include <gtest/gtest.h>

namespace hylo::odometry {
namespace {

constexpr int64_t kMs = 1'000'000;

// Ticks `n` scans `period_ms` apart from `*t_ns` on; every one must be no gap.
void TickSteadily(ScanIntervalClock* clock, int64_t* t_ns, int n, int64_t period_ms) {
  for (int k = 0; k < n; ++k) {
    *t_ns += period_ms * kMs;
    ASSERT_EQ(clock->Tick(*t_ns), 0.0) << "scan " << k;
  }
}

TEST(ScanIntervalClock, AGapIsTheTimeBeyondTheUsualIntervalAtAnyRate) {
  for (const int64_t period_ms : {50, 100, 200}) {
    ScanIntervalClock clock;
    int64_t t_ns = 1'000 * kMs;
    TickSteadily(&clock, &t_ns, 20, period_ms);
    EXPECT_EQ(clock.UsualIntervalNs(), period_ms * kMs);
    // Two scans dropped: still tracked through, not a gap.
    t_ns += 3 * period_ms * kMs;
    EXPECT_EQ(clock.Tick(t_ns), 0.0) << period_ms << " ms";
    t_ns += 4 * period_ms * kMs;
    EXPECT_DOUBLE_EQ(clock.GapBefore(t_ns), 3 * period_ms * 1e-3) << "without ticking";
    EXPECT_DOUBLE_EQ(clock.Tick(t_ns), 3 * period_ms * 1e-3) << period_ms << " ms";
    EXPECT_EQ(clock.GapBefore(t_ns + period_ms * kMs), 0.0) << "ticked: the next one is usual";
  }
}

TEST(ScanIntervalClock, NothingIsAGapBeforeTheRateIsKnownOrWhenTimeGoesBack) {
  ScanIntervalClock clock;
  EXPECT_EQ(clock.UsualIntervalNs(), 0);
  int64_t t_ns = 1'000 * kMs;
  EXPECT_EQ(clock.Tick(t_ns), 0.0);
  t_ns += 100 * kMs;
  EXPECT_EQ(clock.Tick(t_ns), 0.0);
  t_ns += 5'000 * kMs;  // a long interval among the first ones: no rate to judge it by yet
  EXPECT_EQ(clock.Tick(t_ns), 0.0);
  TickSteadily(&clock, &t_ns, 10, 100);
  EXPECT_EQ(clock.Tick(t_ns - 50 * kMs), 0.0);  // backwards: no gap, not an interval
  EXPECT_EQ(clock.UsualIntervalNs(), 100 * kMs);
}

TEST(ScanIntervalClock, AGapDoesNotBecomeTheUsualInterval) {
  ScanIntervalClock clock;
  int64_t t_ns = 1'000 * kMs;
  TickSteadily(&clock, &t_ns, 10, 100);
  for (int k = 0; k < 20; ++k) {  // a gap after every scan still reads as one
    t_ns += 1'000 * kMs;
    EXPECT_GT(clock.Tick(t_ns), 0.0) << k;
    TickSteadily(&clock, &t_ns, 1, 100);
  }
  EXPECT_EQ(clock.UsualIntervalNs(), 100 * kMs);
}

}  // namespace
}  // namespace hylo::odometry
