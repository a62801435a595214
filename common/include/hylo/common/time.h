#pragma once
// Time inside the library is int64 nanoseconds; doubles appear only at file boundaries.

#include <cmath>
#include <cstdint>

namespace hylo {

constexpr int64_t kNanosPerSecond = 1'000'000'000;

/// Seconds (double, e.g. from a file) to nanoseconds, rounded to the nearest nanosecond.
inline int64_t SecondsToNanos(double seconds) {
  return static_cast<int64_t>(std::llround(seconds * 1e9));
}
/// Nanoseconds to seconds, for file output and for arithmetic that needs a duration in s.
inline double NanosToSeconds(int64_t t_ns) { return static_cast<double>(t_ns) * 1e-9; }

}  // namespace hylo
