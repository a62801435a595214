// A ROS 2 recording written as rosbag2 writes one: topics registered on first use (their QoS as
// a reliable, volatile publisher's), each message CDR-encoded into the storage file, and
// metadata.yaml written last, once the storage file is whole.

#include "hylo/logs/rosbag2_writer.h"

#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "cdr_messages.h"
#include "hylo/io/atomic_file.h"
#include "mcap_writer.h"
#include "rosbag2_metadata.h"
#include "sqlite_writer.h"

namespace hylo::logs {
namespace {

namespace fs = std::filesystem;

// What `ros2 bag record` stores for a publisher with the default QoS (history keep-last,
// reliable, volatile; durations unset), in the format every rosbag2 since Foxy parses.
constexpr char kDefaultQos[] =
    "- history: 3\n  depth: 0\n  reliability: 1\n  durability: 2\n  deadline:\n    sec: 0\n"
    "    nsec: 0\n  lifespan:\n    sec: 0\n    nsec: 0\n  liveliness: 1\n"
    "  liveliness_lease_duration:\n    sec: 0\n    nsec: 0\n"
    "  avoid_ros_namespace_conventions: false";

struct Topic {
  std::string type;
  int64_t id = 0;  // MCAP channel id or sqlite3 topic id
  uint64_t count = 0;
};

}  // namespace

bool Rosbag2WriterOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  if (mcap_compression != "" && mcap_compression != "zstd" && mcap_compression != "lz4") {
    os << "mcap_compression = '" << mcap_compression << "' must be '', 'zstd' or 'lz4'";
  } else if (storage == Rosbag2Storage::kSqlite3 && !mcap_compression.empty()) {
    os << "mcap_compression = '" << mcap_compression << "' needs MCAP storage";
  } else if (mcap_chunk_bytes < 1024 || mcap_chunk_bytes > (uint64_t{1} << 30)) {
    os << "mcap_chunk_bytes = " << mcap_chunk_bytes << " must be in [1 KiB, 1 GiB]";
  }
  if (why != nullptr) *why = os.str();
  return os.str().empty();
}

struct Rosbag2Writer::Impl {
  std::string path;
  Rosbag2WriterOptions options;
  bool single_file = false;
  bool created_directory = false;
  std::string storage_name;  // the storage file's name, relative to the directory
  std::optional<detail::McapWriter> mcap;
  std::optional<detail::SqliteWriter> sqlite;
  std::map<std::string, Topic> topics;
  std::vector<std::string> topic_order;
  int64_t first_ns = 0, last_ns = 0;
  uint64_t messages = 0;
  bool open = true;

  void Open() {
    single_file = options.storage == Rosbag2Storage::kMcap && fs::path(path).extension() == ".mcap";
    std::string storage_path = path;
    if (!single_file) {
      std::error_code ec;
      created_directory = !fs::exists(path, ec);
      fs::create_directories(path, ec);
      if (ec || !fs::is_directory(path, ec)) {
        throw std::runtime_error("rosbag2 '" + path + "': cannot create the directory");
      }
      const std::string name = fs::path(path).filename().string();
      storage_name = name + (options.storage == Rosbag2Storage::kMcap ? "_0.mcap" : "_0.db3");
      storage_path = (fs::path(path) / storage_name).string();
      if (fs::exists(fs::path(path) / detail::kRosbag2MetadataFile, ec) ||
          fs::exists(storage_path, ec)) {
        throw std::runtime_error("rosbag2 '" + path + "': already holds a recording");
      }
    }
    if (options.storage == Rosbag2Storage::kMcap) {
      detail::McapWriterOptions o;
      o.compression = options.mcap_compression;
      o.chunk_bytes = options.mcap_chunk_bytes;
      mcap.emplace(storage_path, o);
    } else {
      sqlite.emplace(storage_path);
    }
  }

