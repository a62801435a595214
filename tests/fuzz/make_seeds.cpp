// Writes the fuzz targets' seed inputs with the project's own writers (and, where there is no
// writer, in the formats' documented grammar), one folder per target:
//   hylo_fuzz_make_seeds OUT_DIR      ->  OUT_DIR/<target>/<seed>
// Small on purpose (a few points each): libFuzzer mutates headers and layouts, not bulk data.

#include <ros/serialization.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <vector>

#include "cdr_messages.h"
#include "hylo/config/run_config.h"
#include "hylo/logs/bag_writer.h"
#include "hylo/logs/rosbag2_writer.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/json.h"
#include "hylo/logs/pointcloud2.h"
#include "hylo/logs/ros_bridge.h"
#include "hylo/io/trajectory_io.h"

namespace {

namespace fs = std::filesystem;
namespace io = hylo::io;
namespace logs = hylo::logs;
using logs::PointTimeConvention;

fs::path g_out;

void Emit(const std::string& target, const std::string& name, const std::string& bytes) {
  fs::create_directories(g_out / target);
  std::ofstream(g_out / target / name, std::ios::binary) << bytes;
}

std::string FileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string Scratch(const std::string& name) { return (g_out / ("tmp_" + name)).string(); }

std::string Take(const std::string& path) {
  std::string bytes = FileBytes(path);
  fs::remove(path);
  return bytes;
}

template <class Message>
std::string Serialized(const Message& msg) {
  std::vector<uint8_t> bytes(ros::serialization::serializationLength(msg));
  ros::serialization::OStream out(bytes.data(), static_cast<uint32_t>(bytes.size()));
  ros::serialization::serialize(out, msg);
  return std::string(bytes.begin(), bytes.end());
}

// --- bag messages ---------------------------------------------------------------------------

hylo::LidarScan SmallScan() {
  hylo::LidarScan scan;
  scan.t_ns = 1'700'000'000'123'456'789;
  scan.frame_id = "lidar";
  for (int i = 0; i < 6; ++i) {
    hylo::ScanPoint p;
    p.position_lidar = Eigen::Vector3f(1.0f + i, -2.0f * i, 0.5f);
    p.intensity = 10.0f * i;
    p.ring = static_cast<uint16_t>(i % 4);
    p.offset_ns = 10'000'000 * i;
    scan.points.push_back(p);
  }
  scan.points[3].position_lidar.x() = std::numeric_limits<float>::quiet_NaN();
  scan.end_t_ns = scan.t_ns + scan.points.back().offset_ns;
  return scan;
}

// The same cloud with every field byte-swapped and is_bigendian set.
logs::PointCloud2Message BigEndian(logs::PointCloud2Message cloud) {
  for (uint32_t i = 0; i < cloud.width * cloud.height; ++i) {
    for (const logs::PointFieldInfo& f : cloud.fields) {
      uint8_t* at = cloud.data.data() + i * cloud.point_step + f.offset;
      std::reverse(at, at + logs::PointFieldSize(f.datatype));
    }
  }
  cloud.is_bigendian = true;
  return cloud;
}

// Two rows with 4 padding bytes after each (row_step > width * point_step).
logs::PointCloud2Message Organized(const logs::PointCloud2Message& flat) {
  logs::PointCloud2Message cloud = flat;
  cloud.height = 2;
  cloud.width = flat.width / 2;
  cloud.row_step = cloud.width * cloud.point_step + 4;
  cloud.data.assign(std::size_t{cloud.row_step} * 2, 0);
  for (uint32_t r = 0; r < 2; ++r) {
    std::memcpy(cloud.data.data() + r * cloud.row_step,
                flat.data.data() + r * cloud.width * cloud.point_step,
                cloud.width * cloud.point_step);
  }
  return cloud;
}

void PointCloud2Seeds() {
  const PointTimeConvention layouts[] = {
      PointTimeConvention::kVelodyne,  PointTimeConvention::kOuster, PointTimeConvention::kHesai,
      PointTimeConvention::kRobosense, PointTimeConvention::kLivox,  PointTimeConvention::kNone};
  // The target's first byte: 0 = auto, then the conventions in this order.
  for (std::size_t k = 0; k < std::size(layouts); ++k) {
    const logs::PointCloud2Message cloud = logs::EncodePointCloud2(SmallScan(), layouts[k]);
    const std::string name = logs::ToString(layouts[k]);
    const std::string auto_byte(1, '\0');
    const std::string own_byte(1, static_cast<char>(k + 1));
    Emit("bag_pointcloud2", name + "_auto",
         auto_byte + Serialized(logs::ros_bridge::ToRos(logs::PointCloud2Message(cloud))));
    Emit("bag_pointcloud2", name,
         own_byte + Serialized(logs::ros_bridge::ToRos(logs::PointCloud2Message(cloud))));
    Emit("bag_pointcloud2", name + "_big_endian",
         auto_byte + Serialized(logs::ros_bridge::ToRos(BigEndian(cloud))));
    Emit("bag_pointcloud2", name + "_organized",
         auto_byte + Serialized(logs::ros_bridge::ToRos(Organized(cloud))));
  }
}

void ImuSeeds() {
  sensor_msgs::Imu msg;
  msg.header.stamp.fromNSec(1'700'000'000'000'000'000);
  msg.header.frame_id = "imu";
  msg.orientation_covariance[0] = -1.0;
  msg.linear_acceleration.z = 9.81;
  msg.angular_velocity.x = 0.01;
  Emit("bag_imu", "at_rest", Serialized(msg));
  msg.linear_acceleration.x = std::numeric_limits<double>::quiet_NaN();
  Emit("bag_imu", "nan_accel", Serialized(msg));
}

// --- whole bags (read record by record) ----------------------------------------------------

constexpr std::size_t kBagMagicBytes = 13;  // "#ROSBAG V2.0\n"

uint32_t U32At(const std::string& bytes, std::size_t at) {
  uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = v << 8 | static_cast<uint8_t>(bytes[at + i]);
  return v;
}

// rosbag pads its bag header record to 4 kB of spaces, which the walker skips whole: the
// seeds drop the padding so that libFuzzer mutates records, not spaces.
std::string WithoutHeaderPadding(const std::string& bag) {
  const std::size_t data_len_at = kBagMagicBytes + 4 + U32At(bag, kBagMagicBytes);
  return bag.substr(0, data_len_at) + std::string(4, '\0') +
         bag.substr(data_len_at + 4 + U32At(bag, data_len_at));
}

// Three IMU samples, a scan (with a NaN point), one more sample: one chunk.
std::string SmallBag(logs::BagCompression compression) {
  const std::string path = Scratch("b.bag");
  {
    logs::BagWriter writer(path, compression);
    const hylo::LidarScan scan = SmallScan();
    for (int i = 0; i < 4; ++i) {
      hylo::ImuSample imu;
      imu.t_ns = scan.t_ns + i * 40'000'000LL;
      imu.accel_imu = Eigen::Vector3d(0.01 * i, -0.02, 9.81);
      imu.gyro_imu = Eigen::Vector3d(0.001, 0.002 * i, -0.003);
      writer.WriteImu("/imu", imu, "imu");
      if (i == 2) writer.WriteScan("/points", scan, PointTimeConvention::kVelodyne, "lidar");
    }
  }
  return Take(path);
}

void BagRecordSeeds() {
  const std::string none = SmallBag(logs::BagCompression::kNone);
  Emit("bag_records", "none_padded", none);
  const std::string compact = WithoutHeaderPadding(none);
  Emit("bag_records", "none", compact);
  Emit("bag_records", "bz2", WithoutHeaderPadding(SmallBag(logs::BagCompression::kBz2)));
  const std::string lz4 = WithoutHeaderPadding(SmallBag(logs::BagCompression::kLz4));
  Emit("bag_records", "lz4", lz4);
  // Cut short: inside the chunk (uncompressed: inside the scan; lz4: inside its blocks), and
  // right after the chunk (the index lost, every message whole).
  Emit("bag_records", "none_cut", compact.substr(0, compact.size() * 6 / 10));
  Emit("bag_records", "lz4_cut", lz4.substr(0, lz4.size() * 6 / 10));
  const std::size_t index_pos = none.find("index_pos=");
  if (index_pos != std::string::npos) {
    const std::size_t index_at = U32At(none, index_pos + 10);  // u64; small bags fit in u32
    Emit("bag_records", "no_index", none.substr(0, index_at));
  }
}

// --- ROS 2 recordings -----------------------------------------------------------------------

// The small recording of SmallBag as a single MCAP file (chunks of 1 KiB: several).
std::string SmallMcap(const std::string& compression) {
  const std::string path = Scratch("r.mcap");
  {
    hylo::logs::Rosbag2WriterOptions options;
    options.mcap_compression = compression;
    options.mcap_chunk_bytes = 1024;
    hylo::logs::Rosbag2Writer writer(path, options);
    const hylo::LidarScan scan = SmallScan();
    for (int i = 0; i < 4; ++i) {
      hylo::ImuSample imu;
      imu.t_ns = scan.t_ns + i * 40'000'000LL;
      imu.accel_imu = Eigen::Vector3d(0.01 * i, -0.02, 9.81);
      imu.gyro_imu = Eigen::Vector3d(0.001, 0.002 * i, -0.003);
      writer.WriteImu("/imu", imu, "imu");
      if (i == 2) writer.WriteScan("/points", scan, PointTimeConvention::kVelodyne, "lidar");
    }
    writer.Close();
  }
  return Take(path);
}

void McapSeeds() {
  const std::string stored = SmallMcap("");
  Emit("mcap_records", "stored", stored);
  Emit("mcap_records", "zstd", SmallMcap("zstd"));
  const std::string lz4 = SmallMcap("lz4");
  Emit("mcap_records", "lz4", lz4);
  // Cut short, as a killed recorder leaves it: inside a chunk, and before the summary.
  Emit("mcap_records", "stored_cut", stored.substr(0, stored.size() * 6 / 10));
  Emit("mcap_records", "lz4_cut", lz4.substr(0, lz4.size() * 6 / 10));
  const std::size_t data_end = stored.rfind(std::string("\x0f\x04\0\0\0\0\0\0\0", 9));
  if (data_end != std::string::npos) {
    Emit("mcap_records", "no_summary", stored.substr(0, data_end));
  }
}

void CdrSeeds() {
  namespace detail = hylo::logs::detail;
  const auto bytes = [](const std::vector<uint8_t>& v) { return std::string(v.begin(), v.end()); };
  const PointTimeConvention layouts[] = {PointTimeConvention::kVelodyne,
                                         PointTimeConvention::kOuster, PointTimeConvention::kLivox,
                                         PointTimeConvention::kNone};
  // The target's first byte: 0 PointCloud2, 1 Imu, 2 Livox CustomMsg.
  for (const PointTimeConvention layout : layouts) {
    Emit("cdr_messages", "cloud_" + logs::ToString(layout),
         std::string(1, '\0') +
             bytes(detail::EncodeCdrPointCloud2(logs::EncodePointCloud2(SmallScan(), layout))));
  }
  hylo::ImuSample imu;
  imu.t_ns = 1'700'000'000'000'000'000;
  imu.accel_imu = Eigen::Vector3d(0.1, 0.2, 9.81);
  Emit("cdr_messages", "imu", std::string(1, '\1') + bytes(detail::EncodeCdrImu(imu, "imu")));
  std::vector<detail::LivoxCustomPoint> points(4);
  for (int i = 0; i < 4; ++i) {
    points[i].offset_time_ns = 1000 * i;
    points[i].x = 1.0f + i;
    points[i].line = static_cast<uint8_t>(i);
  }
  Emit("cdr_messages", "livox",
       std::string(1, '\2') +
           bytes(detail::EncodeCdrLivoxCustom(imu.t_ns, "livox", 1700000000000000000ull, points)));
}

void MetadataSeeds() {
  const std::string dir = Scratch("bag");
  {
    hylo::logs::Rosbag2Writer writer(dir, hylo::logs::Rosbag2WriterOptions());
    writer.WriteImu("/imu", hylo::ImuSample(), "imu");
    writer.Close();
  }
  Emit("rosbag2_metadata", "version_5", FileBytes(fs::path(dir) / "metadata.yaml"));
  fs::remove_all(dir);
  // What older recorders wrote: version 4 without the per-file list, flow style.
  Emit("rosbag2_metadata", "version_4",
       "rosbag2_bagfile_information:\n  version: 4\n  storage_identifier: sqlite3\n"
       "  relative_file_paths: [a_0.db3, a_1.db3]\n  duration: {nanoseconds: 411}\n"
       "  starting_time: {nanoseconds_since_epoch: 2623}\n  message_count: 2\n"
       "  topics_with_message_count:\n    - topic_metadata: {name: /a, type: std_msgs/msg/String,"
       " serialization_format: cdr, offered_qos_profiles: ''}\n      message_count: 2\n"
       "  compression_format: zstd\n  compression_mode: message\n");
}

// --- point cloud files ----------------------------------------------------------------------

io::CloudFile SmallCloud(bool utm) {
  io::CloudFile cloud;
  const Eigen::Vector3d origin =
      utm ? Eigen::Vector3d(500123.25, 5432109.5, 210.0) : Eigen::Vector3d::Zero();
  for (int i = 0; i < 5; ++i) {
    cloud.positions.push_back(origin + Eigen::Vector3d(0.1 * i, -0.2 * i, 0.05 * i * i));
    cloud.intensity.push_back(3.0f * i);
    cloud.normals.emplace_back(0.0f, 0.0f, 1.0f);
    cloud.labels.push_back(i % 2);
  }
  return cloud;
}

// Little-endian field `value` at byte `at` of `bytes`.
template <typename T>
void PutAt(std::string* bytes, std::size_t at, T value) {
  std::memcpy(&(*bytes)[at], &value, sizeof(T));
}

// LAS: the writer's files (1.4, format 6, with and without the normals' Extra Bytes VLR, UTM,
// empty), and what it never writes, from the specification's layout: a 1.2 format 3 file with
// a VLR and undescribed extra bytes, and a 1.4 file with an EVLR after its points.
void LasSeeds() {
  for (const bool utm : {false, true}) {
    io::WriteCloud(Scratch("c.las"), SmallCloud(utm));
    Emit("las", utm ? "normals_utm" : "normals", Take(Scratch("c.las")));
  }
  io::CloudFile bare = SmallCloud(true);
  bare.normals.clear();
  io::WriteCloud(Scratch("c.las"), bare);
  const std::string format6 = Take(Scratch("c.las"));
  Emit("las", "format6", format6);
  io::WriteCloud(Scratch("c.las"), io::CloudFile());
  Emit("las", "empty", Take(Scratch("c.las")));
  // 1.2: 227-byte header, one 6-byte VLR, two 34 + 2 byte records (format 3 plus 2 extra).
  std::string v12(227, '\0');
  v12.replace(0, 4, "LASF");
  v12[24] = 1;
  v12[25] = 2;
  PutAt<uint16_t>(&v12, 94, 227);
  PutAt<uint32_t>(&v12, 96, 227 + 54 + 6);
  PutAt<uint32_t>(&v12, 100, 1);
  v12[104] = 3;
  PutAt<uint16_t>(&v12, 105, 36);
  PutAt<uint32_t>(&v12, 107, 2);
  for (int k = 0; k < 3; ++k) PutAt<double>(&v12, 131 + 8 * k, 0.01);
  std::string vlr(54 + 6, '\0');
  vlr.replace(2, 4, "seed");
  PutAt<uint16_t>(&vlr, 20, 6);
  v12 += vlr;
  for (int i = 0; i < 2; ++i) {
    std::string record(36, '\0');
    PutAt<int32_t>(&record, 0, 100 * i - 7);
    PutAt<uint16_t>(&record, 12, 300);
    record[15] = static_cast<char>(2 | 0x80);  // ground, withheld
    v12 += record;
  }
  Emit("las", "v12_format3_vlr_extra", v12);
  // 1.4 with one EVLR (60-byte header, 4 bytes) after the points.
  std::string evlr = format6;
  PutAt<uint64_t>(&evlr, 235, evlr.size());
  PutAt<uint32_t>(&evlr, 243, 1);
  std::string record(60 + 4, '\0');
  record.replace(2, 4, "seed");
  PutAt<uint64_t>(&record, 20, 4);
  Emit("las", "v14_evlr", evlr + record);
}

void CloudSeeds() {
  const std::pair<io::CloudEncoding, const char*> pcd_encodings[] = {
      {io::CloudEncoding::kAscii, "ascii"},
      {io::CloudEncoding::kBinary, "binary"},
      {io::CloudEncoding::kBinaryCompressed, "binary_compressed"}};
  for (const bool utm : {false, true}) {
    const std::string suffix = utm ? "_utm" : "";
    for (const auto& [encoding, name] : pcd_encodings) {
      io::WriteCloud(Scratch("c.pcd"), SmallCloud(utm), encoding);
      Emit("pcd", name + suffix, Take(Scratch("c.pcd")));
      if (encoding == io::CloudEncoding::kBinaryCompressed) continue;
      io::WriteCloud(Scratch("c.ply"), SmallCloud(utm), encoding);
      Emit("ply", name + suffix, Take(Scratch("c.ply")));
    }
  }
  // Big endian, an element before the vertices and faces after them (no writer makes these).
  Emit("ply", "big_endian_with_faces",
       "ply\nformat binary_big_endian 1.0\nelement camera 1\nproperty float f\n"
       "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
           std::string("\x3f\x80\x00\x00", 4) + std::string("\x3f\x80\x00\x00", 4) +
           std::string("\x40\x00\x00\x00", 4) + std::string("\xc0\x40\x00\x00", 4) +
           std::string("\x03\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00", 13));
  io::CloudFile kitti = SmallCloud(false);
  kitti.normals.clear();
  kitti.labels.clear();
  io::WriteCloud(Scratch("c.bin"), kitti);
  Emit("kitti_bin", "five_points", Take(Scratch("c.bin")));
  LasSeeds();
}

// --- trajectories, scan folders, pose guesses ----------------------------------------------

std::vector<io::StampedPose> SmallTrajectory() {
  std::vector<io::StampedPose> poses;
  for (int i = 0; i < 3; ++i) {
    io::StampedPose p;
    p.t_ns = 1'630'577'758'569'490'000 + i * 100'000'000LL;
    p.position = Eigen::Vector3d(0.5 * i, 0.1, -0.25 * i);
    p.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3 * i, Eigen::Vector3d::UnitZ()));
    poses.push_back(p);
  }
  return poses;
}

