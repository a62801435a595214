// hylo.read_log: a ROS1 bag or a scan folder, message by message, as the command line reads it
// (logs::OpenLog with the configuration's topics and per-point time convention).
#include <pybind11/stl.h>

#include <memory>

#include "arrays.h"
#include "bindings.h"
#include "config_binding.h"
#include "errors.h"
#include "hylo/logs/log_reader.h"
#include "log_messages.h"

namespace hylo::python {
namespace {

// A column of a scan's points (a member of ScanPoint) as a numpy view with the point stride;
// `self` (the Python Scan) keeps the memory alive.
template <class T>
py::array PointColumn(py::object self, std::size_t offset_bytes, std::vector<py::ssize_t> shape,
                      std::vector<py::ssize_t> strides) {
  ScanMessage& message = self.cast<ScanMessage&>();
  if (message.scan.points.empty()) return py::array_t<T>(shape);
  char* base = reinterpret_cast<char*>(message.scan.points.data()) + offset_bytes;
  return py::array_t<T>(shape, strides, reinterpret_cast<T*>(base), self);
}

template <class Member>
std::size_t OffsetOf(Member ScanPoint::*member) {
  const ScanPoint p;
  return static_cast<std::size_t>(reinterpret_cast<const char*>(&(p.*member)) -
                                  reinterpret_cast<const char*>(&p));
}

py::array ScanPoints(py::object self) {
  const auto n = static_cast<py::ssize_t>(self.cast<ScanMessage&>().scan.points.size());
  return PointColumn<float>(self, OffsetOf(&ScanPoint::position_lidar), {n, 3},
                            {sizeof(ScanPoint), sizeof(float)});
}

template <class T, class Member>
py::array ScanColumn(py::object self, Member ScanPoint::*member) {
  const auto n = static_cast<py::ssize_t>(self.cast<ScanMessage&>().scan.points.size());
  return PointColumn<T>(self, OffsetOf(member), {n}, {sizeof(ScanPoint)});
}

py::array_t<double> PointTimes(const ScanMessage& message) {
  std::vector<double> times;
  times.reserve(message.scan.points.size());
  for (const ScanPoint& p : message.scan.points) times.push_back(p.offset_ns / 1e9);
  return ArrayFromVector(std::move(times));
}

py::array_t<double> Vector(const Eigen::Vector3d& v) {
  return py::array_t<double>(3, v.data());
}

class LogReaderHandle {
 public:
  LogReaderHandle(const std::string& path, const ConfigHandle& config) : path_(path) {
    reader_ = ReadingFiles({path}, [&] { return logs::OpenLog(path, config.config.LogOptions()); });
  }

  py::object Next() {
    logs::LogMessage message;
    bool more = false;
    {
      py::gil_scoped_release release;
      more = ReadingFiles({}, [&] { return reader_->Next(&message); });
    }
    if (!more) throw py::stop_iteration();
    if (message.kind == logs::LogMessage::Kind::kImu) return py::cast(ImuMessage{message.imu});
    return py::cast(ScanMessage{std::move(message.scan)});
  }

  py::dict Counters() const {
    const logs::LogReadCounters& c = reader_->counters();
    py::dict out;
    out["imu_messages"] = c.imu_messages;
    out["scan_messages"] = c.scan_messages;
    out["dropped_non_finite_points"] = c.dropped_non_finite_points;
    out["dropped_non_finite_imu"] = c.dropped_non_finite_imu;
    out["empty_scans"] = c.empty_scans;
    return out;
  }

  std::string TimeConvention() const { return logs::ToString(reader_->time_convention()); }

  py::object Recovery() const {
    const logs::LogRecovery* r = reader_->recovery();
    return r == nullptr ? py::none() : py::cast(r->Summary());
  }

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::unique_ptr<logs::LogReader> reader_;
};

void BindMessages(py::module_& m) {
  py::class_<ImuMessage>(m, "ImuSample", "One IMU sample of a log (IMU frame).")
      .def_property_readonly("t_ns", [](const ImuMessage& i) { return i.sample.t_ns; },
                             "stamp, ns")
      .def_property_readonly("t_s", [](const ImuMessage& i) { return i.sample.t_ns / 1e9; },
                             "stamp, s")
      .def_property_readonly("accel", [](const ImuMessage& i) { return Vector(i.sample.accel_imu); },
                             "specific force, m/s^2 (after imu.accel_scale)")
      .def_property_readonly("gyro", [](const ImuMessage& i) { return Vector(i.sample.gyro_imu); },
                             "angular rate, rad/s")
      .def("__repr__", [](const ImuMessage& i) {
        return "<hylo.ImuSample t_s=" + std::to_string(i.sample.t_ns / 1e9) + ">";
      });
  py::class_<ScanMessage>(m, "Scan",
                          "One lidar scan of a log. points, offsets_ns, intensity and ring are "
                          "views into the scan (no copy); point_times is computed.")
      .def_property_readonly("t_ns", [](const ScanMessage& s) { return s.scan.t_ns; },
                             "time of the first return, ns")
      .def_property_readonly("t_s", [](const ScanMessage& s) { return s.scan.t_ns / 1e9; },
                             "time of the first return, s")
      .def_property_readonly("end_t_s", [](const ScanMessage& s) { return s.scan.end_t_ns / 1e9; },
                             "time of the last return, s")
      .def_property_readonly("frame_id", [](const ScanMessage& s) { return s.scan.frame_id; })
      .def_property_readonly("points", &ScanPoints, "(N, 3) float32, lidar frame, m (a view)")
      .def_property_readonly("offsets_ns",
                             [](py::object self) {
                               return ScanColumn<int32_t>(self, &ScanPoint::offset_ns);
                             },
                             "(N,) int32: each return's time after t_ns, ns (a view)")
      .def_property_readonly("intensity",
                             [](py::object self) {
                               return ScanColumn<float>(self, &ScanPoint::intensity);
                             },
                             "(N,) float32, driver units (a view)")
      .def_property_readonly("ring",
                             [](py::object self) {
                               return ScanColumn<uint16_t>(self, &ScanPoint::ring);
                             },
                             "(N,) uint16 laser index (a view)")
      .def_property_readonly("point_times", &PointTimes,
                             "(N,) float64: each return's time after t_s, s")
      .def("__len__", [](const ScanMessage& s) { return s.scan.points.size(); })
      .def("__repr__", [](const ScanMessage& s) {
        return "<hylo.Scan t_s=" + std::to_string(s.scan.t_ns / 1e9) + " points=" +
               std::to_string(s.scan.points.size()) + ">";
      });
}

}  // namespace

void BindLogs(py::module_& m) {
  BindMessages(m);
  py::class_<LogReaderHandle>(m, "LogReader",
                              "A ROS1 bag or scan folder, message by message in the log's "
                              "order: hylo.ImuSample and hylo.Scan (use hylo.read_log).")
      .def(py::init<const std::string&, const ConfigHandle&>(), py::arg("path"),
           py::arg("config"))
      .def("__iter__", [](py::object self) { return self; })
      .def("__next__", &LogReaderHandle::Next)
      .def_property_readonly("counters", &LogReaderHandle::Counters,
                             "messages read and dropped so far (NaN/inf points and samples)")
      .def_property_readonly("time_convention", &LogReaderHandle::TimeConvention,
                             "the per-point time convention in use (after detection)")
      .def_property_readonly("recovery", &LogReaderHandle::Recovery,
                             "None, or what a damaged log still gave (one line)")
      .def_property_readonly("path", &LogReaderHandle::path);
}

}  // namespace hylo::python
