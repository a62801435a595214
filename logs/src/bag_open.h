#pragma once
// Private to hylo_io: opening a ROS1 bag with one-line errors that name the file, telling a
// bag rosbag cannot index (recording killed, file cut: read record by record instead) from a
// file that is no bag at all, and reading one of its messages through a bounded stream.

#include <rosbag/bag.h>
#include <rosbag/exceptions.h>
#include <rosbag/message_instance.h>

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "hylo/logs/ros_bridge.h"

#include "bag_records.h"

namespace hylo::logs::detail {

/// Opens a bag through its index. Throws a one-line std::runtime_error naming the file when it
/// is missing, not a regular file, or unreadable and not a bag v2.0. Returns false, with what
/// is wrong in `*damage`, for a bag v2.0 whose index rosbag cannot read: no index (the
/// recording was killed) or an index cut off with the end of the file.
inline bool OpenIndexed(const std::string& path, rosbag::Bag* bag, std::string* damage) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) {
    throw std::runtime_error("bag '" + path + "': no such file");
  }
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw std::runtime_error("bag '" + path + "': not a regular file");
  }
  try {
    bag->open(path, rosbag::bagmode::Read);
    return true;
  } catch (const rosbag::BagUnindexedException&) {
    *damage = "no index (recording interrupted?)";
  } catch (const std::exception& e) {
    if (!HasBagV2Magic(path)) {
      throw std::runtime_error("bag '" + path + "': cannot be read, truncated or not a ROS1 bag (" +
                               e.what() + ")");
    }
    *damage = "index unreadable (file cut short?)";
  }
  return false;
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

}  // namespace hylo::logs::detail
