#include "lidar_like_scene.h"

#include <cmath>

namespace hylo::benchmarks {
namespace {
constexpr float kPi = 3.14159265f;
constexpr float kPoleSpacingX = 8.f;   // m between pole rows along the drive
constexpr float kPoleSpacingY = 10.f;  // m between poles across it
constexpr float kPoleRadius = 0.25f;   // m
constexpr float kPoleHeight = 6.f;     // m
constexpr float kFenceY = 35.f;        // fences at y = +-35 m
constexpr float kFenceHeight = 3.f;    // m

float GroundHeight(float x, float y) { return 0.4f * std::sin(0.13f * x) * std::cos(0.07f * y); }
}  // namespace

Eigen::Vector3f LidarLikeScene::SensorAt(int step) const {
  const float x = options_.speed_m_per_step * static_cast<float>(step);
  return {x, 8.f * std::sin(x / 150.f), GroundHeight(x, 0.f) + 1.8f};
}

PointCloud LidarLikeScene::Scan(int step, int n) {
  const Eigen::Vector3f sensor = SensorAt(step);
  PointCloud points;
  points.reserve(n);
  for (int i = 0; i < n; ++i) points.push_back(SampleAround(sensor));
  return points;
}

PointCloud LidarLikeScene::Map(int last_step, int n) {
  std::uniform_int_distribution<int> step(0, last_step);
  PointCloud points;
  points.reserve(n);
  for (int i = 0; i < n; ++i) points.push_back(SampleAround(SensorAt(step(rng_))));
  return points;
}

// Surface mix of a 16-beam scan in such a site: mostly ground, then poles, then fences.
Eigen::Vector3f LidarLikeScene::SampleAround(const Eigen::Vector3f& sensor) {
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::normal_distribution<float> noise(0.f, options_.noise_m);
  const float pick = u(rng_);
  Eigen::Vector3f p = pick < 0.55f   ? GroundPoint(sensor)
                      : pick < 0.85f ? PolePoint(sensor)
                                     : FencePoint(sensor);
  return p + Eigen::Vector3f(noise(rng_), noise(rng_), noise(rng_));
}

// Range uniform in [2, range]: returns are denser near the sensor, as with a spinning lidar.
Eigen::Vector3f LidarLikeScene::GroundPoint(const Eigen::Vector3f& sensor) {
  std::uniform_real_distribution<float> azimuth(-kPi, kPi);
  std::uniform_real_distribution<float> range(2.f, options_.range_m);
  const float a = azimuth(rng_);
  const float r = range(rng_);
  const float x = sensor.x() + r * std::cos(a);
  const float y = sensor.y() + r * std::sin(a);
  return {x, y, GroundHeight(x, y)};
}

Eigen::Vector3f LidarLikeScene::PolePoint(const Eigen::Vector3f& sensor) {
  const int rows = static_cast<int>(options_.range_m / kPoleSpacingX);
  std::uniform_int_distribution<int> row(-rows, rows);
  std::uniform_int_distribution<int> column(-3, 2);
  std::uniform_real_distribution<float> facing(-0.5f * kPi, 0.5f * kPi);
  std::uniform_real_distribution<float> height(0.f, kPoleHeight);
  const float cx = kPoleSpacingX * (std::round(sensor.x() / kPoleSpacingX) + row(rng_));
  const float cy = kPoleSpacingY * (column(rng_) + 0.5f);
  // The half of the pole facing the sensor.
  const float a = std::atan2(sensor.y() - cy, sensor.x() - cx) + facing(rng_);
  return {cx + kPoleRadius * std::cos(a), cy + kPoleRadius * std::sin(a),
          GroundHeight(cx, cy) + height(rng_)};
}

Eigen::Vector3f LidarLikeScene::FencePoint(const Eigen::Vector3f& sensor) {
  std::uniform_real_distribution<float> along(-options_.range_m, options_.range_m);
  std::uniform_real_distribution<float> height(0.f, kFenceHeight);
  const float y = (rng_() & 1u) ? kFenceY : -kFenceY;
  const float x = sensor.x() + along(rng_);
  return {x, y, GroundHeight(x, y) + height(rng_)};
}

}  // namespace hylo::benchmarks
