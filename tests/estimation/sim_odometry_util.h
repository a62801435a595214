#pragma once
// Runs the odometry pipeline on a simulated session held in memory and scores it against
// the simulator's ground truth. Shared by the integration test and the odometry benchmark.

#include <Eigen/Geometry>
#include <vector>

#include "hylo/odometry/odometry_pipeline.h"
#include "hylo/run/session.h"
#include "hylo/evaluation/trajectory_metrics.h"
#include "hylo/sim/simulator.h"

namespace hylo::testing {

/// Pipeline settings matching the simulator's sensors (extrinsic, IMU noise, gravity).
inline odometry::OdometryPipelineOptions PipelineOptionsFor(const sim::SimulationOptions& s) {
  odometry::OdometryPipelineOptions o;
  o.imu.gravity_mps2 = s.imu.gravity_mps2;
  o.imu.noise.accel_noise_density = s.imu.accel_noise_density;
  o.imu.noise.gyro_noise_density = s.imu.gyro_noise_density;
  o.imu.noise.accel_bias_random_walk = s.imu.accel_bias_random_walk;
  o.imu.noise.gyro_bias_random_walk = s.imu.gyro_bias_random_walk;
  const Eigen::Isometry3d& T = s.lidar.T_imu_lidar;
  o.T_imu_lidar = lie::SE3d(lie::SO3d::FromMatrix(T.linear()), T.translation());
  o.preprocess.min_range_m = static_cast<float>(s.lidar.min_range_m);
  o.preprocess.max_range_m = static_cast<float>(s.lidar.max_range_m);
  return o;
}

struct SimRun {
  std::vector<odometry::ScanResult> results;
  std::vector<evaluation::TimedPose> estimate;       ///< finalized T_map_imu per scan end
  std::vector<evaluation::TimedPose> live_estimate;  ///< live T_map_imu per scan end
  std::vector<evaluation::TimedPose> reference;      ///< true T_map_imu at the IMU rate
  evaluation::AteResult ate;       ///< of the finalized states (the trajectory a run writes)
  evaluation::AteResult live_ate;  ///< of the live states (what odometry published)
  odometry::PipelineCounters counters;
  std::size_t map_points = 0;
  bool failed = false;
  std::string message;
};

/// Streams a session from the simulator straight into a session of the pipeline (nothing but
/// the truth is kept in memory), in the simulator's arrival order, and scores the trajectory.
class PipelineSink : public sim::SessionSink {
 public:
  explicit PipelineSink(const odometry::OdometryPipelineOptions& options)
      : session_(options, run::SessionKeeps{true, false}) {}
  void OnImu(const ImuSample& s) override { session_.AddImu(s); }
  void OnScan(const LidarScan& s) override { session_.AddScan(s); }
  void OnTruth(const sim::TruthSample& t) override {
    run_.reference.push_back({t.t_ns, t.T_map_imu});
  }
  SimRun Finish() {
    session_.Finish();
    const odometry::OdometryPipeline& pipeline = session_.pipeline();
    run_.results = session_.results();
    for (const estimation::NavState& x : session_.finalized()) {
      run_.estimate.push_back({x.t_ns, Eigen::Isometry3d(x.T_map_imu().Matrix())});
    }
    run_.failed = session_.failed();
    run_.message = pipeline.message();
    run_.counters = pipeline.counters();
    run_.map_points = pipeline.map().Size();
    for (const odometry::ScanResult& r : run_.results) {
      run_.live_estimate.push_back({r.t_ns, Eigen::Isometry3d(r.state.T_map_imu().Matrix())});
    }
    run_.ate = evaluation::ComputeAte(run_.estimate, run_.reference);
    run_.live_ate = evaluation::ComputeAte(run_.live_estimate, run_.reference);
    return std::move(run_);
  }
  const odometry::OdometryPipeline& pipeline() const { return session_.pipeline(); }

 private:
  run::Session session_;
  SimRun run_;
};

/// Simulates session `session` of the site built from `sim_options` and runs the pipeline.
inline SimRun RunSimulatedSession(const sim::SimulationOptions& sim_options,
                                  sim::SessionId session,
                                  const odometry::OdometryPipelineOptions& options,
                                  sim::SessionSummary* summary = nullptr) {
  const sim::Site site = sim::BuildSite(sim_options.seed, sim_options.terrain);
  const sim::SessionSimulator simulator(sim_options, site, session);
  PipelineSink sink(options);
  const sim::SessionSummary s = simulator.Run(&sink);
  if (summary != nullptr) *summary = s;
  return sink.Finish();
}

}  // namespace hylo::testing
