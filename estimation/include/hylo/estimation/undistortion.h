#pragma once
// Motion compensation of a spinning-lidar sweep (FAST-LIO2 Sec. IV-B, "back propagation"):
// each return is moved from the lidar pose at its own time to the lidar pose at the scan end,
// using poses predicted at the IMU stamps inside the scan and interpolated per point. The
// poses are predicted once per sweep (SweepMotion) and then applied to whichever of its points
// a caller needs: the registration subset, the dense copy, the whole scan for relocalization.

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/common/sensor_data.h"
#include "hylo/estimation/estimator.h"

namespace hylo::estimation {

/// The lidar's motion within one sweep, seen from the lidar at the sweep's end.
class SweepMotion {
 public:
  /// No motion: points stay as measured (no IMU, or deskewing off).
  SweepMotion() = default;
  /// The poses `estimator.PredictAt` gives at the sweep start `start_ns`, at the
  /// `knot_times_ns` strictly inside it (the IMU stamps) and at its end `end_ns`.
  SweepMotion(int64_t start_ns, int64_t end_ns, const Estimator& estimator,
              const std::vector<int64_t>& knot_times_ns);

  /// Every point of `scan` (a sweep, or a subset of it with the same t_ns) in the lidar frame
  /// at the sweep's end. Between knots the rotation is interpolated by normalised lerp where
  /// the knots are less than 0.05 rad apart, by slerp otherwise; translation by lerp.
  PointCloud ToSweepEnd(const LidarScan& scan) const;

 private:
  Eigen::Vector3f ToSweepEnd(int64_t scan_t_ns, const ScanPoint& point) const;

  std::vector<int64_t> times_ns_;              // knots: start, inside, end
  std::vector<Eigen::Quaterniond> rotations_;  // T_end_lidar(t) rotation at each knot
  std::vector<Eigen::Vector3d> translations_;  // ... and translation, m
  std::vector<char> use_nlerp_;                // per interval [k, k+1]
};

/// Every point of `scan` in the lidar frame at `scan.end_t_ns`: SweepMotion of the scan's
/// times applied to all of it.
PointCloud Undistort(const LidarScan& scan, const Estimator& estimator,
                     const std::vector<int64_t>& knot_times_ns);

/// The points of `scan` as they are, without motion compensation.
PointCloud PointsOf(const LidarScan& scan);

}  // namespace hylo::estimation
