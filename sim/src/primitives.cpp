// Exact ray intersection with oriented boxes (slab method, Kay & Kajiya 1986) and finite
// capped cylinders (quadric side + two cap planes).
#include "hylo/sim/primitives.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "hylo/common/check.h"

namespace hylo::sim {
namespace {

constexpr double kParallelEps = 1e-12;

bool IntersectBox(const Primitive& box, const Ray& ray, double t_min, double t_max,
                  SurfaceHit* hit) {
  const Eigen::Vector3d origin = box.R_map_box.transpose() * (ray.origin - box.center_map);
  const Eigen::Vector3d dir = box.R_map_box.transpose() * ray.direction;
  double t_near = -1e300, t_far = 1e300;
  int near_axis = -1, far_axis = -1;
  double near_sign = 0.0, far_sign = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double h = box.half_extent_m[i];
    if (std::abs(dir[i]) < kParallelEps) {
      if (std::abs(origin[i]) > h) return false;
      continue;
    }
    const double inv = 1.0 / dir[i];
    double t0 = (-h - origin[i]) * inv, t1 = (h - origin[i]) * inv;
    // Entering through the face whose outward normal opposes the direction.
    double s0 = -1.0, s1 = 1.0;
    if (t0 > t1) {
      std::swap(t0, t1);
      std::swap(s0, s1);
    }
    if (t0 > t_near) {
      t_near = t0;
      near_axis = i;
      near_sign = s0;
    }
    if (t1 < t_far) {
      t_far = t1;
      far_axis = i;
      far_sign = s1;
    }
  }
  if (t_near > t_far || near_axis < 0) return false;
  double t = t_near;
  int axis = near_axis;
  double sign = near_sign;
  if (t <= t_min) {  // the ray starts inside: report the exit
    t = t_far;
    axis = far_axis;
    sign = far_sign;
  }
  if (t <= t_min || t >= t_max) return false;
  hit->t = t;
  hit->normal_map = box.R_map_box.col(axis) * sign;
  return true;
}

bool IntersectCylinder(const Primitive& cyl, const Ray& ray, double t_min, double t_max,
                       SurfaceHit* hit) {
  const double length = cyl.length_m;
  const Eigen::Vector3d& u = cyl.axis_unit;
  const Eigen::Vector3d w = ray.origin - cyl.start_map;
  const double w_u = w.dot(u), d_u = ray.direction.dot(u);
  const Eigen::Vector3d w_perp = w - w_u * u, d_perp = ray.direction - d_u * u;
  const double r2 = cyl.radius_m * cyl.radius_m;
  double best = t_max;
  Eigen::Vector3d best_normal = Eigen::Vector3d::UnitZ();
  // Side: |w_perp + t d_perp|^2 = r^2, valid where the axial coordinate is within [0, L].
  const double a = d_perp.squaredNorm();
  if (a > kParallelEps) {
    const double b = w_perp.dot(d_perp), c = w_perp.squaredNorm() - r2;
    const double disc = b * b - a * c;
    if (disc >= 0.0) {
      const double sq = std::sqrt(disc);
      for (const double t : {(-b - sq) / a, (-b + sq) / a}) {
        const double s = w_u + t * d_u;
        if (t > t_min && t < best && s >= 0.0 && s <= length) {
          best = t;
          best_normal = (w_perp + t * d_perp) / cyl.radius_m;
        }
      }
    }
  }
  // Caps: planes s = 0 (normal -u) and s = L (normal +u), inside the disc.
  if (std::abs(d_u) > kParallelEps) {
    for (const double s_cap : {0.0, length}) {
      const double t = (s_cap - w_u) / d_u;
      if (t > t_min && t < best && (w_perp + t * d_perp).squaredNorm() <= r2) {
        best = t;
        best_normal = s_cap == 0.0 ? Eigen::Vector3d(-u) : u;
      }
    }
  }
  if (best >= t_max) return false;
  hit->t = best;
  hit->normal_map = best_normal.normalized();
  return true;
}

}  // namespace

