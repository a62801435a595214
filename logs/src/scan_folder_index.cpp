// Scan folder listing and its pose/time files (see scan_folder.h for the supported layouts).

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "hylo/io/text.h"
#include "hylo/logs/scan_folder.h"

namespace hylo::logs {
namespace {

namespace fs = std::filesystem;
using io::ThrowFileError;

struct ScanFile {
  std::string path;
  std::string name;
  bool has_number = false;
  int64_t number = 0;
};

// The last run of digits in the file stem ("full20" -> 20, "000123" -> 123).
bool NumberInName(const std::string& stem, int64_t* number) {
  const std::size_t end = stem.find_last_of("0123456789");
  if (end == std::string::npos) return false;
  std::size_t begin = end;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(stem[begin - 1]))) --begin;
  if (end - begin + 1 > 18) return false;  // would overflow int64
  *number = std::stoll(stem.substr(begin, end - begin + 1));
  return true;
}

std::string FormatOf(const std::string& extension) {
  if (extension == ".pcd") return "pcd";
  if (extension == ".ply") return "ply";
  if (extension == ".bin") return "kitti_bin";
  return "";
}

std::vector<ScanFile> ListScans(const std::string& dir, std::string* format) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) ThrowFileError(dir, "not a folder");
  std::vector<ScanFile> files;
  std::set<std::string> formats;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const std::string f = FormatOf(io::ToLower(entry.path().extension().string()));
    if (f.empty()) continue;
    formats.insert(f);
    ScanFile file{entry.path().string(), entry.path().filename().string()};
    file.has_number = NumberInName(entry.path().stem().string(), &file.number);
    files.push_back(file);
  }
  if (files.empty()) ThrowFileError(dir, "no scan files (.pcd, .ply or .bin)");
  if (formats.size() > 1) ThrowFileError(dir, "mixed scan formats (pcd, ply and .bin together)");
  *format = *formats.begin();
  const bool numbered = std::all_of(files.begin(), files.end(),
                                    [](const ScanFile& f) { return f.has_number; });
  std::sort(files.begin(), files.end(), [numbered](const ScanFile& a, const ScanFile& b) {
    if (numbered && a.number != b.number) return a.number < b.number;
    return a.name < b.name;
  });
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (!numbered) files[i].number = static_cast<int64_t>(i);
    if (i > 0 && files[i].number == files[i - 1].number) {
      ThrowFileError(dir, "two scans with index " + std::to_string(files[i].number) + ": " +
                              files[i - 1].name + " and " + files[i].name);
    }
  }
  return files;
}

// Rows of the pose/time file: row k belongs to scan index k.
struct Rows {
  std::vector<int64_t> times;       ///< stamps, ns
  std::vector<io::StampedPose> poses;   ///< reference poses
  bool times_from_period = false;   ///< no time source: index x kDefaultScanPeriodNs
};

std::vector<std::string> SplitCommas(const std::string& line) {
  std::vector<std::string> cells;
  std::string cell;
  std::istringstream stream(line);
  while (std::getline(stream, cell, ',')) {
    const std::vector<std::string> words = io::SplitWords(cell);
    cells.push_back(words.empty() ? "" : words[0]);
  }
  while (!cells.empty() && cells.back().empty()) cells.pop_back();  // trailing comma
  return cells;
}

// BALM: blocks of 4 rows; the 4th is "0,0,0,<unix time>", read as 0 0 0 1 + a stamp.
Rows ReadBalmPoses(const std::string& path) {
  std::ifstream in(path);
  if (!in) ThrowFileError(path, "cannot open (missing or unreadable)");
  Rows rows;
  Eigen::Matrix<double, 3, 4> T;
  std::string line;
  int row = 0, line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::vector<std::string> cells = SplitCommas(line);
    if (cells.empty()) continue;
    auto fail = [&](const std::string& why) {
      ThrowFileError(path, "line " + std::to_string(line_no) + ": " + why);
    };
    if (cells.size() != 4) fail("expected 4 comma-separated numbers");
    double v[4];
    for (int k = 0; k < 4; ++k) {
      char* end = nullptr;
      v[k] = std::strtod(cells[k].c_str(), &end);
      if (end == cells[k].c_str() || *end != '\0' || !std::isfinite(v[k])) {
        fail("'" + cells[k] + "' is not a finite number");
      }
    }
    if (row < 3) {
      T.row(row++) << v[0], v[1], v[2], v[3];
      continue;
    }
    if (v[0] != 0 || v[1] != 0 || v[2] != 0) fail("4th row of a block must be 0,0,0,<time>");
    io::StampedPose pose;
    if (!io::ParseSecondsToNs(cells[3], &pose.t_ns)) fail("bad time '" + cells[3] + "'");
    if (!PoseFromMatrix(T, pose.t_ns, &pose)) fail("block does not hold a rotation");
    rows.poses.push_back(pose);
    rows.times.push_back(pose.t_ns);
    row = 0;
  }
  if (row != 0) ThrowFileError(path, "truncated: last block has " + std::to_string(row) + " rows");
  return rows;
}

