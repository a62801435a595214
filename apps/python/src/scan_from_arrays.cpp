#include "scan_from_arrays.h"

#include <pybind11/numpy.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "arrays.h"

namespace hylo::python {
namespace {

// A 1-D array of N values of T (converted when it is another type: these are small).
template <class T>
py::array_t<T> Column(const py::handle& object, std::size_t n, const char* what) {
  auto array = py::array_t<T, py::array::forcecast>::ensure(object);
  if (!array) {
    PyErr_Clear();
    throw std::invalid_argument(std::string(what) + ": expected a numeric array");
  }
  RequireShape(array, {static_cast<py::ssize_t>(n)}, what);
  return array;
}

}  // namespace

int64_t StampNs(const py::handle& t_s, const py::handle& t_ns, const char* what) {
  try {
    if (!t_ns.is_none()) return t_ns.cast<int64_t>();
    if (t_s.is_none()) throw std::invalid_argument(std::string(what) + ": a stamp is needed");
    return SecondsToNs(t_s.cast<double>(), what);
  } catch (const py::cast_error&) {
    throw std::invalid_argument(std::string(what) + ": expected a number (t_s, s) or an integer "
                                "(t_ns, ns)");
  }
}

std::vector<ImuSample> ImuFromArrays(const py::handle& t_s, const py::handle& accel,
                                     const py::handle& gyro, const py::handle& t_ns) {
  const py::array a = FloatArray(accel, "accel");
  const py::array g = FloatArray(gyro, "gyro");
  if (a.ndim() == 1) {  // one sample
    RequireShape(a, {3}, "accel");
    RequireShape(g, {3}, "gyro");
    ImuSample sample;
    sample.t_ns = StampNs(t_s, t_ns, "t_s");
    const auto a64 = py::array_t<double, py::array::forcecast>::ensure(a);
    const auto g64 = py::array_t<double, py::array::forcecast>::ensure(g);
    const auto av = a64.unchecked<1>();
    const auto gv = g64.unchecked<1>();
    sample.accel_imu = Eigen::Vector3d(av(0), av(1), av(2));
    sample.gyro_imu = Eigen::Vector3d(gv(0), gv(1), gv(2));
    return {sample};
  }
  RequireShape(a, {-1, 3}, "accel");
  const auto m = static_cast<std::size_t>(a.shape(0));
  RequireShape(g, {a.shape(0), 3}, "gyro");
  std::vector<ImuSample> samples(m);
  if (!t_ns.is_none()) {
    const auto stamps = Column<int64_t>(t_ns, m, "t_ns");  // owns a converted copy
    const auto t = stamps.unchecked<1>();
    for (std::size_t i = 0; i < m; ++i) samples[i].t_ns = t(static_cast<py::ssize_t>(i));
  } else {
    const auto stamps = Column<double>(t_s, m, "t_s");
    const auto t = stamps.unchecked<1>();
    for (std::size_t i = 0; i < m; ++i) {
      samples[i].t_ns = SecondsToNs(t(static_cast<py::ssize_t>(i)), "t_s[" + std::to_string(i) + "]");
    }
  }
  ForEachRow3(a, [&](py::ssize_t i, double x, double y, double z) {
    samples[static_cast<std::size_t>(i)].accel_imu = Eigen::Vector3d(x, y, z);
  });
  ForEachRow3(g, [&](py::ssize_t i, double x, double y, double z) {
    samples[static_cast<std::size_t>(i)].gyro_imu = Eigen::Vector3d(x, y, z);
  });
  return samples;
}

LidarScan ScanFromArrays(int64_t t_ns, const py::handle& points, const py::handle& point_times,
                         const py::handle& intensity, const py::handle& ring) {
  const py::array xyz = FloatArray(points, "points");
  RequireShape(xyz, {-1, 3}, "points");
  const auto n = static_cast<std::size_t>(xyz.shape(0));
  LidarScan scan;
  scan.t_ns = t_ns;
  scan.points.resize(n);
  ForEachRow3(xyz, [&](py::ssize_t i, auto x, auto y, auto z) {
    scan.points[static_cast<std::size_t>(i)].position_lidar =
        Eigen::Vector3f(static_cast<float>(x), static_cast<float>(y), static_cast<float>(z));
  });
  int32_t last_offset_ns = 0;
  if (!point_times.is_none()) {
    const auto times = Column<double>(point_times, n, "point_times");  // owns a converted copy
    const auto t = times.unchecked<1>();
    constexpr double kMaxS = std::numeric_limits<int32_t>::max() / 1e9;
    for (std::size_t i = 0; i < n; ++i) {
      const double s = t(static_cast<py::ssize_t>(i));
      if (!std::isfinite(s) || std::abs(s) > kMaxS) {
        throw std::invalid_argument("point_times[" + std::to_string(i) + "] = " +
                                    std::to_string(s) +
                                    ": must be finite, in s after the scan stamp, within 2.1 s");
      }
      scan.points[i].offset_ns = static_cast<int32_t>(std::llround(s * 1e9));
      last_offset_ns = std::max(last_offset_ns, scan.points[i].offset_ns);
    }
  }
  if (!intensity.is_none()) {
    const auto values = Column<float>(intensity, n, "intensity");
    const auto v = values.unchecked<1>();
    for (std::size_t i = 0; i < n; ++i) scan.points[i].intensity = v(static_cast<py::ssize_t>(i));
  }
  if (!ring.is_none()) {
    const auto rings = Column<int64_t>(ring, n, "ring");
    const auto r = rings.unchecked<1>();
    for (std::size_t i = 0; i < n; ++i) {
      const int64_t value = r(static_cast<py::ssize_t>(i));
      if (value < 0 || value > std::numeric_limits<uint16_t>::max()) {
        throw std::invalid_argument("ring[" + std::to_string(i) + "] = " +
                                    std::to_string(value) + ": must be within 0..65535");
      }
      scan.points[i].ring = static_cast<uint16_t>(value);
    }
  }
  scan.end_t_ns = t_ns + last_offset_ns;
  return scan;
}

}  // namespace hylo::python
