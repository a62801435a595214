#pragma once
// Synthetic scenes for the registration tests: rectangles and boxes sampled at random, a yard
// without symmetry, a view of a cloud from a pose, and pose errors.

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <memory>
#include <random>

#include "hylo/common/point_types.h"
#include "hylo/mapping/ikd_tree.h"

namespace hylo::registration::synthetic_scene {

constexpr double kDeg = M_PI / 180.0;

inline Eigen::Isometry3d Pose(double x, double y, double z, double yaw_deg) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_deg * kDeg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

inline void AddRectangle(const Eigen::Vector3f& corner, const Eigen::Vector3f& u,
                  const Eigen::Vector3f& v, float spacing_m, std::mt19937* rng,
                  PointCloud* cloud) {
  // Random samples at about one per spacing^2 (a regular grid would alias).
  const int n = static_cast<int>(u.norm() * v.norm() / (spacing_m * spacing_m));
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  for (int i = 0; i < n; ++i) cloud->push_back(corner + unit(*rng) * u + unit(*rng) * v);
}

inline void AddBox(const Eigen::Vector3f& corner, const Eigen::Vector3f& size, float spacing_m,
            std::mt19937* rng, PointCloud* cloud) {
  const Eigen::Vector3f x(size.x(), 0, 0), y(0, size.y(), 0), z(0, 0, size.z());
  AddRectangle(corner, x, z, spacing_m, rng, cloud);
  AddRectangle(corner + y, x, z, spacing_m, rng, cloud);
  AddRectangle(corner, y, z, spacing_m, rng, cloud);
  AddRectangle(corner + x, y, z, spacing_m, rng, cloud);
  AddRectangle(corner + z, x, y, spacing_m, rng, cloud);
}

// A 30 m x 30 m yard: ground, two walls, five boxes of different sizes (no symmetry).
inline PointCloud Yard(float spacing_m, uint32_t seed) {
  std::mt19937 rng(seed);
  PointCloud cloud;
  AddRectangle({-15, -15, 0}, {30, 0, 0}, {0, 30, 0}, spacing_m, &rng, &cloud);
  AddRectangle({-15, 15, 0}, {30, 0, 0}, {0, 0, 3}, spacing_m, &rng, &cloud);
  AddRectangle({-15, -15, 0}, {0, 30, 0}, {0, 0, 2}, spacing_m, &rng, &cloud);
  AddBox({3, 2, 0}, {2, 1, 2.5f}, spacing_m, &rng, &cloud);
  AddBox({-6, -4, 0}, {1, 3, 1.5f}, spacing_m, &rng, &cloud);
  AddBox({5, -7, 0}, {3, 1.5f, 1}, spacing_m, &rng, &cloud);
  AddBox({-9, 6, 0}, {1.5f, 1.5f, 4}, spacing_m, &rng, &cloud);
  AddBox({9, 9, 0}, {1, 4, 2}, spacing_m, &rng, &cloud);
  return cloud;
}

// The map as production searches it (an exact brute-force search would take minutes here).
inline std::unique_ptr<mapping::IkdTree> Tree(const PointCloud& points) {
  auto tree = std::make_unique<mapping::IkdTree>(mapping::IkdTree::Options());
  tree->Build(points);
  return tree;
}

// `world` seen from `T_world_body`: the points in the body frame, with Gaussian noise.
inline PointCloud InBody(const PointCloud& world, const Eigen::Isometry3d& T_world_body,
                  double noise_m, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, noise_m);
  const Eigen::Isometry3d T_body_world = T_world_body.inverse();
  PointCloud body;
  for (const Eigen::Vector3f& p : world) {
    const Eigen::Vector3d n(noise(rng), noise(rng), noise(rng));
    body.push_back((T_body_world * (p.cast<double>() + n)).cast<float>());
  }
  return body;
}

inline double TranslationError(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.translation() - b.translation()).norm();
}
inline double RotationErrorDeg(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return Eigen::AngleAxisd(a.linear().transpose() * b.linear()).angle() / kDeg;
}

}  // namespace hylo::registration::synthetic_scene
