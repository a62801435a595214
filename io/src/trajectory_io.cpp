#include "hylo/io/trajectory_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "cloud_fields.h"
#include "hylo/io/atomic_file.h"

namespace hylo::io {
namespace {



struct NumberLine {
  int line_no = 0;
  std::vector<std::string> words;
};

// Non-blank, non-comment lines with their 1-based line numbers.
std::vector<NumberLine> ReadDataLines(const std::string& path) {
  std::ifstream in(path);
  if (!in) ThrowFileError(path, "cannot open (missing or unreadable)");
  std::vector<NumberLine> lines;
  std::string line;
  for (int line_no = 1; std::getline(in, line); ++line_no) {
    NumberLine entry{line_no, SplitWords(line)};
    if (entry.words.empty() || entry.words[0][0] == '#') continue;
    lines.push_back(std::move(entry));
  }
  return lines;
}

[[noreturn]] void LineError(const std::string& path, int line_no, const std::string& reason) {
  ThrowFileError(path, "line " + std::to_string(line_no) + ": " + reason);
}

double ParseNumber(const std::string& path, int line_no, const std::string& word) {
  char* end = nullptr;
  const double value = std::strtod(word.c_str(), &end);
  if (end == word.c_str() || *end != '\0' || !std::isfinite(value)) {
    LineError(path, line_no, "'" + word + "' is not a finite number");
  }
  return value;
}

}  // namespace

bool ParseSecondsToNs(const std::string& text, int64_t* t_ns) {
  if (text.find_first_of("eE") != std::string::npos) {
    char* end = nullptr;
    const double seconds = std::strtod(text.c_str(), &end);
    // Beyond +-9.2e9 s, llround has no int64 to return (its result is unspecified).
    if (end == text.c_str() || *end != '\0' || !(std::abs(seconds) < 9.2e9)) return false;
    *t_ns = std::llround(seconds * 1e9);
    return true;
  }
  std::size_t pos = 0;
  const bool negative = !text.empty() && text[0] == '-';
  if (!text.empty() && (text[0] == '-' || text[0] == '+')) ++pos;
  int64_t whole = 0, fraction = 0;
  int whole_digits = 0, fraction_digits = 0;
  bool round_up = false;
  constexpr int64_t kMaxWholeSeconds = INT64_MAX / 1000000000 - 1;  // ~292 years
  for (; pos < text.size() && std::isdigit(static_cast<unsigned char>(text[pos])); ++pos) {
    whole = whole * 10 + (text[pos] - '0');
    ++whole_digits;
    if (whole > kMaxWholeSeconds) return false;
  }
  if (pos < text.size() && text[pos] == '.') {
    for (++pos; pos < text.size() && std::isdigit(static_cast<unsigned char>(text[pos])); ++pos) {
      if (fraction_digits < 9) fraction = fraction * 10 + (text[pos] - '0');
      if (fraction_digits == 9) round_up = text[pos] >= '5';
      ++fraction_digits;
    }
  }
  if (pos != text.size() || whole_digits + fraction_digits == 0) return false;
  for (int k = std::min(fraction_digits, 9); k < 9; ++k) fraction *= 10;
  const int64_t magnitude = whole * 1000000000 + fraction + (round_up ? 1 : 0);
  *t_ns = negative ? -magnitude : magnitude;
  return true;
}

std::string FormatNsAsSeconds(int64_t t_ns) {
  const bool negative = t_ns < 0;
  // Work on the unsigned magnitude so that INT64_MIN needs no special case.
  const uint64_t magnitude = negative ? 0 - static_cast<uint64_t>(t_ns) : t_ns;
  std::string fraction = std::to_string(magnitude % 1000000000);
  fraction.insert(0, 9 - fraction.size(), '0');
  return (negative ? "-" : "") + std::to_string(magnitude / 1000000000) + "." + fraction;
}

std::vector<StampedPose> ReadTum(const std::string& path) {
  std::vector<StampedPose> poses;
  for (const NumberLine& line : ReadDataLines(path)) {
    if (line.words.size() != 8) {
      LineError(path, line.line_no, "expected 8 columns (t x y z qx qy qz qw), found " +
                                        std::to_string(line.words.size()));
    }
    StampedPose pose;
    if (!ParseSecondsToNs(line.words[0], &pose.t_ns)) {
      LineError(path, line.line_no, "'" + line.words[0] + "' is not a time in seconds");
    }
    double v[7];
    for (int k = 0; k < 7; ++k) v[k] = ParseNumber(path, line.line_no, line.words[k + 1]);
    pose.position = Eigen::Vector3d(v[0], v[1], v[2]);
    const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);  // file order qx qy qz qw
    if (std::abs(q.norm() - 1.0) > 1e-3) {
      LineError(path, line.line_no, "quaternion norm " + std::to_string(q.norm()) + " is not 1");
    }
    pose.orientation = q.normalized();
    poses.push_back(pose);
  }
  return poses;
}

