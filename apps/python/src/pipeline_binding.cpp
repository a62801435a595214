// hylo.Pipeline: data from memory through run::Session, scan by scan, for data that is not in
// a file (a simulator, a live driver, arrays from a notebook). The session is the one the
// command line drives, so the same measurements give the same states.
#include <pybind11/stl.h>

#include <mutex>
#include <optional>

#include "arrays.h"
#include "bindings.h"
#include "config_binding.h"
#include "errors.h"
#include "guess.h"
#include "hylo/run/run_log.h"
#include "hylo/lie/isometry.h"
#include "hylo/run/session.h"
#include "log_messages.h"
#include "scan_from_arrays.h"

namespace hylo::python {
namespace {

// What `state` reports of the newest processed scan.
struct LiveState {
  int64_t t_ns = 0;
  estimation::NavState state;
  estimation::PoseCovariance6 covariance = estimation::PoseCovariance6::Zero();
  Eigen::Vector3d angular_velocity_imu = Eigen::Vector3d::Zero();
  bool health_good = false;
  odometry::PoseStatus pose_status = odometry::PoseStatus::kValid;
};

const char* StatusName(odometry::OdometryPipeline::Status status) {
  using Status = odometry::OdometryPipeline::Status;
  switch (status) {
    case Status::kInitializing: return "initializing";
    case Status::kRunning: return "running";
    case Status::kLost: return "lost";
    case Status::kFailed: return "failed";
  }
  return "unknown";
}

run::SessionKeeps Keeps(bool keep_history) {
  return run::SessionKeeps{keep_history, keep_history, keep_history};
}

class PipelineHandle {
 public:
  PipelineHandle(const ConfigHandle& config, const py::handle& prior_map, const py::handle& guess,
                 bool keep_history)
      : config_(config.config), session_(config_.PipelineOptions(), Keeps(keep_history)) {
    session_.OnResult([this](const odometry::ScanResult& r) {
      live_ = LiveState{r.t_ns, r.state, r.pose_covariance, r.angular_velocity_imu,
                        r.health.good, r.pose_status};
    });
    if (prior_map.is_none()) {
      if (!guess.is_none()) throw std::invalid_argument("guess: needs a prior_map");
      return;
    }
    const std::optional<Eigen::Isometry3d> start = ResolveGuess(guess, &config_);
    if (py::isinstance<py::str>(prior_map) || py::hasattr(prior_map, "__fspath__")) {
      const std::string path = py::str(py::module_::import("os").attr("fspath")(prior_map));
      py::gil_scoped_release release;
      ReadingFiles({path}, [&] { session_.LoadPriorMap(path, config_.prior_map, start); });
      return;
    }
    const std::vector<Eigen::Vector3d> points = PointsFromArray(prior_map, "prior_map");
    py::gil_scoped_release release;
    session_.SetPriorMap(points, config_.prior_map, start);
  }

  std::size_t AddImu(const py::handle& t_s, const py::handle& accel, const py::handle& gyro,
                     const py::handle& t_ns) {
    std::vector<ImuSample> samples;
    if (py::isinstance<ImuMessage>(t_s)) {
      samples.push_back(t_s.cast<const ImuMessage&>().sample);
    } else {
      samples = ImuFromArrays(t_s, accel, gyro, t_ns);
    }
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    const std::size_t before = session_.scans_processed();
    for (const ImuSample& s : samples) session_.AddImu(s);
    ThrowIfFailed();
    return session_.scans_processed() - before;
  }

  std::size_t AddScan(const py::handle& t_s, const py::handle& points,
                      const py::handle& point_times, const py::handle& intensity,
                      const py::handle& ring, const py::handle& t_ns) {
    LidarScan scan;
    if (py::isinstance<ScanMessage>(t_s)) {
      scan = t_s.cast<const ScanMessage&>().scan;
    } else {
      scan = ScanFromArrays(StampNs(t_s, t_ns, "t_s"), points, point_times, intensity, ring);
    }
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    const std::size_t before = session_.scans_processed();
    session_.AddScan(std::move(scan));
    ThrowIfFailed();
    return session_.scans_processed() - before;
  }

  std::size_t Finish() {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    const std::size_t before = session_.scans_processed();
    session_.Finish();
    ThrowIfFailed();
    return session_.scans_processed() - before;
  }

