// DescribeRosbag2: storage, compression, topics with counts and log-time spans, point fields.
// Counts come from the files' indexes where they have them (sqlite3 tables, MCAP message
// indexes), else from reading every message (a recording without its index or damaged).

#include <algorithm>
#include <filesystem>
#include <set>

#include "cdr_messages.h"
#include "hylo/logs/rosbag2_reader.h"
#include "rosbag2_stream.h"

namespace hylo::logs {
namespace {

using detail::StorageMessage;
using detail::TopicStatistics;

bool IsCloudType(const std::string& type) {
  return type == detail::kRos2CloudType || type == detail::kLivoxCustomType;
}

std::string Compression(const detail::Rosbag2Layout& layout, const detail::Rosbag2Stream& stream) {
  if (!layout.compression_mode.empty()) return "zstd (per " + layout.compression_mode + ")";
  std::set<std::string> codecs;
  for (const auto& source : stream.sources()) {
    for (const std::string& c : source->ChunkCompressions()) codecs.insert(c.empty() ? "none" : c);
  }
  std::string out;
  for (const std::string& c : codecs) out += (out.empty() ? "" : ", ") + c;
  return out.empty() ? "none" : out;
}

/// The first message's fields of each point cloud topic in `stats` with messages, read from a
/// stream of its own (one message per topic decoded).
void DescribeClouds(const detail::Rosbag2Layout& layout,
                    const std::map<std::string, TopicStatistics>& stats,
                    std::map<std::string, BagTopicDescription>* topics) {
  std::set<std::string> wanted;
  for (const auto& [name, s] : stats) {
    if (IsCloudType(s.type) && s.count > 0) wanted.insert(name);
  }
  if (wanted.empty()) return;
  detail::Rosbag2Stream stream(layout);
  detail::MessageBytes bytes(layout.compression_mode == "message");
  StorageMessage m;
  while (!wanted.empty() && stream.Next(&m)) {
    if (wanted.erase(m.topic->name) == 0 || !IsCloudType(m.topic->type)) continue;
    BagTopicDescription& t = (*topics)[m.topic->name];
    try {
      const auto [data, size] = bytes.Of(m);
      t.point_fields = detail::DecodeCdrCloud(m.topic->type, data, size).fields;
      t.detected_convention = DetectPointTimeConvention(t.point_fields);
    } catch (const std::exception&) {  // an unreadable first cloud: no field list
    }
  }
}

}  // namespace

Rosbag2Description DescribeRosbag2(const std::string& path) {
  const detail::Rosbag2Layout layout = detail::ResolveRosbag2(path);
  detail::Rosbag2Stream stream(layout);
  Rosbag2Description d;
  d.path = path;
  d.storage = layout.storage;
  d.metadata_version = layout.metadata ? layout.metadata->version : 0;
  for (const auto& source : stream.sources()) d.size_bytes += source->file_bytes();
  for (const std::string& f : layout.files) d.files.push_back(std::filesystem::path(f).filename());

  std::map<std::string, TopicStatistics> stats;
  bool indexed = stream.recovery() == nullptr;
  for (const auto& source : stream.sources()) {
    indexed = indexed && source->IndexedStatistics(&stats);
  }
  if (!indexed) {  // every message read
    stats.clear();
    StorageMessage m;
    while (stream.Next(&m)) {
      TopicStatistics& t = stats[m.topic->name];
      t.type = m.topic->type;
      ++t.count;
      t.first_ns = std::min(t.first_ns, m.log_time_ns);
      t.last_ns = std::max(t.last_ns, m.log_time_ns);
    }
  }
  for (const auto& [name, types] : stream.Topics()) {
    if (stats.count(name) == 0) stats[name].type = types.front();
  }
  d.compression = Compression(layout, stream);
  std::map<std::string, BagTopicDescription> topics;
  d.start_ns = std::numeric_limits<int64_t>::max();
  d.end_ns = std::numeric_limits<int64_t>::min();
  for (const auto& [name, s] : stats) {
    BagTopicDescription& t = topics[name];
    t.name = name;
    t.type = s.type;
    t.message_count = s.count;
    if (s.count == 0) continue;
    t.first_stamp_ns = s.first_ns;
    t.last_stamp_ns = s.last_ns;
    const int64_t span_ns = s.last_ns - s.first_ns;
    if (s.count > 1 && span_ns > 0) t.mean_rate_hz = (s.count - 1) / (span_ns * 1e-9);
    d.message_count += s.count;
    d.start_ns = std::min(d.start_ns, s.first_ns);
    d.end_ns = std::max(d.end_ns, s.last_ns);
  }
  if (d.message_count == 0) d.start_ns = d.end_ns = 0;
  d.duration_s = (d.end_ns - d.start_ns) * 1e-9;
  DescribeClouds(layout, stats, &topics);
  for (auto& [name, t] : topics) d.topics.push_back(std::move(t));
  if (const LogRecovery* r = stream.recovery()) d.recovery = *r;
  return d;
}

}  // namespace hylo::logs
