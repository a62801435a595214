#pragma once
// Synthetic airborne-like scenes with known ground for the ground filters' tests: a terrain
// function sampled at random positions, boxes (buildings) and a bridge deck that hide the
// terrain under them, and low outliers (multipath returns) below it.

#include <cstdint>
#include <functional>
#include <vector>

#include "hylo/terrain/ground_label.h"
#include "hylo/common/point_types.h"

namespace hylo::terrain::scenes {

/// A raised rectangle: a building, or a bridge deck (deck_m > 0: a slab of that thickness at
/// `top_m` absolute height rather than a box `top_m` above the terrain).
struct Slab {
  float x0, y0, x1, y1;   ///< footprint, m
  float top_m;            ///< height above the terrain (building) or absolute (deck), m
  bool absolute = false;  ///< true: top_m is an absolute height (a deck over a cut)
  bool Contains(float x, float y) const { return x >= x0 && x <= x1 && y >= y0 && y <= y1; }
};

enum class Truth : uint8_t { kGround, kObject, kLowOutlier };

struct Scene {
  PointCloud points;
  std::vector<Truth> truth;  ///< per point
};

struct SceneSpec {
  float size_m = 100.f;   ///< square side, m
  float density = 2.f;    ///< points per m^2
  float noise_m = 0.05f;  ///< vertical noise, m
  std::function<float(float, float)> terrain = [](float, float) { return 0.f; };
  std::vector<Slab> slabs;
  int low_outliers = 0;              ///< isolated returns this many ...
  float low_outlier_depth_m = 10.f;  ///< ... this far below the terrain, m
  uint32_t seed = 1;
};

/// Samples the scene: every position takes the highest surface over it (a roof or a deck
/// hides the terrain), plus `low_outliers` points below the terrain at random positions.
Scene MakeScene(const SceneSpec& spec);

/// Shares of each truth class labelled as expected: ground kept, objects and outliers removed.
struct SceneScore {
  double ground_kept = 1.0;
  double objects_removed = 1.0;
  double outliers_removed = 1.0;
};
SceneScore Score(const Scene& scene, const std::vector<GroundLabel>& labels);

/// A bank of `angle_deg` from (x0, 0) to (x0 + height / tan(angle), 0) rising by height_m.
float Bank(float x, float x0, float height_m, float angle_deg);

}  // namespace hylo::terrain::scenes