  Topic& TopicFor(const std::string& name, const std::string& type) {
    auto it = topics.find(name);
    if (it != topics.end()) {
      if (it->second.type != type) {
        throw std::invalid_argument("rosbag2 '" + path + "': topic '" + name + "' has type " +
                                    it->second.type + ", not " + type);
      }
      return it->second;
    }
    Topic t;
    t.type = type;
    if (mcap) {
      const std::string definition = detail::Ros2MessageDefinition(type);
      const uint16_t schema =
          mcap->AddSchema(type, definition.empty() ? "" : "ros2msg", definition);
      t.id = mcap->AddChannel(schema, name, "cdr", {{"offered_qos_profiles", kDefaultQos}});
    } else {
      t.id = sqlite->AddTopic(name, type, "cdr", kDefaultQos);
    }
    topic_order.push_back(name);
    return topics.emplace(name, t).first->second;
  }

  void Write(const std::string& topic, const std::string& type, int64_t receive_t_ns,
             const std::vector<uint8_t>& cdr) {
    if (!open) throw std::logic_error("rosbag2 '" + path + "': write after Close()");
    if (receive_t_ns < 0) {
      throw std::invalid_argument("negative receive time " + std::to_string(receive_t_ns) + " ns");
    }
    Topic& t = TopicFor(topic, type);
    if (mcap) {
      mcap->WriteMessage(static_cast<uint16_t>(t.id), static_cast<uint64_t>(receive_t_ns),
                         cdr.data(), cdr.size());
    } else {
      sqlite->Write(t.id, receive_t_ns, cdr.data(), cdr.size());
    }
    ++t.count;
    if (messages++ == 0) first_ns = last_ns = receive_t_ns;
    first_ns = std::min(first_ns, receive_t_ns);
    last_ns = std::max(last_ns, receive_t_ns);
  }

  detail::Rosbag2Metadata Metadata() const {
    detail::Rosbag2Metadata m;
    m.version = 5;
    m.storage_identifier = mcap ? "mcap" : "sqlite3";
    m.relative_file_paths = {storage_name};
    m.starting_time_ns = first_ns;
    m.duration_ns = last_ns - first_ns;
    m.message_count = messages;
    for (const std::string& name : topic_order) {
      const Topic& t = topics.at(name);
      m.topics.push_back({name, t.type, "cdr", kDefaultQos, t.count});
    }
    m.files.push_back({storage_name, first_ns, last_ns - first_ns, messages});
    return m;
  }

  void Close() {
    if (!open) return;
    open = false;
    const detail::Rosbag2Metadata metadata = Metadata();
    const std::string yaml = detail::Rosbag2MetadataYaml(metadata);
    if (mcap) mcap->Close();
    if (sqlite) sqlite->Close(metadata.version, yaml);
    if (!single_file) {
      io::WriteFileAtomically((fs::path(path) / detail::kRosbag2MetadataFile).string(), yaml);
    }
  }

  /// A writer given up: its storage file's temporary goes with it, and the directory if this
  /// writer made it and nothing else is in it.
  void Abandon() {
    mcap.reset();
    sqlite.reset();
    std::error_code ec;
    if (created_directory && fs::is_empty(path, ec)) fs::remove(path, ec);
  }
};

Rosbag2Writer::Rosbag2Writer(const std::string& path, const Rosbag2WriterOptions& options)
    : impl_(std::make_unique<Impl>()) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("Rosbag2WriterOptions: " + why);
  impl_->path = path;
  impl_->options = options;
  impl_->Open();
}

Rosbag2Writer::~Rosbag2Writer() {
  if (impl_->open) impl_->Abandon();
}

void Rosbag2Writer::WriteImu(const std::string& topic, const ImuSample& imu,
                             const std::string& frame_id, int64_t receive_t_ns) {
  impl_->Write(topic, detail::kRos2ImuType, receive_t_ns >= 0 ? receive_t_ns : imu.t_ns,
               detail::EncodeCdrImu(imu, frame_id));
}

void Rosbag2Writer::WriteCloud(const std::string& topic, const PointCloud2Message& cloud,
                               int64_t receive_t_ns) {
  impl_->Write(topic, detail::kRos2CloudType, receive_t_ns, detail::EncodeCdrPointCloud2(cloud));
}

void Rosbag2Writer::WriteCdr(const std::string& topic, const std::string& type,
                             int64_t receive_t_ns, const std::vector<uint8_t>& cdr) {
  impl_->Write(topic, type, receive_t_ns, cdr);
}

void Rosbag2Writer::Close() {
  try {
    impl_->Close();
  } catch (...) {
    impl_->Abandon();
    throw;
  }
}

}  // namespace hylo::logs
