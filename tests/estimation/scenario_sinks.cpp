#include "estimation/scenario_sinks.h"

#include <algorithm>
#include <cmath>

#include "hylo/sim/random.h"

namespace hylo::testing {

void Tee::OnImu(const ImuSample& s) {
  for (auto* sink : sinks_) sink->OnImu(s);
}

void Tee::OnScan(const LidarScan& s) {
  for (auto* sink : sinks_) sink->OnScan(s);
}

void Tee::OnTruth(const sim::TruthSample& t) {
  for (auto* sink : sinks_) sink->OnTruth(t);
}

void TruePoseMap::OnScan(const LidarScan& scan) {
  constexpr int64_t kBucketNs = 20'000;
  PointCloud points;
  points.reserve(scan.points.size());
  int64_t bucket = -1;
  Eigen::Isometry3d T_map_lidar = Eigen::Isometry3d::Identity();
  for (const ScanPoint& p : scan.points) {
    if (p.offset_ns / kBucketNs != bucket) {
      bucket = p.offset_ns / kBucketNs;
      T_map_lidar = simulator_.LidarPoseAt(scan.t_ns + bucket * kBucketNs + kBucketNs / 2);
    }
    points.push_back((T_map_lidar * p.position_lidar.cast<double>()).cast<float>());
  }
  sampler_.Add(points);
}

std::vector<Eigen::Vector3d> TruePoseMap::PointsWorld() const {
  std::vector<Eigen::Vector3d> world;
  world.reserve(points().size());
  for (const Eigen::Vector3f& p : points()) world.push_back(p.cast<double>());
  return world;
}

Eigen::Isometry3d StartGuess(const sim::Scenario& scenario, const Eigen::Isometry3d& truth_start) {
  constexpr double kDeg = M_PI / 180.0;
  sim::Rng rng = sim::Rng::Derive(scenario.number, 0x9e55);
  const double distance = rng.Uniform(0.5, 1.5), heading = rng.Uniform(0.0, 2.0 * M_PI);
  const double yaw = (rng.Uniform() < 0.5 ? -1.0 : 1.0) * rng.Uniform(3.0, 10.0) * kDeg;
  Eigen::Isometry3d guess = truth_start;
  guess.translation() += distance * Eigen::Vector3d(std::cos(heading), std::sin(heading), 0.0);
  guess.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * guess.linear();
  return guess;
}

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * (v.size() - 1) + 0.5))];
}

}  // namespace hylo::testing
