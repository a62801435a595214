// Fuzz target: a scan folder (scan files + pose/time file) through IndexScanFolder,
// DescribeScanFolder, ReadScanFolderPoses and the LogReader over it.
// Input: byte 0 picks the pose/time file (none, poses.csv, poses.txt, poses.txt + times.txt,
// times.txt, a .tum file), byte 1 the scan format (pcd, ply, bin, or mixed); then a line of
// scan file stems separated by spaces (letters, digits, '_', '-', '.'; at most 12), then the
// pose file's text ("<poses>\n%%\n<times>" for poses.txt + times.txt). Every scan file holds
// the same small valid cloud: the point readers have their own targets.

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "hylo/io/cloud_io.h"
#include "hylo/logs/scan_folder.h"

namespace {

using hylo::fuzz::Require;
namespace io = hylo::io;
namespace logs = hylo::logs;

constexpr const char* kExtensions[] = {".pcd", ".ply", ".bin"};

// A two-point cloud as the project's own writer stores it, per format.
const std::string& ScanBytes(int format) {
  static const std::vector<std::string> bytes = [] {
    io::CloudFile cloud;
    cloud.positions = {{1.0, 2.0, 3.0}, {-4.0, 5.5, 0.25}};
    cloud.intensity = {7.f, 8.f};
    std::vector<std::string> out;
    for (const char* ext : kExtensions) {
      const std::string path = hylo::fuzz::WriteScratchFile(std::string("template") + ext, "");
      io::WriteCloud(path, cloud);
      std::ifstream in(path, std::ios::binary);
      out.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    return out;
  }();
  return bytes[format];
}

std::string Sanitized(const std::string& stem) {
  std::string out;
  for (const char c : stem) {
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.') {
      out += c;
    }
  }
  return out.size() > 32 || out == "." || out == ".." ? std::string() : out;
}

void WriteFile(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

void CheckIndex(const logs::ScanFolderIndex& index) {
  for (std::size_t i = 0; i < index.scans.size(); ++i) {
    const logs::ScanFolderEntry& e = index.scans[i];
    Require(i == 0 || index.scans[i - 1].index < e.index, "scan indexes not strictly increasing");
    Require(!e.has_pose || e.has_time, "a pose without a stamp");
    if (e.has_pose) {
      Require(e.pose.position.allFinite(), "a non-finite reference position was accepted");
      Require(std::abs(e.pose.orientation.norm() - 1.0) < 1e-9, "orientation is not unit");
    }
  }
}

void CheckDescription(const logs::ScanFolderIndex& index, const logs::ScanFolderDescription& d) {
  Require(d.scan_count == index.scans.size(), "description counts other scans");
  Require(d.scans_with_pose + d.scans_without_pose == d.scan_count, "pose counts do not add up");
  Require(std::isfinite(d.time_span_s) && d.time_span_s >= 0.0, "time span negative or NaN");
}

void ReadAll(const std::string& dir, const logs::ScanFolderIndex& index) {
  const auto reader = logs::OpenScanFolder(dir, logs::LogReadOptions{});
  logs::LogMessage message;
  std::size_t k = 0;
  while (reader->Next(&message)) {
    Require(k < index.scans.size(), "the reader delivers more scans than the index lists");
    Require(message.scan.t_ns == index.scans[k].pose.t_ns, "scan stamp differs from the index");
    ++k;
  }
  Require(k == index.scans.size(), "the reader delivers fewer scans than the index lists");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const int pose_kind = data[0] % 6;
  const int format = data[1] % 4;
  const std::string text(reinterpret_cast<const char*>(data + 2), size - 2);
  const std::size_t line_end = std::min(text.find('\n'), text.size());
  const std::string dir = hylo::fuzz::FreshScratchFolder("scans");
  int written = 0;
  for (const std::string& word : hylo::fuzz::Split(text.substr(0, line_end), " ")) {
    const std::string stem = Sanitized(word);
    if (stem.empty() || written == 12) continue;
    const int f = format == 3 ? written % 3 : format;
    WriteFile(dir + "/" + stem + kExtensions[f], ScanBytes(f));
    ++written;
  }
  const std::string body = line_end < text.size() ? text.substr(line_end + 1) : std::string();
  const std::vector<std::string> parts = hylo::fuzz::Split(body, "\n%%\n");
  const char* const kPoseFiles[] = {nullptr,     "poses.csv", "poses.txt",
                                    "poses.txt", "times.txt", "run.tum"};
  if (kPoseFiles[pose_kind] != nullptr) WriteFile(dir + "/" + kPoseFiles[pose_kind], parts[0]);
  if (pose_kind == 3) WriteFile(dir + "/times.txt", parts.size() > 1 ? parts[1] : "");
  try {
    const logs::ScanFolderIndex index = logs::IndexScanFolder(dir);
    CheckIndex(index);
    CheckDescription(index, logs::DescribeScanFolder(dir));
    std::vector<std::size_t> positions;
    const std::vector<io::StampedPose> poses = logs::ReadScanFolderPoses(dir, &positions);
    Require(poses.size() == positions.size(), "poses and their scan positions differ in number");
    const bool all_stamped = std::all_of(index.scans.begin(), index.scans.end(),
                                         [](const logs::ScanFolderEntry& e) { return e.has_time; });
    if (all_stamped) ReadAll(dir, index);
  } catch (const std::runtime_error& e) {
    hylo::fuzz::RequireClearError(e, dir);
  }
  return 0;
}
