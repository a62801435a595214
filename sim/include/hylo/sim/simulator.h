#pragma once
// Library entry point: simulate a session of the substation, streaming its measurements to
// a sink (in memory for tests, to files for `hylo simulate`, see session_writer.h).

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "hylo/common/sensor_data.h"
#include "hylo/sim/imu_model.h"
#include "hylo/sim/lidar_model.h"
#include "hylo/sim/site_layout.h"
#include "hylo/sim/terrain.h"
#include "hylo/sim/trajectory.h"
#include "hylo/sim/world.h"

namespace hylo::sim {

struct SimulationOptions {
  uint64_t seed = 1;            ///< everything random derives from this
  double duration_a_s = 180.0;  ///< session A length, s (>= 120 s covers >= 100 m of route)
  double duration_b_s = 150.0;  ///< session B length, s
  int64_t start_a_ns = 1'700'000'000'000'000'000;  ///< stamp of session A's start, ns
  int64_t start_b_ns = 1'700'086'400'000'000'000;  ///< session B's start (a day later), ns
  double index_cell_m = 2.0;                       ///< ray-casting index cell, m
  TerrainOptions terrain;
  TrajectoryOptions trajectory;
  LidarOptions lidar;
  ImuOptions imu;

  bool IsValid(std::string* why) const;
  double DurationS(SessionId session) const {
    return session == SessionId::kA ? duration_a_s : duration_b_s;
  }
  int64_t StartNs(SessionId session) const {
    return session == SessionId::kA ? start_a_ns : start_b_ns;
  }
  /// Short, coarse settings for unit tests (8 s, 1 deg columns, 0.4 m terrain).
  static SimulationOptions Fast(double duration_s = 8.0);
};

/// One true pose of the IMU frame, at the IMU rate.
struct TruthSample {
  int64_t t_ns = 0;
  Eigen::Isometry3d T_map_imu = Eigen::Isometry3d::Identity();
  Eigen::Vector3d velocity_map = Eigen::Vector3d::Zero();  ///< m/s

  /// The truth of a motion's state at `t_ns`.
  static TruthSample Of(int64_t t_ns, const KinematicState& state) {
    TruthSample truth;
    truth.t_ns = t_ns;
    truth.T_map_imu.linear() = state.R_map_imu;
    truth.T_map_imu.translation() = state.position_map;
    truth.velocity_map = state.velocity_map;
    return truth;
  }
};

/// Receives a session's data in arrival order (a scan after the IMU samples before its end).
class SessionSink {
 public:
  virtual ~SessionSink() = default;
  virtual void OnImu(const ImuSample& sample) = 0;
  virtual void OnScan(const LidarScan& scan) = 0;
  virtual void OnTruth(const TruthSample& truth) = 0;
};

/// Keeps everything in memory (short sessions only: ~10 MB per simulated second).
struct SessionRecording : SessionSink {
  std::vector<ImuSample> imu;
  std::vector<LidarScan> scans;
  std::vector<TruthSample> truth;
  void OnImu(const ImuSample& s) override { imu.push_back(s); }
  void OnScan(const LidarScan& s) override { scans.push_back(s); }
  void OnTruth(const TruthSample& t) override { truth.push_back(t); }
};

struct SessionSummary {
  SessionId session = SessionId::kA;
  std::size_t imu_samples = 0;
  std::size_t scans = 0;
  std::size_t points = 0;
  double duration_s = 0.0;
  double path_length_m = 0.0;                                    ///< distance driven, m
  double max_tilt_deg = 0.0;                                     ///< max |roll| or |pitch|, deg
  Eigen::Vector3d initial_accel_bias = Eigen::Vector3d::Zero();  ///< m/s^2
  Eigen::Vector3d initial_gyro_bias = Eigen::Vector3d::Zero();   ///< rad/s
  double elapsed_s = 0.0;                                        ///< wall time of the simulation, s
  double cpu_s = 0.0;  ///< process CPU time of the simulation, s
};

/// Everything one session needs, built once: the site's world for that session and the
/// vehicle's trajectory.
class SessionSimulator {
 public:
  SessionSimulator(const SimulationOptions& options, const Site& site, SessionId session);

  /// Runs the session; `progress(done, total)` is called after each scan (may be empty).
  SessionSummary Run(SessionSink* sink,
                     const std::function<void(std::size_t, std::size_t)>& progress = {}) const;

  const World& world() const { return *world_; }
  const Trajectory& trajectory() const { return trajectory_; }
  const LidarSimulator& lidar() const { return *lidar_; }
  int64_t start_ns() const { return options_.StartNs(session_); }

 private:
  SimulationOptions options_;
  SessionId session_;
  std::unique_ptr<World> world_;
  Trajectory trajectory_;
  std::unique_ptr<LidarSimulator> lidar_;
};

}  // namespace hylo::sim
