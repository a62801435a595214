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
/// (The selector keeps the variadic part non-empty, which ISO C++17 requires under -Wpedantic.)
#define HYLO_CHECK(...) \
  HYLO_CHECK_SELECT_(__VA_ARGS__, HYLO_CHECK_MESSAGE_, HYLO_CHECK_PLAIN_, unused)(__VA_ARGS__)
#define HYLO_CHECK_SELECT_(a1, a2, name, ...) name
#define HYLO_CHECK_PLAIN_(cond) HYLO_CHECK_MESSAGE_(cond, "")
#define HYLO_CHECK_MESSAGE_(cond, message)                                      \
  do {                                                                          \
    if (!(cond)) ::hylo::detail::FailCheck(#cond, __FILE__, __LINE__, message); \
  } while (0)
