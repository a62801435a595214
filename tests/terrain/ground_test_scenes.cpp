#include "ground_test_scenes.h"

#include <algorithm>
#include <cmath>
#include <random>

namespace hylo::terrain::scenes {

Scene MakeScene(const SceneSpec& spec) {
  std::mt19937 rng(spec.seed);
  std::uniform_real_distribution<float> uniform(0.f, spec.size_m);
  std::normal_distribution<float> noise(0.f, spec.noise_m);
  Scene scene;
  const int count = static_cast<int>(spec.size_m * spec.size_m * spec.density);
  for (int i = 0; i < count; ++i) {
    const float x = uniform(rng), y = uniform(rng);
    const float ground_z = spec.terrain(x, y);
    float z = ground_z;
    Truth truth = Truth::kGround;
    for (const Slab& slab : spec.slabs) {
      if (!slab.Contains(x, y)) continue;
      const float top = slab.absolute ? slab.top_m : ground_z + slab.top_m;
      if (top <= z) continue;
      z = top;
      truth = Truth::kObject;
    }
    scene.points.emplace_back(x, y, z + noise(rng));
    scene.truth.push_back(truth);
  }
  for (int i = 0; i < spec.low_outliers; ++i) {
    const float x = uniform(rng), y = uniform(rng);
    scene.points.emplace_back(x, y, spec.terrain(x, y) - spec.low_outlier_depth_m);
    scene.truth.push_back(Truth::kLowOutlier);
  }
  return scene;
}

SceneScore Score(const Scene& scene, const std::vector<GroundLabel>& labels) {
  std::size_t counts[3] = {0, 0, 0}, right[3] = {0, 0, 0};
  for (std::size_t i = 0; i < scene.points.size(); ++i) {
    const int k = static_cast<int>(scene.truth[i]);
    ++counts[k];
    const bool want_ground = scene.truth[i] == Truth::kGround;
    right[k] += (labels[i] == GroundLabel::kGround) == want_ground;
  }
  const auto share = [&](int k) { return counts[k] ? double(right[k]) / counts[k] : 1.0; };
  return {share(0), share(1), share(2)};
}

float Bank(float x, float x0, float height_m, float angle_deg) {
  const float run = height_m / std::tan(angle_deg * 3.14159265f / 180.f);
  return height_m * std::clamp((x - x0) / run, 0.f, 1.f);
}

}  // namespace hylo::terrain::scenes
