#pragma once
// Programmer-error checks. Bad *data* never reaches these: it is reported through a status
// in the returned summary. A failed check throws hylo::InternalError (never exit/abort), so a
// host application can log it and keep its own process alive.

#include <sstream>
#include <stdexcept>
#include <string>

namespace hylo {

/// Thrown when an invariant of the library itself is broken (a bug, not bad input).
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

namespace detail {
[[noreturn]] inline void FailCheck(const char* expr, const char* file, int line,
                                   const std::string& message) {
  std::ostringstream os;
  os << file << ":" << line << ": check failed: " << expr;
  if (!message.empty()) os << " (" << message << ")";
  throw InternalError(os.str());
}
}  // namespace detail
}  // namespace hylo

/// HYLO_CHECK(cond) or HYLO_CHECK(cond, "message"): throws hylo::InternalError if cond is false.
#define HYLO_CHECK(cond, ...)                                                       \
  do {                                                                              \
    if (!(cond)) ::hylo::detail::FailCheck(#cond, __FILE__, __LINE__, "" __VA_ARGS__); \
  } while (0)
