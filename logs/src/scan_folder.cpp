// A scan folder as a LogReader, its description and its reference poses.

#include "hylo/logs/scan_folder.h"

#include <algorithm>
#include <stdexcept>

#include "hylo/io/cloud_io.h"

namespace hylo::logs {
namespace {

class ScanFolderReader : public LogReader {
 public:
  explicit ScanFolderReader(ScanFolderIndex index) : index_(std::move(index)) {}

  bool Next(LogMessage* message) override {
    if (next_ >= index_.scans.size()) return false;
    const ScanFolderEntry& entry = index_.scans[next_++];
    const io::CloudFile cloud = io::ReadCloud(entry.path);  // one scan in memory at a time
    message->kind = LogMessage::Kind::kScan;
    LidarScan& scan = message->scan;
    scan.t_ns = entry.pose.t_ns;
    scan.end_t_ns = entry.pose.t_ns;  // no per-point time: every return at the stamp
    scan.frame_id = "lidar";
    scan.points.resize(cloud.positions.size());
    for (std::size_t i = 0; i < cloud.positions.size(); ++i) {
      ScanPoint& p = scan.points[i];
      // Scans are in their own sensor frame (near zero), so float keeps sub-millimetre detail.
      p.position_lidar = cloud.positions[i].cast<float>();
      p.intensity = cloud.intensity.empty() ? 0.f : cloud.intensity[i];
      p.offset_ns = 0;
      p.ring = 0;
    }
    ++counters_.scan_messages;
    counters_.dropped_non_finite_points += cloud.dropped_non_finite;
    if (scan.points.empty()) ++counters_.empty_scans;
    return true;
  }

  const LogReadCounters& counters() const override { return counters_; }
  PointTimeConvention time_convention() const override { return PointTimeConvention::kNone; }

 private:
  ScanFolderIndex index_;
  std::size_t next_ = 0;
  LogReadCounters counters_;
};

}  // namespace

ScanFolderDescription DescribeScanFolder(const std::string& dir) {
  const ScanFolderIndex index = IndexScanFolder(dir);
  ScanFolderDescription d;
  d.dir = dir;
  d.scan_count = index.scans.size();
  d.format = index.format;
  d.pose_kind = index.pose_kind;
  d.pose_file = index.pose_file;
  d.time_source = index.time_source;
  const io::CloudFileInfo first = io::ReadCloudInfo(index.scans.front().path);
  d.encoding = first.encoding;
  d.point_fields = first.fields;
  d.first_scan_points = first.points;
  bool any_time = false;
  for (const ScanFolderEntry& scan : index.scans) {
    (scan.has_pose ? d.scans_with_pose : d.scans_without_pose) += 1;
    if (!scan.has_time) {
      ++d.scans_without_time;
      continue;
    }
    d.first_t_ns = any_time ? std::min(d.first_t_ns, scan.pose.t_ns) : scan.pose.t_ns;
    d.last_t_ns = any_time ? std::max(d.last_t_ns, scan.pose.t_ns) : scan.pose.t_ns;
    any_time = true;
  }
  d.time_span_s = static_cast<double>(d.last_t_ns - d.first_t_ns) * 1e-9;
  return d;
}

std::vector<io::StampedPose> ReadScanFolderPoses(const std::string& dir,
                                             std::vector<std::size_t>* scan_positions) {
  const ScanFolderIndex index = IndexScanFolder(dir);
  std::vector<io::StampedPose> poses;
  if (scan_positions != nullptr) scan_positions->clear();
  for (std::size_t i = 0; i < index.scans.size(); ++i) {
    if (!index.scans[i].has_pose) continue;
    poses.push_back(index.scans[i].pose);
    if (scan_positions != nullptr) scan_positions->push_back(i);
  }
  return poses;
}

std::unique_ptr<LogReader> OpenScanFolder(const std::string& dir, const LogReadOptions& options) {
  if (options.time_convention != PointTimeConvention::kAuto &&
      options.time_convention != PointTimeConvention::kNone) {
    throw std::runtime_error(dir + ": scan folders carry no per-point time; time convention '" +
                             ToString(options.time_convention) + "' needs a bag (use auto or "
                             "none)");
  }
  ScanFolderIndex index = IndexScanFolder(dir);
  for (const ScanFolderEntry& scan : index.scans) {
    if (!scan.has_time) {
      throw std::runtime_error(
          scan.path + ": no stamp for scan index " + std::to_string(scan.index) +
          (index.pose_file.empty() ? " (index x 0.1 s is beyond the int64 ns range)"
                                   : " in " + index.pose_file));
    }
  }
  return std::make_unique<ScanFolderReader>(std::move(index));
}

}  // namespace hylo::logs
