#pragma once
// Small helpers shared by the file readers (PLY and PCD headers, trajectories, scan folders'
// pose and time files): words, case, and the one shape of a file error.

#include <string>
#include <vector>

namespace hylo::io {

/// Throws std::runtime_error("<path>: <reason>"), the message every reader gives.
[[noreturn]] void ThrowFileError(const std::string& path, const std::string& reason);
/// Lower-cased copy (ASCII).
std::string ToLower(std::string text);
/// Splits on blanks (spaces, tabs, \r).
std::vector<std::string> SplitWords(const std::string& line);

}  // namespace hylo::io
