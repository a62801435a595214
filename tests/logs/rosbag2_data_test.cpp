// Conformance with real ROS 2 recordings (rosbag2's own test resources, recorded by ROS 2's
// tools; see the data README): every bag, sqlite3 and MCAP, several metadata versions, split
// and empty ones, listed with exactly the topics, types and counts its metadata.yaml states,
// and walked message by message in log-time order. Their messages are std_msgs and test_msgs
// types, which hylo does not decode as sensor data; the test_msgs ones are decoded here field by
// field with the CDR reader, a check of its alignment rules on bytes another implementation
// wrote. Skipped visibly when the data is absent.

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cdr_reader.h"
#include "hylo/logs/log_reader.h"
#include "hylo/logs/rosbag2_reader.h"
#include "rosbag2_stream.h"
#include "test_data.h"

namespace hylo::logs {
namespace {

namespace fs = std::filesystem;

/// What a bag's metadata.yaml states, read here with yaml-cpp directly.
struct Expected {
  std::string storage;
  uint64_t message_count = 0;
  std::map<std::string, std::pair<std::string, uint64_t>> topics;  // name -> type, count
  std::vector<std::string> files;
  bool has_file_times = false;  // version >= 5: per-file start and duration
  int64_t start_ns = 0, duration_ns = 0;
};

Expected ReadExpected(const std::string& dir) {
  const YAML::Node info = YAML::LoadFile(dir + "/metadata.yaml")["rosbag2_bagfile_information"];
  Expected e;
  e.storage = info["storage_identifier"].as<std::string>();
  e.message_count = info["message_count"].as<uint64_t>();
  for (const auto& t : info["topics_with_message_count"]) {
    e.topics[t["topic_metadata"]["name"].as<std::string>()] = {
        t["topic_metadata"]["type"].as<std::string>(), t["message_count"].as<uint64_t>()};
  }
  for (const auto& f : info["relative_file_paths"]) e.files.push_back(f.as<std::string>());
  e.has_file_times = static_cast<bool>(info["files"]);
  e.start_ns = info["starting_time"]["nanoseconds_since_epoch"].as<int64_t>();
  e.duration_ns = info["duration"]["nanoseconds"].as<int64_t>();
  return e;
}

std::vector<std::string> BagDirs() {
  std::vector<std::string> dirs;
  const std::string root = testing::DataPath("rosbag2");
  for (const char* storage : {"mcap", "sqlite3"}) {
    std::error_code ec;
    for (const auto& entry : fs::directory_iterator(root + "/" + storage, ec)) {
      if (fs::exists(entry.path() / "metadata.yaml")) dirs.push_back(entry.path().string());
    }
  }
  std::sort(dirs.begin(), dirs.end());
  return dirs;
}

void ExpectListedAsStated(const Rosbag2Description& d, const Expected& e, const std::string& dir) {
  SCOPED_TRACE(dir);
  EXPECT_EQ(d.storage, e.storage);
  EXPECT_EQ(d.message_count, e.message_count);
  EXPECT_EQ(d.files, e.files);
  std::map<std::string, std::pair<std::string, uint64_t>> listed;
  for (const BagTopicDescription& t : d.topics) listed[t.name] = {t.type, t.message_count};
  EXPECT_EQ(listed, e.topics);
  if (e.has_file_times && e.message_count > 0) {  // earlier versions' spans are not reliable
    EXPECT_EQ(d.start_ns, e.start_ns);
    EXPECT_EQ(d.end_ns - d.start_ns, e.duration_ns);
  }
  EXPECT_FALSE(d.recovery.has_value());
}

TEST(Rosbag2Data, EveryBagIsListedWithItsTopicsTypesAndCounts) {
  HYLO_REQUIRE_DATA("rosbag2");
  const std::vector<std::string> dirs = BagDirs();
  ASSERT_EQ(dirs.size(), 8u);  // 4 MCAP, 4 sqlite3
  for (const std::string& dir : dirs) {
    const Rosbag2Description d = DescribeRosbag2(dir);
    std::printf("%-60s %-7s %-12s %5zu messages in %zu file(s), %zu topics\n", dir.c_str(),
                d.storage.c_str(), d.compression.c_str(), d.message_count, d.files.size(),
                d.topics.size());
    ExpectListedAsStated(d, ReadExpected(dir), dir);
  }
}

TEST(Rosbag2Data, EveryBagIsWalkedInLogTimeOrderWithItsCounts) {
  HYLO_REQUIRE_DATA("rosbag2");
  for (const std::string& dir : BagDirs()) {
    SCOPED_TRACE(dir);
    const Expected e = ReadExpected(dir);
    detail::Rosbag2Stream stream(detail::ResolveRosbag2(dir));
    std::map<std::string, uint64_t> counts;
    detail::StorageMessage m;
    int64_t last_ns = std::numeric_limits<int64_t>::min();
    uint64_t total = 0;
    while (stream.Next(&m)) {
      ++counts[m.topic->name];
      ++total;
      EXPECT_GE(m.log_time_ns, last_ns) << "message " << total;
      last_ns = m.log_time_ns;
      EXPECT_EQ(m.topic->serialization_format, "cdr");
      EXPECT_GE(m.size, 4u);  // at least the CDR header
    }
    EXPECT_EQ(total, e.message_count);
    for (const auto& [name, expected] : e.topics) {
      EXPECT_EQ(counts[name], expected.second) << name;
    }
    EXPECT_EQ(stream.recovery(), nullptr);
  }
}

TEST(Rosbag2Data, ASingleMcapFileIsReadWithoutItsMetadata) {
  HYLO_REQUIRE_DATA("rosbag2/mcap/talker/talker.mcap");
  const std::string dir = testing::DataPath("rosbag2/mcap/talker");
  const Rosbag2Description d = DescribeRosbag2(dir + "/talker.mcap");
  EXPECT_EQ(d.metadata_version, 0);
  EXPECT_EQ(d.compression, "zstd");
  ExpectListedAsStated(d, ReadExpected(dir), dir);
  EXPECT_TRUE(IsRosbag2(dir + "/talker.mcap"));
  EXPECT_TRUE(IsRosbag2(dir));
}

/// test_msgs/BasicTypes: bool byte char float32 float64 int8 uint8 int16 uint16 int32 uint32
/// int64 uint64.
void ReadBasicTypes(detail::CdrReader* in, int32_t* int32_value) {
  for (int i = 0; i < 3; ++i) in->Read<uint8_t>();
  in->Read<float>();
  in->Read<double>();
  in->Read<int8_t>();
  in->Read<uint8_t>();
  in->Read<int16_t>();
  in->Read<uint16_t>();
  *int32_value = in->Read<int32_t>();
  in->Read<uint32_t>();
  in->Read<int64_t>();
  in->Read<uint64_t>();
}

/// Each fixed array of 3 of the basic types, as test_msgs/Arrays lays them out.
void ReadBasicArrays(detail::CdrReader* in, std::vector<std::string>* strings) {
  for (int i = 0; i < 9; ++i) in->Read<uint8_t>();  // bool[3] byte[3] char[3]
  for (int i = 0; i < 3; ++i) in->Read<float>();
  for (int i = 0; i < 3; ++i) in->Read<double>();
  for (int i = 0; i < 6; ++i) in->Read<uint8_t>();  // int8[3] uint8[3]
  for (int i = 0; i < 6; ++i) in->Read<uint16_t>();
  for (int i = 0; i < 6; ++i) in->Read<uint32_t>();
  for (int i = 0; i < 6; ++i) in->Read<uint64_t>();
  for (int i = 0; i < 3; ++i) strings->push_back(in->ReadString());
}

TEST(Rosbag2Data, TestMessagesDecodeFieldByFieldToTheirLastByte) {
  HYLO_REQUIRE_DATA("rosbag2");
  for (const char* storage : {"mcap", "sqlite3"}) {
    SCOPED_TRACE(storage);
    detail::Rosbag2Stream stream(
        detail::ResolveRosbag2(testing::DataPath(std::string("rosbag2/") + storage + "/cdr_test")));
    detail::StorageMessage m;
    int basic = 0, arrays = 0;
    while (stream.Next(&m)) {
      detail::CdrReader in(m.data, m.size);
      if (m.topic->type == "test_msgs/msg/BasicTypes") {
        int32_t value = 0;
        ReadBasicTypes(&in, &value);
        EXPECT_EQ(value, 123);
        ++basic;
      } else {
        ASSERT_EQ(m.topic->type, "test_msgs/msg/Arrays");
        std::vector<std::string> strings;
        ReadBasicArrays(&in, &strings);
        EXPECT_EQ(strings,
                  (std::vector<std::string>{"Complex Hello1", "Complex Hello2", "Complex Hello3"}));
        int32_t value = 0;
        for (int i = 0; i < 3; ++i) ReadBasicTypes(&in, &value);
        for (int i = 0; i < 3; ++i) in.Read<uint8_t>();  // Constants[3]: one dummy byte each
        for (int i = 0; i < 3; ++i) ReadBasicTypes(&in, &value);  // Defaults[3]
        strings.clear();
        ReadBasicArrays(&in, &strings);  // the *_default arrays
        EXPECT_EQ(strings, (std::vector<std::string>{"", "max value", "min value"}));
        in.Read<int32_t>();  // alignment_check
        ++arrays;
      }
      // Past the last field only the padding CDR2 may add to a multiple of 4 remains.
      EXPECT_LT(in.remaining(), 4u) << m.topic->type;
    }
    EXPECT_EQ(basic, 3);
    EXPECT_EQ(arrays, 4);
  }
}

TEST(Rosbag2Data, OpeningForSensorDataNamesTheTopicsThereAre) {
  HYLO_REQUIRE_DATA("rosbag2");
  try {
    OpenLog(testing::DataPath("rosbag2/sqlite3/talker"), LogReadOptions());
    FAIL() << "no /points topic, yet it opened";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no topic '/points'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("/topic (std_msgs/msg/String)"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace hylo::logs
