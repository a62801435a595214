#pragma once
// Trajectories on disk: TUM (`t x y z qx qy qz qw`) and KITTI (row-major 3x4 [R | t] per
// line, times in a separate file). Times are int64 ns inside and decimal seconds in files,
// converted digit by digit so that a Unix stamp keeps its nanoseconds.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace hylo::io {

/// One pose T_world_body at a time.
struct StampedPose {
  int64_t t_ns = 0;                                                ///< stamp, ns
  Eigen::Vector3d position = Eigen::Vector3d::Zero();              ///< body origin in world, m
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< R_world_body (unit)

  /// The pose as the transform T_world_body.
  Eigen::Isometry3d T_world_body() const {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.linear() = orientation.normalized().toRotationMatrix();
    T.translation() = position;
    return T;
  }
};

/// Reads a TUM file: exactly 8 numbers per line, `#` comments and blank lines allowed.
/// Throws std::runtime_error naming the file and line: wrong column count, a field that is
/// not a number, a quaternion whose norm is not 1 within 1e-3 (it is then normalised).
std::vector<StampedPose> ReadTum(const std::string& path);

/// Writes a TUM file (stamps in seconds with 9 decimals, other numbers with the shortest text
/// that reads back to the same double). Throws naming the file when it cannot be written.
void WriteTum(const std::string& path, const std::vector<StampedPose>& poses);

/// Where KITTI poses get their stamps.
struct KittiTiming {
  std::string times_path;   ///< one time (s) per line, line k for pose k; empty = use period
  double period_s = 0.1;    ///< time between poses when there is no times file, s (> 0)
  int64_t start_t_ns = 0;   ///< stamp of pose 0 when there is no times file, ns
  bool IsValid(std::string* why) const;
};

/// Reads a KITTI pose file: 12 numbers per line (row-major [R | t]). Throws naming the file
/// and line: wrong column count, non-numbers, R not a rotation (|R^T R - I| > 1e-3 or
/// det < 0), fewer times than poses in the times file.
std::vector<StampedPose> ReadKitti(const std::string& path, const KittiTiming& timing = {});

/// Writes a KITTI pose file and, when `times_path` is not empty, its times file.
void WriteKitti(const std::string& path, const std::vector<StampedPose>& poses,
                const std::string& times_path = "");

/// [R | t] to a pose; false when R is not a rotation (|R^T R - I|_F > 1e-3, det < 0, NaN).
bool PoseFromMatrix(const Eigen::Matrix<double, 3, 4>& T_world_body, int64_t t_ns,
                    StampedPose* pose);

/// Reads a times file: one time in seconds per line (blank and `#` lines skipped).
std::vector<int64_t> ReadTimes(const std::string& path);

/// Decimal seconds ("1630577758.569490", "-0.5", "1.2e3") to ns; plain decimals are converted
/// exactly (rounded at the 10th decimal), exponents through double. False on bad text.
bool ParseSecondsToNs(const std::string& text, int64_t* t_ns);

/// ns as seconds with exactly 9 decimals ("1630577758.569490000").
std::string FormatNsAsSeconds(int64_t t_ns);

}  // namespace hylo::io
