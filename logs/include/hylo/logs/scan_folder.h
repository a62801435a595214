#pragma once
// A folder of lidar scans (PCD, PLY or KITTI .bin, one file per scan) with an optional
// pose/time file, read as a LogReader (scans only, no IMU). Scan files are ordered by the
// number in their name (full20 < full100); that number is the scan index, and row k of a
// pose or time file belongs to scan k. Supported pose/time files, looked up in this order:
//   poses.csv        BALM: blocks of 4 rows "r r r t" x3 + "0,0,0,<unix time s>" (T_world_lidar)
//   poses.txt        TUM (8 columns) or KITTI (12 columns; times from times.txt if present)
//   *.tum            TUM
//   times.txt        times only (one time in s per line)
// With none of them, scan k is stamped k x kDefaultScanPeriodNs (said in the description).
// Scans carry no per-point time: convention kNone, every offset 0.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hylo/logs/log_reader.h"
#include "hylo/io/trajectory_io.h"

namespace hylo::logs {

/// Stamp spacing assumed when a folder has no time source at all (10 Hz).
constexpr int64_t kDefaultScanPeriodNs = 100'000'000;

enum class ScanPoseFileKind { kNone, kBalm, kTum, kKitti, kTimesOnly };
/// "none", "balm", "tum", "kitti", "times".
std::string ToString(ScanPoseFileKind kind);

/// One scan file of a folder, in reading order.
struct ScanFolderEntry {
  std::string path;        ///< scan file
  int64_t index = 0;       ///< number in the name (position in name order when some lack one)
  bool has_time = false;   ///< a stamp was found for it
  bool has_pose = false;   ///< a reference pose was found for it
  io::StampedPose pose;        ///< T_world_lidar when has_pose; pose.t_ns = the scan stamp
};

/// The folder listing with stamps and reference poses (reads no point data).
struct ScanFolderIndex {
  std::string dir;
  std::string format;                   ///< "pcd", "ply" or "kitti_bin"
  ScanPoseFileKind pose_kind = ScanPoseFileKind::kNone;
  std::string pose_file;                ///< pose (or times) file used, empty when none
  std::string time_source;              ///< where stamps come from, for printouts
  std::vector<ScanFolderEntry> scans;   ///< reading order
};

/// What `hylo info` prints about a folder.
struct ScanFolderDescription {
  std::string dir;
  std::size_t scan_count = 0;
  std::string format;                     ///< "pcd", "ply" or "kitti_bin"
  std::string encoding;                   ///< of the first scan ("binary", ...)
  std::vector<std::string> point_fields;  ///< of the first scan, file order
  std::size_t first_scan_points = 0;      ///< points announced by the first scan's header
  ScanPoseFileKind pose_kind = ScanPoseFileKind::kNone;
  std::string pose_file;
  std::string time_source;
  int64_t first_t_ns = 0;                 ///< earliest scan stamp, ns
  int64_t last_t_ns = 0;                  ///< latest scan stamp, ns
  double time_span_s = 0.0;               ///< last - first, s
  std::size_t scans_with_pose = 0;
  std::size_t scans_without_pose = 0;
  std::size_t scans_without_time = 0;
};

/// Lists the folder and reads its pose/time file. Throws std::runtime_error naming the
/// folder or file: missing folder, no scan files, mixed scan formats, a malformed pose file.
ScanFolderIndex IndexScanFolder(const std::string& dir);

/// Header-level summary (reads the first scan's header only).
ScanFolderDescription DescribeScanFolder(const std::string& dir);

/// Reference poses T_world_lidar of the scans that have one, in reading order, each stamped
/// with its scan's stamp (the one the LogReader delivers, so associating by time is exact).
/// `scan_positions` (optional) receives each pose's position in the reading order.
std::vector<io::StampedPose> ReadScanFolderPoses(const std::string& dir,
                                             std::vector<std::size_t>* scan_positions = nullptr);

/// A LogReader over the folder, one scan in memory at a time. Throws when a scan has no stamp
/// or when options ask for a per-point time convention other than auto/none.
std::unique_ptr<LogReader> OpenScanFolder(const std::string& dir, const LogReadOptions& options);

}  // namespace hylo::logs
