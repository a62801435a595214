#pragma once
// Private to hylo_io: opening a ROS1 bag with one-line errors that name the file, and
// reading one of its messages.

#include <rosbag/bag.h>
#include <rosbag/exceptions.h>
#include <rosbag/message_instance.h>

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "hylo/io/ros_bridge.h"

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

/// The message, deserialized with ros_bridge::Deserialize rather than
/// MessageInstance::instantiate, whose stream lets a corrupt array length allocate gigabytes.
/// The caller checks the message type. Throws std::runtime_error (ROS or rosbag exceptions)
/// on corrupt data.
template <class Message>
Message ReadMessage(const rosbag::MessageInstance& m) {
  std::vector<uint8_t> bytes(m.size());
  ros::serialization::OStream out(bytes.data(), static_cast<uint32_t>(bytes.size()));
  m.write(out);
  return ros_bridge::Deserialize<Message>(bytes.data(), bytes.size());
}

}  // namespace hylo::io::detail
