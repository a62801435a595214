#pragma once
// Pieces every run of a randomized scenario shares (the scenario matrix, the recovery
// benchmark and their tests): one simulation feeding several sinks, the truth of a drive, the
// prior map made of the mapping drive's scans at their true poses, and the guess a
// localization drive starts from.

#include <Eigen/Geometry>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/evaluation/trajectory_metrics.h"
#include "hylo/registration/voxel_filter.h"
#include "hylo/sim/scenario.h"
#include "hylo/sim/scenario_simulator.h"

namespace hylo::testing {

/// Hands every measurement to several sinks, in the order they were added.
class Tee : public sim::SessionSink {
 public:
  void Add(sim::SessionSink* sink) { sinks_.push_back(sink); }
  void OnImu(const ImuSample& s) override;
  void OnScan(const LidarScan& s) override;
  void OnTruth(const sim::TruthSample& t) override;

 private:
  std::vector<sim::SessionSink*> sinks_;
};

/// The truth at every IMU stamp (T_map_imu; the scenario's map frame is the site's).
struct TruthTrack : sim::SessionSink {
  void OnImu(const ImuSample&) override {}
  void OnScan(const LidarScan&) override {}
  void OnTruth(const sim::TruthSample& t) override { poses.push_back({t.t_ns, t.T_map_imu}); }
  std::vector<evaluation::TimedPose> poses;
};

/// The mapping drive's scans placed at their true poses (each return at its own time, to
/// 10 us), uniformly sampled: a prior map with the sensor's noise and no SLAM drift.
class TruePoseMap : public sim::SessionSink {
 public:
  TruePoseMap(const sim::ScenarioSimulator& simulator, double voxel_m)
      : simulator_(simulator), sampler_(static_cast<float>(voxel_m)) {}
  void OnImu(const ImuSample&) override {}
  void OnTruth(const sim::TruthSample&) override {}
  void OnScan(const LidarScan& scan) override;
  const PointCloud& points() const { return sampler_.points(); }
  /// The same points in double, world (= site) frame, m.
  std::vector<Eigen::Vector3d> PointsWorld() const;

 private:
  const sim::ScenarioSimulator& simulator_;
  registration::UniformSampler sampler_;
};

/// The localization drive's true start pose `truth_start` off by 0.5-1.5 m and 3-10 deg of
/// yaw, drawn from the scenario's number.
Eigen::Isometry3d StartGuess(const sim::Scenario& scenario, const Eigen::Isometry3d& truth_start);

/// The q-quantile (0..1) of `v`, nearest rank; 0 when empty.
double Percentile(std::vector<double> v, double q);

}  // namespace hylo::testing
