#pragma once
// The recovery benchmark's cases: a localization drive that loses its data while moving, or
// whose log begins while it moves, drawn reproducibly on a randomized scenario. Each case is
// a sink that drops the messages its event cuts and hands the rest to a session of its own,
// so every case of a scenario runs from one simulation of the drive (a Tee).
//
// Kinds (the drive's truth decides where and for how long):
//   gap_all       IMU and lidar both cut while driving, for as long as the vehicle takes to
//                 travel a drawn distance (5-100 m); it reappears there, moving. The session
//                 starts normally from a guess (StartGuess) before the cut;
//   gap_lidar     the same with the lidar alone cut, the IMU running;
//   moving_start  the log begins while the vehicle drives at 0.5-3 m/s, without a guess (a
//                 global start).
// Every case reappears (begins) inside the fenced yard, where the prior map has something to
// find, and its data end `window_s` after that moment.

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "hylo/mapping/prior_map.h"
#include "hylo/odometry/odometry_pipeline.h"
#include "hylo/run/session.h"
#include "hylo/sim/scenario_simulator.h"

namespace hylo::testing {

enum class RecoveryKind { kGapAll, kGapLidar, kMovingStart };
/// "gap_all", "gap_lidar", "moving_start".
std::string ToString(RecoveryKind kind);
bool ParseRecoveryKind(const std::string& name, RecoveryKind* kind);
std::vector<RecoveryKind> AllRecoveryKinds();

/// A drive's truth, with the distance driven sampled every 50 ms: what cases are drawn on and
/// scored against. Stamps are the IMU's (true time), ns.
class DriveTruth {
 public:
  explicit DriveTruth(const sim::ScenarioSimulator& drive);
  /// T_world_imu (the scenario's map frame is the site's).
  Eigen::Isometry3d PoseAt(int64_t t_ns) const;
  /// Distance the vehicle drove from the drive's start to `t_ns`, m.
  double DistanceAt(int64_t t_ns) const;
  /// The first stamp by which the vehicle drove `distance_m` since the start (end_ns() if never).
  int64_t TimeAtDistance(double distance_m) const;
  /// The vehicle's speed over the 0.2 s around `t_ns`, m/s.
  double SpeedAt(int64_t t_ns) const;
  int64_t start_ns() const { return start_ns_; }
  int64_t end_ns() const { return end_ns_; }
  /// When the vehicle first moves (after the standstill), ns.
  int64_t motion_start_ns() const { return motion_start_ns_; }

 private:
  const sim::ScenarioSimulator& drive_;
  int64_t start_ns_, end_ns_, motion_start_ns_;
  std::vector<double> distance_m_;  // at start_ns_ + k * kStepNs
};

struct RecoveryCase {
  uint64_t scenario = 0;
  int index = 0;  ///< within the scenario
  RecoveryKind kind = RecoveryKind::kGapAll;
  /// Gaps: the first instant without data; moving start: the log's first instant, ns.
  int64_t cut_t_ns = 0;
  /// Gaps: the data's return; moving start: the same as cut_t_ns, ns.
  int64_t return_t_ns = 0;
  int64_t end_t_ns = 0;           ///< the case's data end here, ns
  double drawn_distance_m = 0.0;  ///< gaps: the distance drawn, m
  double distance_m = 0.0;        ///< gaps: driven during the gap (the drawn one, shortened
                                  ///< to what the drive allows), m
  double speed_mps = 0.0;         ///< true speed at the return (the log's start), m/s
};

struct RecoveryDrawOptions {
  int cases = 6;           ///< per scenario, the kinds in turn (offset by the scenario)
  uint64_t seed = 0;       ///< another seed, other cases on the same drives
  double window_s = 30.0;  ///< data after the return (the log's start), s
  double min_gap_m = 5.0;  ///< gaps: travel drawn uniformly in [min, max], m
  double max_gap_m = 100.0;
  double min_speed_mps = 0.5;  ///< moving start: true speed in [min, max], m/s
  double max_speed_mps = 3.0;
  double tracking_before_s = 3.0;  ///< gaps begin this long after the motion at the earliest,
                                   ///< s (the start from the guess is done by then)
};

/// Cases of every kind in turn on `truth` (the scenario's drive) inside a yard of
/// `yard_size_m` (site frame, from the origin). A case that finds no place after many draws
/// is left out (the list is then shorter).
std::vector<RecoveryCase> DrawRecoveryCases(uint64_t scenario, const DriveTruth& truth,
                                            const Eigen::Vector2d& yard_size_m,
                                            const RecoveryDrawOptions& options);

/// One case of `kind` whose cut (or log) begins `after_motion_s` after the motion starts, a gap
/// lasting `distance_m` of travel. False when the drive is too short for it.
bool PlaceRecoveryCase(RecoveryKind kind, double after_motion_s, double distance_m,
                       const DriveTruth& truth, const RecoveryDrawOptions& options,
                       RecoveryCase* out);

/// One case's session: the drive's data minus what the case cuts, localizing in `prior` from
/// `T_world_imu_guess` (none: a global start).
class RecoveryRun : public sim::SessionSink {
 public:
  /// `lidar_time_offset_ns`: the scenario's (lidar stamps = true time + offset), to tell which
  /// scans the cut covers.
  RecoveryRun(const RecoveryCase& recovery_case, const odometry::OdometryPipelineOptions& options,
              const mapping::PriorMap& prior,
              const std::optional<Eigen::Isometry3d>& T_world_imu_guess,
              int64_t lidar_time_offset_ns);
  void OnImu(const ImuSample& s) override;
  void OnScan(const LidarScan& s) override;
  void OnTruth(const sim::TruthSample&) override {}
  void Finish() { session_.Finish(); }

  const RecoveryCase& recovery_case() const { return case_; }
  const run::Session& session() const { return session_; }
  /// World position of the map frame's zero (the prior's origin), m.
  const Eigen::Vector3d& origin_world() const { return origin_world_; }

 private:
  // True when data spanning true times [from_ns, to_ns] reach the session.
  bool Kept(int64_t from_ns, int64_t to_ns, bool imu) const;

  RecoveryCase case_;
  run::Session session_;
  Eigen::Vector3d origin_world_;
  int64_t lidar_time_offset_ns_;
};

}  // namespace hylo::testing