std::string Balm(const std::vector<io::StampedPose>& poses) {
  std::string text;
  for (const io::StampedPose& p : poses) {
    const Eigen::Matrix3d R = p.orientation.toRotationMatrix();
    for (int r = 0; r < 3; ++r) {
      text += std::to_string(R(r, 0)) + "," + std::to_string(R(r, 1)) + "," +
              std::to_string(R(r, 2)) + "," + std::to_string(p.position[r]) + "\n";
    }
    text += "0,0,0," + io::FormatNsAsSeconds(p.t_ns) + "\n";
  }
  return text;
}

void TrajectorySeeds() {
  const std::vector<io::StampedPose> poses = SmallTrajectory();
  io::WriteTum(Scratch("t.tum"), poses);
  const std::string tum = Take(Scratch("t.tum"));
  io::WriteKitti(Scratch("k.txt"), poses, Scratch("times.txt"));
  const std::string kitti = Take(Scratch("k.txt"));
  const std::string times = Take(Scratch("times.txt"));
  // The target's first byte: TUM, KITTI, KITTI + times, times.
  Emit("trajectory", "tum", std::string(1, '\0') + tum);
  Emit("trajectory", "kitti", std::string(1, '\1') + kitti);
  Emit("trajectory", "kitti_times", std::string(1, '\2') + kitti + "\n%%\n" + times);
  Emit("trajectory", "times", std::string(1, '\3') + times);
  // The scan folder target: pose kind, scan format, stems, pose file text.
  const std::string stems = "full20 full21 full22\n";
  Emit("scan_folder", "none_pcd", std::string("\0\0", 2) + stems);
  Emit("scan_folder", "balm_pcd", std::string("\1\0", 2) + stems + Balm(poses));
  Emit("scan_folder", "tum_ply", std::string("\2\1", 2) + stems + tum);
  Emit("scan_folder", "kitti_times_bin", std::string("\3\2", 2) + stems + kitti + "\n%%\n" + times);
  Emit("scan_folder", "times_bin", std::string("\4\2", 2) + "000000 000001 000002\n" + times);
  Emit("scan_folder", "dot_tum_unnumbered", std::string("\5\0", 2) + "a b c\n" + tum);
  Emit("scan_folder", "mixed", std::string("\0\3", 2) + stems);
  Emit("pose_guess", "xyz_rpy", std::string(1, '\0') + "1 2 3 0 0 90");
  Emit("pose_guess", "bracketed", std::string(1, '\0') + "[1.5, -2, 0.25; 10, -5, 179.9]");
  Emit("pose_guess", "matrix", std::string(1, '\0') + "0 -1 0 1\n1 0 0 2\n0 0 1 3\n0 0 0 1");
  std::string numbers(1, '\1');
  for (const double v : {1.0, 2.0, 3.0, 0.0, 0.0, 90.0}) {
    numbers.append(reinterpret_cast<const char*>(&v), sizeof(v));
  }
  Emit("pose_guess", "numbers", numbers);
}

