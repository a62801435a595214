#include "hylo/logs/log_reader.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "hylo/logs/bag_reader.h"
#include "hylo/logs/rosbag2_reader.h"
#include "hylo/logs/scan_folder.h"

namespace hylo::logs {

std::string LogRecovery::Summary() const {
  char line[160];
  std::snprintf(line, sizeof(line),
                ": recovered %zu messages over %.3f s; last %llu bytes unreadable", messages,
                messages > 0 ? span_s() : 0.0, static_cast<unsigned long long>(unreadable_bytes));
  return damage + line + (stop_reason.empty() ? "" : " (" + stop_reason + ")");
}

std::unique_ptr<LogReader> OpenLog(const std::string& path, const LogReadOptions& options) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw std::runtime_error("log '" + path + "' does not exist");
  // A rosbag2 directory or storage file is told by its content, not its name.
  if (IsRosbag2(path)) return OpenRosbag2(path, options);
  if (fs::is_directory(path, ec)) return OpenScanFolder(path, options);
  return OpenBag(path, options);
}

}  // namespace hylo::logs