  py::dict State() {
    std::optional<LiveState> live;
    std::string status;
    Eigen::Vector3d origin;
    {
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(mutex_);
      live = live_;
      status = StatusName(session_.pipeline().status());
      origin = session_.origin_world();
    }
    py::dict out;
    out["status"] = status;
    // Only a pose placed in the map is valid: not a lost vehicle's, nor one of a search's
    // provisional frame (pose_status says which).
    out["valid"] = live.has_value() && status == "running" &&
                   live->pose_status == odometry::PoseStatus::kValid;
    if (!live) return out;
    out["pose_status"] = odometry::ToString(live->pose_status);
    Eigen::Isometry3d T_world_imu = lie::ToIsometry(live->state.T_map_imu());
    T_world_imu.translation() += origin;
    out["t_ns"] = live->t_ns;
    out["pose"] = MatrixArray(T_world_imu);
    out["velocity"] = py::array_t<double>(3, live->state.v_map_imu.data());
    out["angular_velocity"] = py::array_t<double>(3, live->angular_velocity_imu.data());
    py::array_t<double> covariance({6, 6});
    Eigen::Map<Eigen::Matrix<double, 6, 6, Eigen::RowMajor>>(covariance.mutable_data()) =
        live->covariance;
    out["covariance"] = covariance;
    out["health_good"] = live->health_good;
    return out;
  }

  // Finalized (or live) states in the world frame so far, with their exact stamps.
  py::tuple Trajectory(bool live) {
    std::vector<io::StampedPose> poses;
    {
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(mutex_);
      poses = live ? session_.LiveTrajectory() : session_.Trajectory();
    }
    return py::make_tuple(TrajectoryArray(poses), StampsArray(poses));
  }

  py::array_t<double> Map(bool dense) {
    PointCloud points;
    Eigen::Vector3d origin;
    {
      py::gil_scoped_release release;
      std::lock_guard<std::mutex> lock(mutex_);
      points = dense ? session_.dense_map() : session_.pipeline().map().Flatten();
      origin = session_.origin_world();
    }
    return WorldArray(points, origin);
  }

  std::string SummaryJson() {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    const odometry::OdometryPipeline& pipeline = session_.pipeline();
    io::Json j;
    j["mode"] = session_.localizing() ? "localization" : "slam";
    j["backend"] = config_.BackendName();
    j["status"] = StatusName(pipeline.status());
    j["message"] = pipeline.message();
    j["scans_added"] = session_.scans_added();
    j["scans_processed"] = session_.scans_processed();
    j["counters"] = run::PipelineCountersJson(pipeline.counters());
    j["map_points"] = pipeline.map().Size();
    const Eigen::Vector3d& o = session_.origin_world();
    j["origin_world"] = io::Json::array({o.x(), o.y(), o.z()});
    return j.dump();
  }

  std::size_t scans_added() { return Locked([this] { return session_.scans_added(); }); }
  std::size_t scans_processed() { return Locked([this] { return session_.scans_processed(); }); }

 private:
  // Runs `read` under the lock, the GIL released first: a thread waiting for the lock must
  // not hold the GIL the working thread needs to return.
  template <class Read>
  auto Locked(Read&& read) -> decltype(read()) {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    return read();
  }

  // Called with the lock held: a failed pipeline takes no more data; say why.
  void ThrowIfFailed() const {
    if (session_.failed()) throw run::RunFailed(session_.pipeline().message());
  }

  std::mutex mutex_;
  config::RunConfig config_;
  run::Session session_;
  std::optional<LiveState> live_;
};

}  // namespace

void BindPipeline(py::module_& m) {
  const py::none none;
  py::class_<PipelineHandle>(m, "_Pipeline")
      .def(py::init<const ConfigHandle&, const py::handle&, const py::handle&, bool>(),
           py::arg("config"), py::arg("prior_map"), py::arg("guess"), py::arg("keep_history"))
      .def("add_imu", &PipelineHandle::AddImu, py::arg("t_s"), py::arg("accel") = none,
           py::arg("gyro") = none, py::kw_only(), py::arg("t_ns") = none)
      .def("add_scan", &PipelineHandle::AddScan, py::arg("t_s"), py::arg("points") = none,
           py::arg("point_times") = none, py::arg("intensity") = none, py::arg("ring") = none,
           py::kw_only(), py::arg("t_ns") = none)
      .def("_finish", &PipelineHandle::Finish)
      .def("_state", &PipelineHandle::State)
      .def("_trajectory", &PipelineHandle::Trajectory, py::arg("live"))
      .def("_map", &PipelineHandle::Map, py::arg("dense"))
      .def("_summary_json", &PipelineHandle::SummaryJson)
      .def_property_readonly("scans_added", &PipelineHandle::scans_added)
      .def_property_readonly("scans_processed", &PipelineHandle::scans_processed);
}

}  // namespace hylo::python
