#pragma once
// A scenario's sessions: the vehicle's drive (trajectory.h) with engine vibration on top and
// the IMU mounted in any orientation; an IMU with scale and axis errors and a bias that
// wanders (Gauss-Markov) on top of imu_model.h's; a lidar firing a ScanPattern, stamped on
// its own clock. Data go to the same SessionSink as the fixed site's sessions.

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "hylo/sim/scenario.h"
#include "hylo/sim/simulator.h"

namespace hylo::sim {

/// The IMU's true motion: the vehicle's trajectory, vibration added, the IMU's mounting.
class VehicleMotion {
 public:
  /// Vibration fades in from `vibration_start_ns` (since the session start).
  VehicleMotion(Trajectory vehicle, const Vibration& vibration, int64_t vibration_start_ns,
                const Eigen::Matrix3d& R_vehicle_imu);

  /// The IMU's state at `t_ns` since the session start (exact derivatives).
  KinematicState StateAt(int64_t t_ns) const;
  /// T_map_imu at `t_ns`.
  Eigen::Isometry3d PoseAt(int64_t t_ns) const;
  const Trajectory& vehicle() const { return vehicle_; }
  const Eigen::Matrix3d& R_vehicle_imu() const { return R_vehicle_imu_; }

 private:
  Trajectory vehicle_;
  Vibration vibration_;
  double vibration_start_s_;
  Eigen::Matrix3d R_vehicle_imu_;
};

/// imu_model.h's IMU plus scale and axis errors (on the true signal) and a first-order
/// Gauss-Markov bias (bias instability), each axis independent.
class ScenarioImu {
 public:
  ScenarioImu(const ImuGrade& grade, uint64_t seed);
  ImuSample Measure(const KinematicState& state, int64_t t_ns);
  const ImuSimulator& base() const { return base_; }

 private:
  ImuGrade grade_;
  ImuSimulator base_;
  Rng rng_;
  Eigen::Matrix3d accel_errors_, gyro_errors_;  // (I + scale + misalignment) - I
  Eigen::Vector3d accel_wander_ = Eigen::Vector3d::Zero(), gyro_wander_ = Eigen::Vector3d::Zero();
};

/// Ray casts a ScanPattern from the moving lidar. Scan `index` covers true times
/// [index, index + 1) periods since the session start and is stamped on the lidar clock
/// (true time + the clock offset).
class PatternLidar {
 public:
  PatternLidar(const SensorSpec& spec, const World& world, const VehicleMotion& motion,
               const Eigen::Isometry3d& T_imu_lidar, int64_t time_offset_ns, uint64_t seed);
  LidarScan Scan(int64_t index, int64_t session_start_ns) const;
  int64_t period_ns() const { return pattern_.period_ns(); }
  const ScanPattern& pattern() const { return pattern_; }

 private:
  SensorSpec spec_;
  ScanPattern pattern_;
  const World& world_;
  const VehicleMotion& motion_;
  Eigen::Isometry3d T_imu_lidar_;
  int64_t time_offset_ns_;
  uint64_t seed_;
};

/// One drive of a scenario: session A maps (from outside the fence, the spur if any),
/// session B localizes over the yard's lanes. The drive lasts until the route's end or the
/// scenario's drive cap, after the standstill.
class ScenarioSimulator {
 public:
  ScenarioSimulator(const Scenario& scenario, const Site& site, SessionId session);

  SessionSummary Run(SessionSink* sink,
                     const std::function<void(std::size_t, std::size_t)>& progress = {}) const;

  const World& world() const { return *world_; }
  const VehicleMotion& motion() const { return *motion_; }
  int64_t start_ns() const { return start_ns_; }
  int64_t duration_ns() const { return motion_->vehicle().duration_ns(); }
  /// True T_map_lidar of a return stamped `t_ns` on the lidar clock (offset removed).
  Eigen::Isometry3d LidarPoseAt(int64_t lidar_stamp_ns) const;

 private:
  Scenario scenario_;
  SessionId session_;
  int64_t start_ns_ = 0;
  std::unique_ptr<World> world_;
  std::unique_ptr<VehicleMotion> motion_;
  std::unique_ptr<PatternLidar> lidar_;
};

/// Seconds of session `session`: standstill, the drive (capped), one second at the end.
double ScenarioDurationS(const Scenario& scenario, const Site& site, SessionId session);

}  // namespace hylo::sim
