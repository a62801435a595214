#include "message_decode.h"

#include <stdexcept>

#include "printable.h"

namespace hylo::logs::detail {
namespace {

std::string Describe(const TopicTypes& topics) {
  std::string out;
  for (const auto& [topic, types] : topics) {
    out += (out.empty() ? "" : ", ") + Printable(topic) + " (" + Printable(types.front()) + ")";
  }
  return out.empty() ? "none" : out;
}

std::string Alternatives(const std::vector<std::string>& types) {
  std::string out;
  for (std::size_t i = 0; i < types.size(); ++i) {
    out += (i == 0 ? "" : i + 1 == types.size() ? " or " : ", ") + types[i];
  }
  return out;
}

}  // namespace

void RequireTopic(const std::string& path, const TopicTypes& topics, const std::string& topic,
                  const std::vector<std::string>& types) {
  const auto it = topics.find(topic);
  if (it == topics.end()) {
    throw std::runtime_error("bag '" + path + "': no topic '" + topic + "' (" +
                             Alternatives(types) + "); topics in the bag: " + Describe(topics));
  }
  for (const std::string& found : it->second) {
    bool known = false;
    for (const std::string& type : types) known = known || found == type;
    if (!known) {
      throw std::runtime_error("bag '" + path + "': topic '" + topic + "' has type " +
                               Printable(found) + ", expected " + Alternatives(types));
    }
  }
}

PointTimeConvention CheckFirstCloud(const PointCloud2Message& first, PointTimeConvention convention,
                                    const std::string& path, const std::string& topic) {
  if (convention == PointTimeConvention::kAuto) {
    convention = DetectPointTimeConvention(first.fields);
  }
  try {
    DecodePointCloud2(first, convention, nullptr);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("bag '" + path + "', topic '" + topic +
                             "', first message: " + e.what());
  }
  return convention;
}

void DecodeScan(const PointCloud2Message& cloud, PointTimeConvention convention,
                LogMessage* message, LogReadCounters* counters) {
  message->kind = LogMessage::Kind::kScan;
  message->scan = DecodePointCloud2(cloud, convention, &counters->dropped_non_finite_points);
  ++counters->scan_messages;
  if (message->scan.points.empty()) ++counters->empty_scans;
}

bool AcceptImu(const ImuSample& imu, LogMessage* message, LogReadCounters* counters) {
  message->imu = imu;
  if (!imu.accel_imu.allFinite() || !imu.gyro_imu.allFinite()) {
    ++counters->dropped_non_finite_imu;
    return false;
  }
  message->kind = LogMessage::Kind::kImu;
  ++counters->imu_messages;
  return true;
}

}  // namespace hylo::logs::detail
