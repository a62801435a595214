#pragma once
// The message every options struct's IsValid gives for a field out of range.

#include <sstream>
#include <string>

namespace hylo {

/// Writes "<owner>.<field> = <value>: must be <constraint>" into *why (when not null) and
/// returns false, so that IsValid can `return OptionError(...)`.
template <typename T>
bool OptionError(std::string* why, const char* owner, const char* field, const T& value,
                 const char* constraint) {
  if (why != nullptr) {
    std::ostringstream os;
    os << owner << "." << field << " = " << value << ": must be " << constraint;
    *why = os.str();
  }
  return false;
}

}  // namespace hylo
