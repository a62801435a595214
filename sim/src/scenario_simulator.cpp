// A scenario's session: IMU samples at the IMU rate, scans once their last shot has been
// fired (stamped on the lidar clock), ground truth at every IMU stamp.
#include "hylo/sim/scenario_simulator.h"

#include <algorithm>
#include <chrono>
#include <ctime>

#include "hylo/common/check.h"
#include "hylo/common/time.h"
#include "route.h"

namespace hylo::sim {
namespace {

uint64_t SessionTag(SessionId session) { return session == SessionId::kA ? 0xA : 0xB; }

const std::vector<Eigen::Vector2d>& Route(const Site& site, SessionId session) {
  return session == SessionId::kA ? site.route_a : site.route_b;
}

// Motion starts two knots after the standstill (trajectory.cpp), and so does the vibration.
int64_t MotionStartNs(const TrajectoryOptions& options) {
  return SecondsToNanos(options.standstill_s + 2.0 * options.knot_spacing_s);
}

}  // namespace

double ScenarioDurationS(const Scenario& scenario, const Site& site, SessionId session) {
  const RoutePlan plan(Route(site, session), scenario.trajectory);
  const double cap = session == SessionId::kA ? scenario.max_drive_a_s : scenario.max_drive_b_s;
  return NanosToSeconds(MotionStartNs(scenario.trajectory)) + std::min(plan.duration_s(), cap) +
         1.0;
}

ScenarioSimulator::ScenarioSimulator(const Scenario& scenario, const Site& site, SessionId session)
    : scenario_(scenario), session_(session) {
  start_ns_ = session == SessionId::kA ? scenario.start_a_ns : scenario.start_b_ns;
  world_ = std::make_unique<World>(site.terrain, SessionPrimitives(site, session),
                                   scenario.index_cell_m);
  Rng rng = Rng::Derive(scenario.number, SessionTag(session), 0x7a1);
  Trajectory vehicle =
      Trajectory::FromRoute(Route(site, session), *site.terrain, scenario.trajectory,
                            SecondsToNanos(ScenarioDurationS(scenario, site, session)), &rng);
  motion_ =
      std::make_unique<VehicleMotion>(std::move(vehicle), scenario.vibration,
                                      MotionStartNs(scenario.trajectory), scenario.R_vehicle_imu);
  lidar_ = std::make_unique<PatternLidar>(
      scenario.lidar, *world_, *motion_, scenario.T_imu_lidar, scenario.lidar_time_offset_ns,
      Rng::Derive(scenario.number, SessionTag(session), 0x1d4).NextU64());
}

Eigen::Isometry3d ScenarioSimulator::LidarPoseAt(int64_t lidar_stamp_ns) const {
  const int64_t t = lidar_stamp_ns - scenario_.lidar_time_offset_ns - start_ns_;
  return motion_->PoseAt(t) * scenario_.T_imu_lidar;
}

SessionSummary ScenarioSimulator::Run(
    SessionSink* sink, const std::function<void(std::size_t, std::size_t)>& progress) const {
  HYLO_CHECK(sink != nullptr, "a sink is required");
  const auto wall_start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  const Trajectory& vehicle = motion_->vehicle();
  SessionSummary summary;
  summary.session = session_;
  summary.duration_s = NanosToSeconds(vehicle.duration_ns());
  summary.path_length_m = vehicle.path_length_m();
  summary.max_tilt_deg = vehicle.max_tilt_rad() * 180.0 / M_PI;
  ScenarioImu imu(scenario_.imu,
                  Rng::Derive(scenario_.number, SessionTag(session_), 0x1e0).NextU64());
  summary.initial_accel_bias = imu.base().accel_bias();
  summary.initial_gyro_bias = imu.base().gyro_bias();
  const int64_t imu_period = scenario_.imu.base.period_ns();
  const int64_t scan_period = lidar_->period_ns();
  const int64_t duration = vehicle.duration_ns();
  const std::size_t scans = static_cast<std::size_t>(duration / scan_period);
  std::size_t next_scan = 0;
  const auto emit_scan = [&] {
    const LidarScan scan = lidar_->Scan(static_cast<int64_t>(next_scan), start_ns_);
    summary.points += scan.points.size();
    sink->OnScan(scan);
    ++next_scan;
    if (progress) progress(next_scan, scans);
  };
  for (int64_t t = 0; t <= duration; t += imu_period) {
    // A scan arrives once its period has elapsed (true time).
    while (next_scan < scans && static_cast<int64_t>(next_scan + 1) * scan_period <= t) {
      emit_scan();
    }
    const KinematicState state = motion_->StateAt(t);
    sink->OnImu(imu.Measure(state, start_ns_ + t));
    sink->OnTruth(TruthSample::Of(start_ns_ + t, state));
    ++summary.imu_samples;
  }
  while (next_scan < scans) emit_scan();
  summary.scans = next_scan;
  summary.cpu_s = double(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  summary.elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return summary;
}

}  // namespace hylo::sim
