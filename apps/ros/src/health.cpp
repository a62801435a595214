#include "health.h"

#include "hylo/common/time.h"
#include "hylo/io/json.h"
#include "hylo/run/run_log.h"

namespace hylo::rosnode {

std::string ToString(HealthState state) {
  switch (state) {
    case HealthState::kInitialising: return "initialising";
    case HealthState::kLocalized: return "localized";
    case HealthState::kLost: return "lost";
    case HealthState::kRelocalizing: return "relocalizing";
    case HealthState::kFailed: return "failed";
  }
  return "unknown";
}

HealthState StateOf(odometry::OdometryPipeline::Status status, bool relocalization_pending) {
  using Status = odometry::OdometryPipeline::Status;
  switch (status) {
    case Status::kInitializing: return HealthState::kInitialising;
    case Status::kFailed: return HealthState::kFailed;
    case Status::kLost:
      return relocalization_pending ? HealthState::kRelocalizing : HealthState::kLost;
    case Status::kRunning:
      return relocalization_pending ? HealthState::kRelocalizing : HealthState::kLocalized;
  }
  return HealthState::kFailed;
}

namespace {

io::Json InputJson(const InputCounters& c) {
  io::Json j;
  j["scans_received"] = c.scans_received;
  j["imu_received"] = c.imu_received;
  j["scans_out_of_order"] = c.scans_out_of_order;
  j["imu_out_of_order"] = c.imu_out_of_order;
  j["scans_dropped_full"] = c.scans_dropped_full;
  j["imu_dropped_full"] = c.imu_dropped_full;
  j["max_scans_waiting"] = c.max_scans_waiting;
  return j;
}


}  // namespace

std::string HealthJson(const HealthReport& report) {
  io::Json j;
  j["state"] = ToString(report.state);
  j["stamp_s"] = NanosToSeconds(report.t_ns);
  j["mode"] = report.localizing ? "localization" : "slam";
  j["backend"] = report.backend;
  j["fitness_m2"] = report.scan.fitness_m2;
  j["inlier_ratio"] = report.scan.inlier_ratio;
  j["matches"] = report.scan.num_matches;
  j["scan_good"] = report.scan.good;
  j["update_applied"] = report.update_applied;
  j["map_points"] = report.map_points;
  j["pipeline"] = run::PipelineCountersJson(report.pipeline);
  j["input"] = InputJson(report.input);
  j["last_event"] = report.last_event;
  j["message"] = report.message;
  return io::DumpJson(j, -1);
}

}  // namespace hylo::rosnode
