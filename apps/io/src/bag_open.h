#pragma once
// Private to hylo_io: opening a ROS1 bag with one-line errors that name the file.

#include <rosbag/bag.h>
#include <rosbag/exceptions.h>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace hylo::io::detail {

/// Opens a bag for reading; one-line std::runtime_error naming the file on any failure.
inline void OpenForReading(const std::string& path, rosbag::Bag* bag) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    throw std::runtime_error("bag '" + path + "': no such file");
  }
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw std::runtime_error("bag '" + path + "': not a regular file");
  }
  try {
    bag->open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagUnindexedException& e) {
    throw std::runtime_error("bag '" + path + "': has no index (recording interrupted?); " +
                             "`rosbag reindex` can rebuild it");
  } catch (const std::exception& e) {
    throw std::runtime_error("bag '" + path + "': cannot be read, truncated or not a ROS1 bag (" +
                             e.what() + ")");
  }
}

}  // namespace hylo::io::detail
