#pragma once
// Measurements from numpy: what a caller of hylo.Pipeline hands in, as the pipeline's own
// IMU samples and scans. Arrays are read in place; each scan is written once into the
// pipeline's layout (float position, time offset, intensity, ring per point).

#include <pybind11/pybind11.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "hylo/common/sensor_data.h"

namespace hylo::python {

namespace py = pybind11;

/// The stamp of a measurement: `t_ns` (int, exact) when given, else `t_s` (float, s; about
/// 0.2 µs of rounding at Unix-epoch magnitudes). Throws std::invalid_argument naming `what`.
int64_t StampNs(const py::handle& t_s, const py::handle& t_ns, const char* what);

/// One sample (t scalar, accel and gyro 3-vectors) or M of them (t (M,), accel and gyro
/// (M, 3)); m/s², rad/s, IMU frame. Throws std::invalid_argument naming the argument.
std::vector<ImuSample> ImuFromArrays(const py::handle& t_s, const py::handle& accel,
                                     const py::handle& gyro, const py::handle& t_ns);

/// A scan: points (N, 3) in the lidar frame (m), point_times (N,) s after the scan stamp (None:
/// every return at the stamp), intensity (N,) and ring (N,) optional. Throws
/// std::invalid_argument naming the argument: wrong shape, non-finite or out-of-range times.
LidarScan ScanFromArrays(int64_t t_ns, const py::handle& points, const py::handle& point_times,
                         const py::handle& intensity, const py::handle& ring);

}  // namespace hylo::python