// --- configuration and JSON -----------------------------------------------------------------

void ConfigAndJsonSeeds() {
  hylo::config::RunConfig config;
  Emit("run_config", "defaults", hylo::config::ToYaml(config));
  config = hylo::config::ParseRunConfig(
      "backend: sliding_window\nimu: none\nlidar: {topic: /velodyne_points, time_convention: "
      "velodyne}\nlocalization: {initial_guess: \"1 2 3 0 0 45\"}\n",
      "seed");
  Emit("run_config", "sliding_window_no_imu", hylo::config::ToYaml(config));
  io::Json summary;
  summary["command"] = "map";
  summary["ate"] = {{"rmse_m", 0.0123}, {"max_m", std::numeric_limits<double>::quiet_NaN()}};
  summary["scans"] = {1, 2, 3};
  summary["name"] = "µ-site \"A\"";
  summary["ok"] = true;
  io::WriteJsonFile(Scratch("s.json"), summary);
  Emit("json", "summary", Take(Scratch("s.json")));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s OUT_DIR\n", argv[0]);
    return 2;
  }
  g_out = argv[1];
  for (const char* target :
       {"bag_pointcloud2", "bag_imu", "bag_records", "mcap_records", "cdr_messages",
        "rosbag2_metadata", "pcd", "ply", "kitti_bin", "las", "trajectory", "scan_folder",
        "pose_guess", "run_config", "json"}) {
    fs::remove_all(g_out / target);  // seeds only: a rerun leaves no stale files
  }
  fs::create_directories(g_out);
  PointCloud2Seeds();
  ImuSeeds();
  BagRecordSeeds();
  McapSeeds();
  CdrSeeds();
  MetadataSeeds();
  CloudSeeds();
  TrajectorySeeds();
  ConfigAndJsonSeeds();
  std::printf("seeds written to %s\n", g_out.string().c_str());
  return 0;
}
