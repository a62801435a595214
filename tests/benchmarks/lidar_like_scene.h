#pragma once
// A generated, lidar-like point distribution for the map benchmarks: a vehicle drives along x
// through a substation-like site (undulating ground, rows of poles, two fences) and each scan
// samples those surfaces within sensor range, denser near the sensor, with range noise.
// Fixed seeds: the same arguments always give the same points.

#include <Eigen/Core>
#include <cstdint>
#include <random>

#include "hylo/common/point_types.h"

namespace hylo::benchmarks {

class LidarLikeScene {
 public:
  struct Options {
    float speed_m_per_step = 1.0f;  ///< sensor travel per scan, m
    float range_m = 40.f;           ///< sensor range, m
    float noise_m = 0.02f;          ///< Gaussian noise on every coordinate, m (1 sigma)
    uint32_t seed = 42;             ///< random seed
  };

  explicit LidarLikeScene(Options options) : options_(options), rng_(options.seed) {}

  /// Sensor position at scan `step`, m (world frame, z up).
  Eigen::Vector3f SensorAt(int step) const;

  /// `n` world points seen from SensorAt(step).
  PointCloud Scan(int step, int n);

  /// `n` points spread over the stretch of site seen along steps [0, last_step].
  PointCloud Map(int last_step, int n);

 private:
  Eigen::Vector3f SampleAround(const Eigen::Vector3f& sensor);
  Eigen::Vector3f GroundPoint(const Eigen::Vector3f& sensor);
  Eigen::Vector3f PolePoint(const Eigen::Vector3f& sensor);
  Eigen::Vector3f FencePoint(const Eigen::Vector3f& sensor);

  Options options_;
  std::mt19937 rng_;
};

}  // namespace hylo::benchmarks
