// Session simulation: IMU samples at the IMU rate, scans emitted once their last column has
// been fired, ground truth at every IMU stamp.
#include "hylo/sim/simulator.h"

#include <chrono>
#include <cmath>
#include <ctime>
#include <sstream>
#include <stdexcept>

#include "hylo/common/check.h"
#include "hylo/common/time.h"

namespace hylo::sim {
namespace {
uint64_t SessionTag(SessionId session) { return session == SessionId::kA ? 0xA : 0xB; }
}  // namespace

bool SimulationOptions::IsValid(std::string* why) const {
  std::string sub;
  std::ostringstream os;
  if (!(duration_a_s > 0.0 && duration_b_s > 0.0))
    os << "durations must be > 0 s";
  else if (!(index_cell_m > 0.0))
    os << "index_cell_m = " << index_cell_m << " must be > 0";
  else if (!terrain.IsValid(&sub))
    os << "terrain." << sub;
  else if (!trajectory.IsValid(&sub))
    os << "trajectory." << sub;
  else if (!lidar.IsValid(&sub))
    os << "lidar." << sub;
  else if (!imu.IsValid(&sub))
    os << "imu." << sub;
  if (why != nullptr) *why = os.str();
  return os.str().empty();
}

SimulationOptions SimulationOptions::Fast(double duration_s) {
  SimulationOptions options;
  options.duration_a_s = options.duration_b_s = duration_s;
  options.lidar.column_deg = 1.0;
  options.terrain.resolution_m = 0.4;
  return options;
}

SessionSimulator::SessionSimulator(const SimulationOptions& options, const Site& site,
                                   SessionId session)
    : options_(options), session_(session) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("SimulationOptions: " + why);
  world_ =
      std::make_unique<World>(site.terrain, SessionPrimitives(site, session), options.index_cell_m);
  Rng rng = Rng::Derive(options.seed, SessionTag(session), 0x7a1);
  trajectory_ =
      Trajectory::FromRoute(session == SessionId::kA ? site.route_a : site.route_b, *site.terrain,
                            options.trajectory, SecondsToNanos(options.DurationS(session)), &rng);
  lidar_ = std::make_unique<LidarSimulator>(
      options.lidar, *world_, trajectory_,
      Rng::Derive(options.seed, SessionTag(session), 0x1d4).NextU64());
}

SessionSummary SessionSimulator::Run(
    SessionSink* sink, const std::function<void(std::size_t, std::size_t)>& progress) const {
  HYLO_CHECK(sink != nullptr, "a sink is required");
  const auto wall_start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  SessionSummary summary;
  summary.session = session_;
  summary.duration_s = NanosToSeconds(trajectory_.duration_ns());
  summary.path_length_m = trajectory_.path_length_m();
  summary.max_tilt_deg = trajectory_.max_tilt_rad() * 180.0 / M_PI;
  ImuSimulator imu(options_.imu, Rng::Derive(options_.seed, SessionTag(session_), 0x1e0));
  summary.initial_accel_bias = imu.accel_bias();
  summary.initial_gyro_bias = imu.gyro_bias();
  const int64_t imu_period = options_.imu.period_ns();
  const int64_t scan_period = lidar_->period_ns();
  const int64_t duration = trajectory_.duration_ns();
  const std::size_t scans = static_cast<std::size_t>(duration / scan_period);
  const int64_t t0 = start_ns();
  std::size_t next_scan = 0;
  for (int64_t t = 0; t <= duration; t += imu_period) {
    // A scan is complete (and "arrives") once its period has elapsed.
    while (next_scan < scans && static_cast<int64_t>(next_scan + 1) * scan_period <= t) {
      const LidarScan scan = lidar_->Scan(static_cast<int>(next_scan), t0);
      summary.points += scan.points.size();
      sink->OnScan(scan);
      ++next_scan;
      if (progress) progress(next_scan, scans);
    }
    const KinematicState state = trajectory_.StateAt(t);
    sink->OnImu(imu.Measure(state, t0 + t));
    sink->OnTruth(TruthSample::Of(t0 + t, state));
    ++summary.imu_samples;
  }
  for (; next_scan < scans; ++next_scan) {  // only when the IMU period does not divide
    const LidarScan scan = lidar_->Scan(static_cast<int>(next_scan), t0);
    summary.points += scan.points.size();
    sink->OnScan(scan);
  }
  summary.scans = next_scan;
  summary.cpu_s = double(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  summary.elapsed_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return summary;
}

}  // namespace hylo::sim