Primitive MakeBox(const Eigen::Vector3d& center_map, const Eigen::Vector3d& size_m, double yaw_rad,
                  float reflectivity) {
  HYLO_CHECK((size_m.array() > 0.0).all(), "box sizes must be positive");
  Primitive box;
  box.shape = Primitive::Shape::kBox;
  box.center_map = center_map;
  box.R_map_box = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  box.half_extent_m = 0.5 * size_m;
  box.reflectivity = reflectivity;
  return box;
}

Primitive MakeCylinder(const Eigen::Vector3d& start_map, const Eigen::Vector3d& end_map,
                       double radius_m, float reflectivity) {
  HYLO_CHECK(radius_m > 0.0 && (end_map - start_map).norm() > 1e-9, "degenerate cylinder");
  Primitive cyl;
  cyl.shape = Primitive::Shape::kCylinder;
  cyl.start_map = start_map;
  cyl.end_map = end_map;
  cyl.center_map = 0.5 * (start_map + end_map);
  cyl.radius_m = radius_m;
  cyl.length_m = (end_map - start_map).norm();
  cyl.axis_unit = (end_map - start_map) / cyl.length_m;
  cyl.reflectivity = reflectivity;
  return cyl;
}

Aabb BoundsOf(const Primitive& p) {
  Aabb box;
  if (p.shape == Primitive::Shape::kBox) {
    const Eigen::Vector3d extent = p.R_map_box.cwiseAbs() * p.half_extent_m;
    box.min = p.center_map - extent;
    box.max = p.center_map + extent;
    return box;
  }
  const Eigen::Vector3d u = (p.end_map - p.start_map).normalized();
  // Extent of the end discs along each map axis: r * sqrt(1 - u_i^2).
  const Eigen::Vector3d disc =
      p.radius_m * (Eigen::Vector3d::Ones() - u.cwiseAbs2()).cwiseMax(0.0).cwiseSqrt();
  box.min = p.start_map.cwiseMin(p.end_map) - disc;
  box.max = p.start_map.cwiseMax(p.end_map) + disc;
  return box;
}

bool Intersect(const Primitive& primitive, const Ray& ray, double t_min, double t_max,
               SurfaceHit* hit) {
  return primitive.shape == Primitive::Shape::kBox
             ? IntersectBox(primitive, ray, t_min, t_max, hit)
             : IntersectCylinder(primitive, ray, t_min, t_max, hit);
}

double SignedDistance(const Primitive& p, const Eigen::Vector3d& point_map) {
  Eigen::Vector2d q;  // per-direction excess over the half size (box: 3 axes, below)
  if (p.shape == Primitive::Shape::kBox) {
    const Eigen::Vector3d local = p.R_map_box.transpose() * (point_map - p.center_map);
    const Eigen::Vector3d excess = local.cwiseAbs() - p.half_extent_m;
    return excess.cwiseMax(0.0).norm() + std::min(excess.maxCoeff(), 0.0);
  }
  const Eigen::Vector3d axis = p.end_map - p.start_map;
  const double length = axis.norm();
  const Eigen::Vector3d u = axis / length;
  const Eigen::Vector3d w = point_map - p.start_map;
  const double s = w.dot(u);
  q << (w - s * u).norm() - p.radius_m, std::abs(s - 0.5 * length) - 0.5 * length;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

double SurfaceArea(const Primitive& p) {
  if (p.shape == Primitive::Shape::kBox) {
    const Eigen::Vector3d s = 2.0 * p.half_extent_m;
    return 2.0 * (s.x() * s.y() + s.y() * s.z() + s.x() * s.z());
  }
  const double length = (p.end_map - p.start_map).norm();
  return 2.0 * M_PI * p.radius_m * (length + p.radius_m);
}

}  // namespace hylo::sim
