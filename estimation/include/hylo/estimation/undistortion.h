#pragma once
// Motion compensation of a spinning-lidar sweep (FAST-LIO2 Sec. IV-B, "back propagation"):
// each return is moved from the lidar pose at its own time to the lidar pose at the scan end,
// using IMU poses predicted at the IMU stamps inside the scan and interpolated per point.

#include <cstdint>
#include <vector>

#include "hylo/estimation/estimator.h"
#include "hylo/estimation/measurements.h"
#include "hylo/registration/point_types.h"

namespace hylo::estimation {

/// Every point of `scan` in the lidar frame at `scan.end_t_ns`. `knot_times_ns` are the
/// times at which `estimator.PredictAt` is evaluated (the IMU stamps inside the scan; the
/// scan start and end are added); poses between knots are interpolated (rotation: normalised
/// lerp between knots under 0.05 rad apart, slerp otherwise; translation: lerp).
registration::PointCloud Undistort(const LidarScan& scan, const Estimator& estimator,
                                   const std::vector<int64_t>& knot_times_ns);

/// The points of `scan` as they are, without motion compensation (no-IMU mode).
registration::PointCloud PointsOf(const LidarScan& scan);

}  // namespace hylo::estimation
