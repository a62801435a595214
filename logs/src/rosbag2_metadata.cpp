// metadata.yaml read with yaml-cpp, key by key, so that an error names the key a user can find.

#include "rosbag2_metadata.h"

#include <yaml-cpp/yaml.h>

#include <fstream>
#include <sstream>
#include <stdexcept>

#include "printable.h"

namespace hylo::logs::detail {
namespace {

/// Reads values under one key path, throwing errors that name the file and the key.
class Keys {
 public:
  explicit Keys(const std::string& source) : source_(source) {}

  [[noreturn]] void Fail(const std::string& key, const std::string& why) const {
    throw std::runtime_error(Printable(source_ + ": '" + key + "' " + why));
  }

  YAML::Node Required(const YAML::Node& parent, const std::string& name,
                      const std::string& key) const {
    if (!parent.IsMap() || !parent[name]) Fail(key, "is missing");
    return parent[name];
  }

  template <typename T>
  T As(const YAML::Node& node, const std::string& key) const {
    try {
      if (!node.IsScalar()) Fail(key, "is not a single value");
      return node.as<T>();
    } catch (const YAML::Exception&) {
      Fail(key, "has a value of the wrong type ('" + node.Scalar() + "')");
    }
  }

  template <typename T>
  T Optional(const YAML::Node& parent, const std::string& name, const std::string& key,
             T fallback) const {
    if (!parent.IsMap() || !parent[name] || parent[name].IsNull()) return fallback;
    return As<T>(parent[name], key);
  }

  YAML::Node Sequence(const YAML::Node& parent, const std::string& name,
                      const std::string& key) const {
    YAML::Node node = Required(parent, name, key);
    if (!node.IsSequence()) Fail(key, "is not a list");
    return node;
  }

 private:
  std::string source_;
};

int64_t Nanoseconds(const Keys& k, const YAML::Node& parent, const std::string& name,
                    const std::string& field, const std::string& key) {
  if (!parent.IsMap() || !parent[name]) return 0;
  const YAML::Node node = parent[name];
  if (!node.IsMap()) k.Fail(key, "is not a map");
  // rosbag2 writes the start of an empty recording as the largest int64.
  return k.Optional<int64_t>(node, field, key + "." + field, 0);
}

Rosbag2TopicInfo ParseTopic(const Keys& k, const YAML::Node& entry, const std::string& key) {
  Rosbag2TopicInfo t;
  const YAML::Node meta = k.Required(entry, "topic_metadata", key + ".topic_metadata");
  const std::string mkey = key + ".topic_metadata";
  t.name = k.As<std::string>(k.Required(meta, "name", mkey + ".name"), mkey + ".name");
  t.type = k.As<std::string>(k.Required(meta, "type", mkey + ".type"), mkey + ".type");
  t.serialization_format =
      k.Optional<std::string>(meta, "serialization_format", mkey + ".serialization_format", "");
  t.offered_qos_profiles =
      k.Optional<std::string>(meta, "offered_qos_profiles", mkey + ".offered_qos_profiles", "");
  t.message_count = k.Optional<uint64_t>(entry, "message_count", key + ".message_count", 0);
  return t;
}

}  // namespace

Rosbag2Metadata ParseRosbag2Metadata(const std::string& yaml_text, const std::string& source) {
  const Keys k(source);
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw std::runtime_error(Printable(source + ": malformed YAML (" + e.what() + ")"));
  }
  const std::string top = "rosbag2_bagfile_information";
  const YAML::Node info = k.Required(root, top, top);
  if (!info.IsMap()) k.Fail(top, "is not a map");
  Rosbag2Metadata m;
  m.version = k.As<int>(k.Required(info, "version", top + ".version"), top + ".version");
  m.storage_identifier =
      k.As<std::string>(k.Required(info, "storage_identifier", top + ".storage_identifier"),
                        top + ".storage_identifier");
  const YAML::Node paths = k.Sequence(info, "relative_file_paths", top + ".relative_file_paths");
  for (std::size_t i = 0; i < paths.size(); ++i) {
    m.relative_file_paths.push_back(
        k.As<std::string>(paths[i], top + ".relative_file_paths[" + std::to_string(i) + "]"));
  }
  m.starting_time_ns =
      Nanoseconds(k, info, "starting_time", "nanoseconds_since_epoch", top + ".starting_time");
  m.duration_ns = Nanoseconds(k, info, "duration", "nanoseconds", top + ".duration");
  m.message_count = k.Optional<uint64_t>(info, "message_count", top + ".message_count", 0);
  const YAML::Node topics =
      k.Sequence(info, "topics_with_message_count", top + ".topics_with_message_count");
  for (std::size_t i = 0; i < topics.size(); ++i) {
    m.topics.push_back(
        ParseTopic(k, topics[i], top + ".topics_with_message_count[" + std::to_string(i) + "]"));
  }
  m.compression_format =
      k.Optional<std::string>(info, "compression_format", top + ".compression_format", "");
  m.compression_mode =
      k.Optional<std::string>(info, "compression_mode", top + ".compression_mode", "");
  if (info["files"] && !info["files"].IsNull()) {
    const YAML::Node files = k.Sequence(info, "files", top + ".files");
    for (std::size_t i = 0; i < files.size(); ++i) {
      const std::string key = top + ".files[" + std::to_string(i) + "]";
      Rosbag2FileInfo f;
      f.path = k.As<std::string>(k.Required(files[i], "path", key + ".path"), key + ".path");
      f.starting_time_ns = Nanoseconds(k, files[i], "starting_time", "nanoseconds_since_epoch",
                                       key + ".starting_time");
      f.duration_ns = Nanoseconds(k, files[i], "duration", "nanoseconds", key + ".duration");
      f.message_count = k.Optional<uint64_t>(files[i], "message_count", key + ".message_count", 0);
      m.files.push_back(f);
    }
  }
  return m;
}