void WriteTum(const std::string& path, const std::vector<StampedPose>& poses) {
  AtomicFile file(path);
  std::ofstream& out = file.stream();
  out << "# t x y z qx qy qz qw (T_world_body; t in s)\n";
  for (const StampedPose& p : poses) {
    const Eigen::Quaterniond& q = p.orientation;
    out << FormatNsAsSeconds(p.t_ns);
    for (double v : {p.position.x(), p.position.y(), p.position.z(), q.x(), q.y(), q.z(), q.w()}) {
      out << ' ' << internal::FormatShortest(v);
    }
    out << '\n';
  }
  file.Commit();
}

bool PoseFromMatrix(const Eigen::Matrix<double, 3, 4>& T_world_body, int64_t t_ns,
                    StampedPose* pose) {
  const Eigen::Matrix3d R = T_world_body.leftCols<3>();
  const double orthogonality_error = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
  if (!(orthogonality_error <= 1e-3) || R.determinant() < 0) return false;
  pose->t_ns = t_ns;
  pose->position = T_world_body.col(3);
  pose->orientation = Eigen::Quaterniond(R).normalized();
  return true;
}

bool KittiTiming::IsValid(std::string* why) const {
  if (!(period_s > 0.0) || !std::isfinite(period_s)) {
    if (why != nullptr) *why = "period_s = " + std::to_string(period_s) + " must be > 0";
    return false;
  }
  return true;
}

std::vector<int64_t> ReadTimes(const std::string& path) {
  std::vector<int64_t> times;
  for (const NumberLine& line : ReadDataLines(path)) {
    int64_t t_ns = 0;
    if (line.words.size() != 1 || !ParseSecondsToNs(line.words[0], &t_ns)) {
      LineError(path, line.line_no, "expected one time in seconds");
    }
    times.push_back(t_ns);
  }
  return times;
}

std::vector<StampedPose> ReadKitti(const std::string& path, const KittiTiming& timing) {
  std::string why;
  if (!timing.IsValid(&why)) ThrowFileError(path, "bad KittiTiming: " + why);
  const std::vector<int64_t> times =
      timing.times_path.empty() ? std::vector<int64_t>{} : ReadTimes(timing.times_path);
  std::vector<StampedPose> poses;
  for (const NumberLine& line : ReadDataLines(path)) {
    if (line.words.size() != 12) {
      LineError(path, line.line_no, "expected 12 numbers (row-major 3x4), found " +
                                        std::to_string(line.words.size()));
    }
    Eigen::Matrix<double, 3, 4> T;
    for (int k = 0; k < 12; ++k) T(k / 4, k % 4) = ParseNumber(path, line.line_no, line.words[k]);
    StampedPose pose;
    if (!PoseFromMatrix(T, 0, &pose)) {
      LineError(path, line.line_no, "the 3x3 block is not a rotation");
    }
    const std::size_t index = poses.size();
    if (timing.times_path.empty()) {
      pose.t_ns = timing.start_t_ns + std::llround(static_cast<double>(index) * timing.period_s * 1e9);
    } else if (index < times.size()) {
      pose.t_ns = times[index];
    } else {
      ThrowFileError(timing.times_path, "has " + std::to_string(times.size()) +
                                            " times, fewer than the poses in " + path);
    }
    poses.push_back(pose);
  }
  return poses;
}

void WriteKitti(const std::string& path, const std::vector<StampedPose>& poses,
                const std::string& times_path) {
  AtomicFile file(path);
  std::ofstream& out = file.stream();
  for (const StampedPose& p : poses) {
    const Eigen::Matrix3d R = p.orientation.normalized().toRotationMatrix();
    for (int k = 0; k < 12; ++k) {
      const double v = k % 4 == 3 ? p.position[k / 4] : R(k / 4, k % 4);
      out << (k > 0 ? " " : "") << internal::FormatShortest(v);
    }
    out << '\n';
  }
  file.Commit();
  if (times_path.empty()) return;
  AtomicFile times(times_path);
  for (const StampedPose& p : poses) times.stream() << FormatNsAsSeconds(p.t_ns) << '\n';
  times.Commit();
}

}  // namespace hylo::io
