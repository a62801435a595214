#pragma once
// Synthetic scenes of axis-aligned rectangles for estimator tests: what a scan of each observes
// is known exactly (a room fixes every pose direction, a floor only height, roll and pitch, a
// corridor all but its length).

#include "hylo/common/point_types.h"

namespace hylo::testing {

// Points on the rectangle [lo, hi] of the plane `fixed_axis` = `fixed`, spacing 0.1 m.
inline void AddFace(int fixed_axis, double fixed, Eigen::Vector2d lo, Eigen::Vector2d hi,
                    PointCloud* points) {
  const int a = (fixed_axis + 1) % 3, b = (fixed_axis + 2) % 3;
  for (double u = lo.x(); u <= hi.x(); u += 0.1) {
    for (double v = lo.y(); v <= hi.y(); v += 0.1) {
      Eigen::Vector3f p;
      p[fixed_axis] = static_cast<float>(fixed);
      p[a] = static_cast<float>(u);
      p[b] = static_cast<float>(v);
      points->push_back(p);
    }
  }
}

inline PointCloud Floor() {
  PointCloud p;
  AddFace(2, 0.0, {-10, -10}, {10, 10}, &p);
  return p;
}

inline PointCloud Corridor() {  // along x: floor and two walls, no end
  PointCloud p;
  AddFace(2, 0.0, {-15, -1.5}, {15, 1.5}, &p);
  AddFace(1, -1.5, {0, -15}, {3, 15}, &p);
  AddFace(1, 1.5, {0, -15}, {3, 15}, &p);
  return p;
}

inline PointCloud Room() {  // 8 m × 12 m, 3 m high, floor at z = 0
  PointCloud p;
  AddFace(2, 0.0, {-4, -6}, {4, 6}, &p);
  AddFace(0, -4.0, {-6, 0}, {6, 3}, &p);
  AddFace(0, 4.0, {-6, 0}, {6, 3}, &p);
  AddFace(1, -6.0, {0, -4}, {3, 4}, &p);
  AddFace(1, 6.0, {0, -4}, {3, 4}, &p);
  return p;
}

}  // namespace hylo::testing
