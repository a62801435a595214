// The bad-input suite: the built `hylo` executable on broken files, configurations and
// sensor streams. Each case is listed below with what it must give: a failure (exit code 1)
// whose one-line message contains the expected words, or a run that succeeds and counts what
// it dropped. After every failure the output folder holds only complete files (an output is
// either whole or absent: no temporary left over, no half-written trajectory or summary).
//
// The logs are made from one short simulated session (`hylo simulate`, 8 s, coarse columns):
// cut, unindexed, corrupted in the middle, or rewritten with faults in its streams.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "apps/cli_test_util.h"
#include "hylo/logs/bag_reader.h"
#include "hylo/logs/bag_writer.h"
#include "hylo/logs/log_convert.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/json.h"
#include "hylo/logs/log_reader.h"
#include "test_data.h"

namespace hylo {
namespace {

namespace fs = std::filesystem;
using testing::ReadText;

const std::string kConfig = std::string(HYLO_SOURCE_DIR) + "/config/presets/sim_vlp16.yaml";

std::string Dir() {
  static const std::string dir = testing::ScratchDir("bad_input");
  return dir;
}
std::string Path(const std::string& name) { return Dir() + "/" + name; }

std::vector<char> ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}
void WriteBytes(const std::string& path, const std::vector<char>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}
void WriteText(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

/// A configuration: the simulator's with `yaml` appended (a later key wins in the test's
/// own files only where the keys differ; the cases add sections the example lacks, or
/// replace the whole file).
std::string Config(const std::string& name, const std::string& yaml) {
  WriteText(Path(name), yaml);
  return Path(name);
}

// ---------------------------------------------------------------------------------------------
// The inputs, made once.

/// The simulated session every log case starts from: 8 s (4 s at rest, then driving).
const std::string& GoodBag() {
  static const std::string bag = [] {
    const std::string out = Path("sim");
    const int rc = testing::RunHylo(
        "simulate --out " + out + " --session a --duration 8 --column-deg 1 --no-site",
        Path("simulate.log"), Path("simulate.log"));
    EXPECT_EQ(rc, 0) << ReadText(Path("simulate.log"));
    return out + "/session_a.bag";
  }();
  return bag;
}

/// The session's messages in receive order.
std::vector<logs::LogMessage> GoodMessages() {
  logs::LogReadOptions options;
  auto reader = logs::OpenLog(GoodBag(), options);
  std::vector<logs::LogMessage> messages;
  logs::LogMessage m;
  while (reader->Next(&m)) messages.push_back(m);
  return messages;
}

/// The session cut after `fraction` of its bytes.
std::string CutBag(double fraction) {
  const std::string path = Path("cut_" + std::to_string(static_cast<int>(fraction * 100)) + ".bag");
  std::vector<char> bytes = ReadBytes(GoodBag());
  bytes.resize(static_cast<std::size_t>(bytes.size() * fraction));
  WriteBytes(path, bytes);
  return path;
}

/// The session as a killed recorder leaves it: the index (from the bag header's index_pos on)
/// gone and index_pos 0.
std::string UnindexedBag() {
  const std::string path = Path("unindexed.bag");
  std::vector<char> bytes = ReadBytes(GoodBag());
  const char kField[] = "index_pos=";
  const auto at = std::search(bytes.begin(), bytes.end(), kField, kField + sizeof(kField) - 1);
  EXPECT_NE(at, bytes.end());
  char* value = &*at + sizeof(kField) - 1;
  uint64_t index_pos = 0;
  std::memcpy(&index_pos, value, 8);
  bytes.resize(index_pos);
  std::memset(value, 0, 8);
  WriteBytes(path, bytes);
  return path;
}

/// The session with one scan's PointCloud2 width made wrong in the middle of the file: the
/// index is intact, the run fails when it reaches that scan.
std::string CorruptMidBag() {
  const std::string path = Path("corrupt_mid.bag");
  std::vector<char> bytes = ReadBytes(GoodBag());
  // frame_id "lidar" then height 1: the width follows.
  const char kPattern[] = "\x05\x00\x00\x00lidar\x01\x00\x00\x00";
  const std::size_t n = sizeof(kPattern) - 1;
  auto it = std::search(bytes.begin() + bytes.size() / 2, bytes.end(), kPattern, kPattern + n);
  EXPECT_NE(it, bytes.end());
  std::memset(&*it + n, 0x7f, 4);
  WriteBytes(path, bytes);
  return path;
}

/// What was put wrong in FaultyBag, to compare with the run's counters.
struct Faults {
  std::size_t nan_imu = 0, saturated_imu = 0, duplicate_imu = 0, stale_imu = 0, gaps = 0;
  std::size_t stale_scans = 0, empty_scans = 0, nan_points = 0;
};

/// The session rewritten with faults in both streams after the IMU start (t > 5 s).
std::string FaultyBag(Faults* faults) {
  const std::string path = Path("faulty.bag");
  const std::vector<logs::LogMessage> messages = GoodMessages();
  const int64_t t0 = messages.front().kind == logs::LogMessage::Kind::kImu
                         ? messages.front().imu.t_ns
                         : messages.front().scan.t_ns;
  logs::BagWriter writer(path);
  std::size_t imu_index = 0, scan_index = 0;
  for (const logs::LogMessage& m : messages) {
    if (m.kind == logs::LogMessage::Kind::kScan) {
      LidarScan scan = m.scan;
      const bool late = scan.t_ns - t0 > 5'000'000'000;
      if (late && scan_index % 10 == 3) {  // an empty scan
        scan.points.clear();
        ++faults->empty_scans;
      } else if (late && scan_index % 10 == 6) {  // three NaN points
        for (int i = 0; i < 3; ++i) {
          scan.points[i * 100].position_lidar.x() = std::numeric_limits<float>::quiet_NaN();
        }
        faults->nan_points += 3;
      }
      writer.WriteScan("/points", scan, logs::PointTimeConvention::kVelodyne, "lidar");
      if (late && scan_index % 10 == 8) {  // the previous scan again, received now: backwards
        LidarScan old = scan;
        old.t_ns -= 300'000'000;
        old.end_t_ns -= 300'000'000;
        writer.WriteCloud("/points", logs::EncodePointCloud2(old, logs::PointTimeConvention::kVelodyne),
                          scan.end_t_ns);
        ++faults->stale_scans;
      }
      ++scan_index;
      continue;
    }
    ImuSample imu = m.imu;
    const int64_t t = imu.t_ns - t0;
    ++imu_index;
    if (t > 5'500'000'000 && t < 5'800'000'000) {  // a 0.3 s dropout
      continue;
    }
    if (t == 5'800'000'000) ++faults->gaps;
    const bool faulty = t > 5'000'000'000 && (t < 5'400'000'000 || t > 6'000'000'000);
    if (faulty && imu_index % 97 == 0) {
      imu.gyro_imu.z() = std::numeric_limits<double>::quiet_NaN();
      ++faults->nan_imu;
    } else if (faulty && imu_index % 89 == 0) {
      imu.accel_imu.x() = 200.0;  // beyond the default 16 g range
      ++faults->saturated_imu;
    }
    writer.WriteImu("/imu", imu, "imu");
    if (faulty && imu_index % 83 == 0) {
      writer.WriteImu("/imu", m.imu, "imu");  // the same stamp twice
      ++faults->duplicate_imu;
    }
    if (faulty && imu_index % 79 == 0) {  // a sample from 0.5 s ago, received now
      ImuSample old = m.imu;
      old.t_ns -= 501'000'000;
      writer.WriteImu("/imu", old, "imu", m.imu.t_ns);
      ++faults->stale_imu;
    }
  }
  writer.Close();
  return path;
}

/// The session as a ROS 2 recording (a rosbag2 directory) in `format`.
const std::string& Ros2Bag(logs::LogFormat format) {
  static std::map<logs::LogFormat, std::string> made;
  std::string& path = made[format];
  if (path.empty()) {
    path = Path("ros2_" + logs::ToString(format));
    logs::ConvertLog(GoodBag(), path, format, logs::LogReadOptions());
  }
  return path;
}

/// A copy of the MCAP recording with `from` replaced by `to` in its metadata.yaml (nothing
/// replaced when `from` is empty), or without metadata.yaml when `to` is "<none>".
std::string Ros2Variant(const std::string& name, const std::string& from, const std::string& to) {
  const std::string bag = Path(name);
  fs::create_directories(bag);
  const std::string source = Ros2Bag(logs::LogFormat::kMcap);
  const std::string storage = fs::path(source).filename().string() + "_0.mcap";
  fs::copy_file(source + "/" + storage, bag + "/" + storage, fs::copy_options::overwrite_existing);
  if (to == "<none>") return bag;
  std::string yaml = ReadText(source + "/metadata.yaml");
  if (!from.empty()) yaml.replace(yaml.find(from), from.size(), to);
  WriteText(bag + "/metadata.yaml", yaml);
  return bag;
}

/// A storage file of `format` cut after `fraction` of its bytes, given directly.
std::string CutRos2(logs::LogFormat format, double fraction) {
  const std::string source = Ros2Bag(format);
  const std::string ext = format == logs::LogFormat::kSqlite3 ? ".db3" : ".mcap";
  const std::string path = Path("cut_" + logs::ToString(format) + ext);
  std::vector<char> bytes =
      ReadBytes(source + "/" + fs::path(source).filename().string() + "_0" + ext);
  bytes.resize(static_cast<std::size_t>(bytes.size() * fraction));
  WriteBytes(path, bytes);
  return path;
}

// ---------------------------------------------------------------------------------------------
// Checks.

/// Every file in `dir` (recursively) is complete: no temporary, JSON parses, YAML
/// configurations load back, clouds and trajectories read.
void ExpectOnlyCompleteFiles(const std::string& dir) {
  if (!fs::exists(dir)) return;
  for (const auto& entry : fs::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const std::string path = entry.path().string();
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << "temporary left over: " << path;
    const std::string ext = entry.path().extension().string();
    try {
      if (ext == ".json") io::ReadJsonFile(path);
      if (ext == ".pcd" || ext == ".ply" || ext == ".las") io::ReadCloud(path);
      if (ext == ".yaml" && name == "config.yaml") {
        EXPECT_NE(ReadText(path).find("ground:"), std::string::npos) << "cut short: " << path;
      }
    } catch (const std::exception& e) {
      ADD_FAILURE() << "incomplete output " << path << ": " << e.what();
    }
  }
}

struct Case {
  std::string name;
  std::function<std::string()> args;  // the command line (may make files)
  int exit_code;                      // 1: refused with a message; 0: runs and warns
  std::vector<std::string> expected;  // words the output must contain
};

std::string MapArgs(const std::string& log, const std::string& config, const std::string& out) {
  return "map --log " + log + " --config " + config + " --out " + Path(out);
}

std::vector<Case> Cases() {
  const std::string pcd = Path("cloud.pcd"), ply = Path("cloud.ply");
  const auto cloud = [=] {
    io::CloudFile c;
    for (int i = 0; i < 2000; ++i) c.positions.emplace_back(0.1 * (i % 50), 0.1 * (i / 50), 0.0);
    io::WriteCloud(pcd, c, io::CloudEncoding::kBinary);
    io::WriteCloud(ply, c);
  };
  const auto truncated = [](const std::string& from, const std::string& to, double keep) {
    std::vector<char> bytes = ReadBytes(from);
    bytes.resize(static_cast<std::size_t>(bytes.size() * keep));
    WriteBytes(to, bytes);
    return to;
  };
  const std::string good_tum = Path("good.tum");
  WriteText(good_tum, "1.0 0 0 0 0 0 0 1\n2.0 1 0 0 0 0 0 1\n3.0 2 0 0 0 0 0 1\n");
  const std::string sim = kConfig;
  return {
      // Logs.
      {"log file missing",
       [=] { return MapArgs(Path("absent.bag"), sim, "o1"); },
       1,
       {"absent.bag", "does not exist"}},
      {"log not a bag",
       [=] {
         WriteText(Path("text.bag"), "hello, not a bag\n");
         return MapArgs(Path("text.bag"), sim, "o2");
       },
       1,
       {"text.bag", "not a ROS1 bag"}},
      {"bag cut before its first scan",
       [=] { return MapArgs(truncated(GoodBag(), Path("cut_early.bag"), 0.0005), sim, "o3"); },
       1,
       {"cut_early.bag", "no topic '/points'"}},
      {"bag cut at 60 %: info",
       [=] { return "info " + CutBag(0.6); },
       0,
       {"damaged:", "recovered", "bytes unreadable"}},
      {"bag cut at 60 %: map",
       [=] { return MapArgs(CutBag(0.6), sim, "o4"); },
       0,
       {"warning:", "index unreadable", "recovered"}},
      {"bag without index (recording killed): info",
       [=] { return "info " + UnindexedBag(); },
       0,
       {"damaged:", "no index"}},
      {"bag without index (recording killed): map",
       [=] { return MapArgs(UnindexedBag(), sim, "o5"); },
       0,
       {"warning:", "no index"}},
      {"bag corrupt in the middle",
       [=] { return MapArgs(CorruptMidBag(), sim, "o6"); },
       1,
       {"corrupt_mid.bag", "topic '/points'"}},
      {"lidar topic missing",
       [=] {
         return MapArgs(GoodBag(), Config("c_topic.yaml", "lidar: {topic: /velodyne_points}\n"),
                        "o7");
       },
       1,
       {"no topic '/velodyne_points'", "/points (sensor_msgs/PointCloud2)"}},
      {"imu topic of the wrong type",
       [=] {
         return MapArgs(GoodBag(), Config("c_imu_type.yaml", "imu: {topic: /points}\n"), "o8");
       },
       1,
       {"'/points' has type sensor_msgs/PointCloud2, expected sensor_msgs/Imu"}},
      // ROS 2 recordings.
      {"rosbag2 without metadata.yaml (recorder killed): map",
       [=] { return MapArgs(Ros2Variant("r2_no_metadata", "", "<none>"), sim, "o22"); },
       0,
       {"warning:", "no metadata.yaml (recording interrupted?)"}},
      {"rosbag2 metadata.yaml naming a missing storage file",
       [=] { return MapArgs(Ros2Variant("r2_missing", "_0.mcap", "_1.mcap"), sim, "o23"); },
       1,
       {"r2_missing", "storage file 'ros2_mcap_1.mcap' (listed in metadata.yaml) is missing"}},
      {"rosbag2 metadata.yaml malformed",
       [=] {
         return MapArgs(Ros2Variant("r2_malformed", "version: 5", "version: [5"), sim, "o24");
       },
       1,
       {"r2_malformed/metadata.yaml", "malformed YAML"}},
      {"rosbag2 with an unknown storage",
       [=] {
         return MapArgs(Ros2Variant("r2_storage", "storage_identifier: mcap",
                                    "storage_identifier: rosbag_v2"),
                        sim, "o25");
       },
       1,
       {"r2_storage", "storage 'rosbag_v2' is not supported (hylo reads sqlite3 and mcap)"}},
      {"rosbag2 with an unsupported compression",
       [=] {
         return MapArgs(
             Ros2Variant("r2_lz4", "compression_format: \"\"", "compression_format: lz4"), sim,
             "o26");
       },
       1,
       {"r2_lz4", "compression 'lz4' is not supported"}},
      {"rosbag2 imu topic of the wrong type",
       [=] {
         return MapArgs(Ros2Bag(logs::LogFormat::kMcapZstd),
                        Config("c_imu_type2.yaml", "imu: {topic: /points}\n"), "o27");
       },
       1,
       {"'/points' has type sensor_msgs/msg/PointCloud2, expected sensor_msgs/msg/Imu"}},
      {"MCAP cut at 60 % (no footer, last chunk cut): info",
       [=] { return "info " + CutRos2(logs::LogFormat::kMcapZstd, 0.6); },
       0,
       {"damaged:", "no footer (recording interrupted?)", "recovered"}},
      {"MCAP cut at 60 % (no footer, last chunk cut): map",
       [=] { return MapArgs(CutRos2(logs::LogFormat::kMcap, 0.6), sim, "o28"); },
       0,
       {"warning:", "no footer", "recovered", "the last chunk is cut"}},
      {"sqlite3 database cut at 60 %: map",
       [=] { return MapArgs(CutRos2(logs::LogFormat::kSqlite3, 0.6), sim, "o29"); },
       0,
       {"warning:", "database cut short", "recovered"}},
      // Configuration files.
      {"config missing",
       [=] { return MapArgs(GoodBag(), Path("absent.yaml"), "o9"); },
       1,
       {"cannot read configuration file", "absent.yaml"}},
      {"config malformed YAML",
       [=] {
         return MapArgs(GoodBag(), Config("c_malformed.yaml", "imu: {rate_hz: [200\n"), "o10");
       },
       1,
       {"c_malformed.yaml", "malformed YAML"}},
      {"config unknown key",
       [=] { return MapArgs(GoodBag(), Config("c_unknown.yaml", "imu: {rate: 200}\n"), "o11"); },
       1,
       {"imu.rate"}},
      {"config wrong type",
       [=] { return MapArgs(GoodBag(), Config("c_type.yaml", "imu: {rate_hz: fast}\n"), "o12"); },
       1,
       {"imu.rate_hz", "fast"}},
      {"config NaN value",
       [=] {
         return MapArgs(GoodBag(), Config("c_nan.yaml", "preprocess: {scan_voxel_m: .nan}\n"),
                        "o13");
       },
       1,
       {"scan_voxel_m"}},
      {"config clock offset out of range",
       [=] {
         return MapArgs(GoodBag(), Config("c_offset.yaml", "lidar: {time_offset_s: 5}\n"), "o14");
       },
       1,
       {"lidar.time_offset_s = 5", "another time base"}},
      {"config accel range below gravity",
       [=] {
         return MapArgs(GoodBag(), Config("c_range.yaml", "imu: {accel_range_mps2: 5}\n"), "o15");
       },
       1,
       {"imu.accel_range_mps2 = 5"}},
      {"config unknown back-end",
       [=] { return MapArgs(GoodBag(), Config("c_backend.yaml", "backend: magic\n"), "o16"); },
       1,
       {"backend", "magic"}},
      {"config moved key",
       [=] {
         return MapArgs(GoodBag(), Config("c_moved.yaml", "ieskf: {lidar_noise_m: 0.01}\n"), "o17");
       },
       1,
       {"lidar_update"}},
      // Outputs.
      {"output folder under a file",
       [=] {
         WriteText(Path("a_file"), "x");
         return "map --log " + GoodBag() + " --config " + sim + " --out " + Path("a_file/out");
       },
       1,
       {"a_file"}},
      // Clouds.
      {"PCD truncated",
       [=] {
         cloud();
         return "craft --in " + truncated(pcd, Path("cut.pcd"), 0.5) + " --out " + Path("o.pcd");
       },
       1,
       {"cut.pcd"}},
      {"PLY truncated",
       [=] {
         cloud();
         return "craft --in " + truncated(ply, Path("cut.ply"), 0.5) + " --out " + Path("o.pcd");
       },
       1,
       {"cut.ply"}},
      {"PCD header only",
       [=] {
         cloud();
         return "ground --in " + truncated(pcd, Path("header.pcd"), 0.0) + " --out-ground " +
                Path("g.pcd") + " --out-objects " + Path("ob.pcd");
       },
       1,
       {"header.pcd"}},
      {"PCD with only NaN points",
       [=] {
         WriteText(Path("nan.pcd"),
                   "VERSION .7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\n"
                   "HEIGHT 1\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 2\nDATA ascii\nnan nan nan\n"
                   "nan 1 2\n");
         return "craft --in " + Path("nan.pcd") + " --out " + Path("o2.pcd");
       },
       1,
       {"nan.pcd"}},
      {"LAS truncated",
       [=] {
         cloud();
         io::WriteCloud(Path("cloud.las"), io::ReadCloud(pcd));
         return "craft --in " + truncated(Path("cloud.las"), Path("cut.las"), 0.5) + " --out " +
                Path("o.las");
       },
       1,
       {"cut.las", "truncated: 2000 points of 30 bytes"}},
      {"LAS header with a broken VLR count",
       [=] {
         cloud();
         io::WriteCloud(Path("cloud.las"), io::ReadCloud(pcd));
         std::vector<char> bytes = ReadBytes(Path("cloud.las"));
         bytes[100] = 1;  // one VLR announced, none between the header and the points
         WriteBytes(Path("bad_vlr.las"), bytes);
         return "ground --in " + Path("bad_vlr.las") + " --out-ground " + Path("g.las") +
                " --out-objects " + Path("ob.las");
       },
       1,
       {"bad_vlr.las", "VLR 1 of 1 does not fit"}},
      {"LAZ prior map",
       [=] {
         WriteText(Path("map.laz"), "LASF");
         return "localize --log " + GoodBag() + " --map " + Path("map.laz") + " --config " + sim +
                " --guess '0 0 0 0 0 0' --out " + Path("o22");
       },
       1,
       {"map.laz", "LAZ (compressed LAS) is not supported", "laszip -i"}},
      {"LAS output cannot hold a label",
       [=] {
         io::CloudFile c;  // flat ground and a 1 m block 3 m up, every point labelled 1000
         for (int i = 0; i < 2100; ++i) {
           const double up = i < 2000 ? 0.0 : 3.0;
           const int k = i < 2000 ? i : i - 2000;
           c.positions.emplace_back(0.1 * (k % 50) + up, 0.1 * (k / 50) + up, up);
         }
         c.labels.assign(c.positions.size(), 1000);
         io::WriteCloud(Path("labelled.pcd"), c);
         return "ground --in " + Path("labelled.pcd") + " --out-ground " + Path("g2.las") +
                " --out-objects " + Path("objects.las");
       },
       1,
       {"objects.las", "label 1000, a LAS classification is 0-255"}},
      {"cloud file missing",
       [=] { return "craft --in " + Path("absent.pcd") + " --out x.pcd"; },
       1,
       {"absent.pcd"}},
      {"prior map empty",
       [=] {
         io::WriteCloud(Path("empty.pcd"), io::CloudFile());
         return "localize --log " + GoodBag() + " --map " + Path("empty.pcd") + " --config " + sim +
                " --guess '0 0 0 0 0 0' --out " + Path("o18");
       },
       1,
       {"empty.pcd", "no point"}},
      {"guess malformed",
       [=] {
         cloud();
         return "localize --log " + GoodBag() + " --map " + pcd + " --config " + sim +
                " --guess '1 2 3 4 5' --out " + Path("o19");
       },
       1,
       {"guess"}},
      // Trajectories.
      {"trajectory line malformed",
       [=] {
         WriteText(Path("bad.tum"), "1.0 0 0 0 0 0 0 1\n2.0 zero 0 0 0 0 0 1\n");
         return "eval ate --est " + Path("bad.tum") + " --gt " + good_tum;
       },
       1,
       {"bad.tum", "2"}},
      {"trajectory empty",
       [=] {
         WriteText(Path("empty.tum"), "");
         return "eval ate --est " + Path("empty.tum") + " --gt " + good_tum;
       },
       1,
       {"empty.tum"}},
      {"scan folder without scans",
       [=] {
         fs::create_directories(Path("no_scans"));
         return "info " + Path("no_scans");
       },
       1,
       {"no_scans"}},
      {"ground cloud missing for traversability",
       [=] {
         return "traversability --ground " + Path("absent_ground.pcd") + " --out " + Path("o21");
       },
       1,
       {"absent_ground.pcd"}},
      // Command line.
      {"simulate clock offset out of range",
       [=] { return "simulate --out " + Path("o20") + " --lidar-time-offset 2"; },
       109,
       {"--lidar-time-offset"}},
  };
}

TEST(BadInput, EveryCaseGivesItsClearErrorAndWritesNothingHalf) {
  const std::vector<Case> cases = Cases();
  std::size_t n = 0;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string log = Path("case_" + std::to_string(n++) + ".log");
    const std::string args = c.args();
    const int rc = testing::RunHylo(args, log, log);
    const std::string output = ReadText(log);
    std::printf(
        "[%2zu] %-45s exit %d: %s", n, c.name.c_str(), rc,
        output.empty() ? "\n" : output.substr(output.rfind('\n', output.size() - 2) + 1).c_str());
    if (c.exit_code == 109) {
      EXPECT_NE(rc, 0) << output;  // CLI11 reports its own exit codes for bad flags
    } else {
      EXPECT_EQ(rc, c.exit_code) << args << "\n" << output;
    }
    for (const std::string& words : c.expected) {
      EXPECT_NE(output.find(words), std::string::npos) << "'" << words << "' not in: " << output;
    }
    if (c.exit_code == 1) {
      EXPECT_NE(output.find("error:"), std::string::npos) << output;
    }
  }
  EXPECT_GE(cases.size(), 39u);
  for (const auto& entry : fs::directory_iterator(Dir())) {
    if (entry.is_directory() && entry.path().filename().string()[0] == 'o') {
      ExpectOnlyCompleteFiles(entry.path().string());
    }
  }
}

TEST(BadInput, AFailureMidRunLeavesOnlyCompleteFiles) {
  const std::string out = Path("mid_run");
  const std::string log = Path("mid_run.log");
  ASSERT_EQ(testing::RunHylo(MapArgs(CorruptMidBag(), kConfig, "mid_run"), log, log), 1)
      << ReadText(log);
  EXPECT_TRUE(fs::exists(out + "/config.yaml"));  // written first, whole
  for (const char* name : {"trajectory.tum", "summary.json", "map.pcd", "odometry.csv"}) {
    EXPECT_FALSE(fs::exists(out + "/" + name)) << name;
  }
  ExpectOnlyCompleteFiles(out);
}

TEST(BadInput, FaultsInTheStreamsAreCountedAndTheRunCarriesOn) {
  Faults f;
  const std::string bag = FaultyBag(&f);
  const std::string log = Path("faulty.log");
  ASSERT_EQ(testing::RunHylo(MapArgs(bag, kConfig, "faulty") + " --json " + Path("faulty.json"),
                             log, log),
            0)
      << ReadText(log);
  const io::Json s = io::ReadJsonFile(Path("faulty") + "/summary.json");
  const auto at = [&](const std::string& key) { return io::NumberAt(s, key); };
  std::printf(
      "injected: %zu NaN IMU, %zu clipped, %zu duplicated, %zu stale IMU, %zu gap, "
      "%zu stale scans, %zu empty scans, %zu NaN points\n%s",
      f.nan_imu, f.saturated_imu, f.duplicate_imu, f.stale_imu, f.gaps, f.stale_scans,
      f.empty_scans, f.nan_points, ReadText(log).c_str());
  // Each is one case of the suite: a counted drop.
  EXPECT_EQ(at("log_read.dropped_non_finite_imu"), f.nan_imu);       // NaN IMU values
  EXPECT_EQ(at("counters.queue.imu_saturated"), f.saturated_imu);    // clipped IMU values
  EXPECT_EQ(at("counters.queue.imu_duplicates"), f.duplicate_imu);   // duplicated stamps
  EXPECT_EQ(at("counters.queue.imu_stale"), f.stale_imu);            // IMU time going backwards
  EXPECT_EQ(at("counters.queue.imu_gaps"), f.gaps);                  // an IMU dropout
  EXPECT_NEAR(at("counters.queue.longest_imu_gap_s"), 0.3, 0.0051);  // ... of 0.3 s
  EXPECT_EQ(at("counters.queue.scan_stale"), f.stale_scans);         // scans going backwards
  EXPECT_EQ(at("log_read.empty_scans"), f.empty_scans);              // empty scans
  EXPECT_GE(at("counters.scans_too_small"), f.empty_scans);
  EXPECT_EQ(at("log_read.dropped_non_finite_points"), f.nan_points);  // NaN points
  EXPECT_GT(f.nan_imu * f.saturated_imu * f.duplicate_imu * f.stale_imu, 0u);
  EXPECT_GT(f.stale_scans * f.empty_scans, 0u);
  EXPECT_NE(ReadText(log).find("warning:"), std::string::npos);
  EXPECT_NE(ReadText(log).find("gap"), std::string::npos);
}

}  // namespace
}  // namespace hylo
