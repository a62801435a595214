#pragma once
// The checks behind every options struct's `bool IsValid(std::string* why) const`: each
// returns true when the field is fine, else false with "<field> = <value>: <constraint>" in
// *why (when why is not null), so one chain of && names the first broken field.

#include <cmath>
#include <sstream>
#include <string>

namespace hylo {

/// "<field> = <value>: <constraint>" into *why; false.
template <class T>
bool FailOption(const std::string& field, const T& value, const std::string& constraint,
                std::string* why) {
  if (why != nullptr) {
    std::ostringstream os;
    os << field << " = " << value << ": " << constraint;
    *why = os.str();
  }
  return false;
}

inline bool CheckPositive(const char* field, double value, std::string* why) {
  return (std::isfinite(value) && value > 0.0) ||
         FailOption(field, value, "must be finite and > 0", why);
}

inline bool CheckNonNegative(const char* field, double value, std::string* why) {
  return (std::isfinite(value) && value >= 0.0) ||
         FailOption(field, value, "must be finite and >= 0", why);
}

/// lo <= value <= hi (and finite).
inline bool CheckInRange(const char* field, double value, double lo, double hi, std::string* why) {
  if (std::isfinite(value) && value >= lo && value <= hi) return true;
  std::ostringstream range;
  range << "must be in [" << lo << ", " << hi << "]";
  return FailOption(field, value, range.str(), why);
}

/// value >= minimum; `reason` (may be empty) is appended to the constraint.
inline bool CheckAtLeast(const char* field, int value, int minimum, const char* reason,
                         std::string* why) {
  if (value >= minimum) return true;
  std::string constraint = "must be >= " + std::to_string(minimum);
  if (reason != nullptr && reason[0] != '\0') constraint += std::string(" ") + reason;
  return FailOption(field, value, constraint, why);
}

/// A nested options struct: its IsValid, with "<section>." prefixed to the field it names.
template <class S>
bool CheckSection(const S& section, const std::string& name, std::string* why) {
  std::string inner;
  if (section.IsValid(&inner)) return true;
  if (why != nullptr) *why = name + "." + inner;
  return false;
}

}  // namespace hylo