Rosbag2Metadata ReadRosbag2Metadata(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot be read");
  std::stringstream text;
  text << in.rdbuf();
  return ParseRosbag2Metadata(text.str(), path);
}

std::string Rosbag2MetadataYaml(const Rosbag2Metadata& m) {
  YAML::Emitter out;
  const auto time = [&](const char* name, const char* field, int64_t ns) {
    out << YAML::Key << name << YAML::Value << YAML::BeginMap << YAML::Key << field << YAML::Value
        << ns << YAML::EndMap;
  };
  out << YAML::BeginMap << YAML::Key << "rosbag2_bagfile_information" << YAML::Value
      << YAML::BeginMap;
  out << YAML::Key << "version" << YAML::Value << m.version;
  out << YAML::Key << "storage_identifier" << YAML::Value << m.storage_identifier;
  time("duration", "nanoseconds", m.duration_ns);
  time("starting_time", "nanoseconds_since_epoch", m.starting_time_ns);
  out << YAML::Key << "message_count" << YAML::Value << m.message_count;
  out << YAML::Key << "topics_with_message_count" << YAML::Value << YAML::BeginSeq;
  for (const Rosbag2TopicInfo& t : m.topics) {
    out << YAML::BeginMap << YAML::Key << "topic_metadata" << YAML::Value << YAML::BeginMap;
    out << YAML::Key << "name" << YAML::Value << t.name;
    out << YAML::Key << "type" << YAML::Value << t.type;
    out << YAML::Key << "serialization_format" << YAML::Value << t.serialization_format;
    out << YAML::Key << "offered_qos_profiles" << YAML::Value << YAML::DoubleQuoted
        << t.offered_qos_profiles;
    out << YAML::EndMap << YAML::Key << "message_count" << YAML::Value << t.message_count
        << YAML::EndMap;
  }
  out << YAML::EndSeq;
  out << YAML::Key << "compression_format" << YAML::Value << YAML::DoubleQuoted
      << m.compression_format;
  out << YAML::Key << "compression_mode" << YAML::Value << YAML::DoubleQuoted << m.compression_mode;
  out << YAML::Key << "relative_file_paths" << YAML::Value << m.relative_file_paths;
  out << YAML::Key << "files" << YAML::Value << YAML::BeginSeq;
  for (const Rosbag2FileInfo& f : m.files) {
    out << YAML::BeginMap << YAML::Key << "path" << YAML::Value << f.path;
    time("starting_time", "nanoseconds_since_epoch", f.starting_time_ns);
    time("duration", "nanoseconds", f.duration_ns);
    out << YAML::Key << "message_count" << YAML::Value << f.message_count << YAML::EndMap;
  }
  out << YAML::EndSeq << YAML::EndMap << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace hylo::logs::detail
