#pragma once
// Vectors and poses as JSON, the same way in every manifest of the simulator's files.

#include <Eigen/Geometry>
#include <vector>

#include "hylo/io/json.h"

namespace hylo::sim {

inline io::Json Vec(const Eigen::Vector3d& v) { return io::Json::array({v.x(), v.y(), v.z()}); }

/// Translation, quaternion (x y z w) and the row-major 4x4 matrix.
inline io::Json PoseJson(const Eigen::Isometry3d& T) {
  io::Json j = io::Json::object();
  const Eigen::Quaterniond q(T.linear());
  j["translation_m"] = Vec(T.translation());
  j["quaternion_xyzw"] = io::Json::array({q.x(), q.y(), q.z(), q.w()});
  std::vector<double> m;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) m.push_back(T.matrix()(r, c));
  }
  j["matrix_row_major"] = io::Json(m);
  return j;
}

}  // namespace hylo::sim