Rows FromTum(const std::string& path) {
  Rows rows;
  rows.poses = io::ReadTum(path);
  for (const io::StampedPose& p : rows.poses) rows.times.push_back(p.t_ns);
  return rows;
}

// Column count of the first data line of a whitespace-separated file.
std::size_t FirstLineColumns(const std::string& path) {
  std::ifstream in(path);
  if (!in) ThrowFileError(path, "cannot open (missing or unreadable)");
  std::string line;
  while (std::getline(in, line)) {
    const std::vector<std::string> words = io::SplitWords(line);
    if (!words.empty() && words[0][0] != '#') return words.size();
  }
  return 0;
}

Rows ReadPoseRows(const std::string& dir, ScanFolderIndex* index) {
  const fs::path folder(dir);
  const std::string times_txt = (folder / "times.txt").string();
  const bool has_times = fs::is_regular_file(times_txt);
  auto use = [&](ScanPoseFileKind kind, const fs::path& file, const std::string& source) {
    index->pose_kind = kind;
    index->pose_file = file.string();
    index->time_source = source;
  };
  if (fs::is_regular_file(folder / "poses.csv")) {
    use(ScanPoseFileKind::kBalm, folder / "poses.csv", "BALM poses.csv (4th row of each block)");
    return ReadBalmPoses(index->pose_file);
  }
  if (fs::is_regular_file(folder / "poses.txt")) {
    const std::string poses_txt = (folder / "poses.txt").string();
    const std::size_t columns = FirstLineColumns(poses_txt);
    if (columns == 8) {
      use(ScanPoseFileKind::kTum, poses_txt, "TUM poses.txt");
      return FromTum(poses_txt);
    }
    if (columns != 12) {
      ThrowFileError(poses_txt, "neither TUM (8 columns) nor KITTI (12): " +
                                    std::to_string(columns) + " columns");
    }
    use(ScanPoseFileKind::kKitti, poses_txt, has_times ? "times.txt" : "scan index x 0.1 s");
    Rows rows;
    rows.poses = io::ReadKitti(poses_txt);
    if (has_times) rows.times = io::ReadTimes(times_txt);
    rows.times_from_period = !has_times;
    return rows;
  }
  std::vector<fs::path> tum_files;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    if (e.is_regular_file() && io::ToLower(e.path().extension().string()) == ".tum") {
      tum_files.push_back(e.path());
    }
  }
  if (!tum_files.empty()) {
    std::sort(tum_files.begin(), tum_files.end());
    use(ScanPoseFileKind::kTum, tum_files[0], "TUM " + tum_files[0].filename().string());
    return FromTum(index->pose_file);
  }
  Rows rows;
  if (has_times) {
    use(ScanPoseFileKind::kTimesOnly, times_txt, "times.txt");
    rows.times = io::ReadTimes(times_txt);
  } else {
    use(ScanPoseFileKind::kNone, "", "none: scan index x 0.1 s (10 Hz assumed)");
    rows.times_from_period = true;
  }
  return rows;
}

}  // namespace

std::string ToString(ScanPoseFileKind kind) {
  switch (kind) {
    case ScanPoseFileKind::kNone: return "none";
    case ScanPoseFileKind::kBalm: return "balm";
    case ScanPoseFileKind::kTum: return "tum";
    case ScanPoseFileKind::kKitti: return "kitti";
    case ScanPoseFileKind::kTimesOnly: return "times";
  }
  return "unknown";
}

ScanFolderIndex IndexScanFolder(const std::string& dir) {
  ScanFolderIndex index;
  index.dir = dir;
  const std::vector<ScanFile> files = ListScans(dir, &index.format);
  const Rows rows = ReadPoseRows(dir, &index);
  for (const ScanFile& file : files) {
    ScanFolderEntry entry;
    entry.path = file.path;
    entry.index = file.number;
    const auto k = static_cast<std::size_t>(file.number);
    if (k < rows.times.size()) {
      entry.has_time = true;
      entry.pose.t_ns = rows.times[k];
    } else if (rows.times_from_period &&
               file.number <= std::numeric_limits<int64_t>::max() / kDefaultScanPeriodNs) {
      // A larger index (a file name with 11+ digits) has no stamp: it would overflow int64 ns.
      entry.has_time = true;
      entry.pose.t_ns = file.number * kDefaultScanPeriodNs;
    }
    if (entry.has_time && k < rows.poses.size()) {
      entry.has_pose = true;
      const int64_t t_ns = entry.pose.t_ns;
      entry.pose = rows.poses[k];
      entry.pose.t_ns = t_ns;
    }
    index.scans.push_back(entry);
  }
  return index;
}

}  // namespace hylo::logs
