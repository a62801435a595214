#pragma once
// JSON for the machine-readable summaries (`--json PATH`), manifests, and the runs that
// `hylo compare` and `hylo demo` start in their own processes and read back. The value type is
// nlohmann's ordered_json: objects keep insertion order, so a summary reads top-down like the
// terminal output, and non-finite doubles are written as null (JSON has no NaN), so a summary
// with a failed figure stays parseable.

#include <nlohmann/json.hpp>
#include <string>

namespace hylo::io {

using Json = nlohmann::ordered_json;

/// The text of `json`; indent < 0 writes one line. Bytes that are not UTF-8 (a path from an
/// odd file system, say) are written as U+FFFD instead of throwing, so a summary is never lost
/// over one string.
std::string DumpJson(const Json& json, int indent = 2);

/// Writes `json` (indented) to `path`. Throws std::runtime_error naming the file when it cannot
/// be written; a file that failed half-way is removed.
void WriteJsonFile(const std::string& path, const Json& json);

/// Reads and parses a JSON file. Throws std::runtime_error naming the file and the reason: it
/// cannot be opened, or the byte offset, line and column where the text stops being JSON.
Json ReadJsonFile(const std::string& path);

/// The number at a dotted key path ("c2c.mean_m"), or NaN when a key is absent, null or not a
/// number.
double NumberAt(const Json& json, const std::string& dotted_path);

}  // namespace hylo::io
