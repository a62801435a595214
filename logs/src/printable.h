#pragma once
// Private to hylo_io: a name read from a file (a PointCloud2 field, a bag's topic, type or
// md5sum) as the one-line errors show it.

#include <cctype>
#include <string>

namespace hylo::logs::detail {

/// `text` with each control character replaced by '?': the text comes from the file, and a
/// line break in it would split the one-line error.
inline std::string Printable(std::string text) {
  for (char& c : text) {
    if (std::iscntrl(static_cast<unsigned char>(c))) c = '?';
  }
  return text;
}

}  // namespace hylo::logs::detail
