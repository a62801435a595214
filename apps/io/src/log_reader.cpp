#include "hylo/io/log_reader.h"

#include <filesystem>
#include <stdexcept>

#include "hylo/io/bag_reader.h"
#include "hylo/io/scan_folder.h"

namespace hylo::io {

std::unique_ptr<LogReader> OpenLog(const std::string& path, const LogReadOptions& options) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::exists(path, ec)) throw std::runtime_error("log '" + path + "' does not exist");
  if (fs::is_directory(path, ec)) return OpenScanFolder(path, options);
  return OpenBag(path, options);
}

}  // namespace hylo::io
