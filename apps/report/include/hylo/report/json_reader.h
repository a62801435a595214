#pragma once
// Reads JSON text back into io::Json (which only writes): `hylo compare` and `hylo demo` run
// each back-end in its own process and read that run's summary.json. Whole RFC 8259 values
// (objects, arrays, strings with escapes, numbers, true/false/null); integers without a
// fraction or exponent stay integers.

#include <string>

#include "hylo/io/json.h"

namespace hylo::report {

/// Parses `text`. Throws std::runtime_error naming `source_name`, the byte offset and the
/// reason (unexpected character, unterminated string, trailing text, ...).
io::Json ParseJson(const std::string& text, const std::string& source_name);

/// Reads and parses a file (std::runtime_error naming the file when it cannot be read).
io::Json ReadJsonFile(const std::string& path);

/// The number at a dotted key path ("c2c.mean_m"), or NaN when a key is absent, null or not a
/// number.
double NumberAt(const io::Json& json, const std::string& dotted_path);

}  // namespace hylo::report
