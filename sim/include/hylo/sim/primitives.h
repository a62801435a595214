#pragma once
// Analytic primitives of the simulated site (oriented boxes, finite cylinders) with exact
// ray intersection. Every structure of the substation (gantry lattices, transformers,
// insulators, busbars, fences, buildings, vehicles) is assembled from these two shapes.

#include <Eigen/Core>
#include <cstdint>

namespace hylo::sim {

/// Axis-aligned bounding box in the map frame.
struct Aabb {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(1e300);   ///< m
  Eigen::Vector3d max = Eigen::Vector3d::Constant(-1e300);  ///< m
  void Extend(const Aabb& other) {
    min = min.cwiseMin(other.min);
    max = max.cwiseMax(other.max);
  }
};

/// A ray: origin + t * direction, direction of unit length, t in metres.
struct Ray {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();
};

/// The first crossing of a ray with a surface.
struct SurfaceHit {
  double t = 0.0;                                         ///< distance along the ray, m
  Eigen::Vector3d normal_map = Eigen::Vector3d::UnitZ();  ///< outward unit normal, map frame
};

/// One analytic solid. Boxes: `R_map_box` rotates box axes into the map, `half_extent_m`
/// per box axis. Cylinders: the axis runs from `start_map` to `end_map`, closed by flat caps.
struct Primitive {
  enum class Shape : uint8_t { kBox, kCylinder };
  Shape shape = Shape::kBox;
  Eigen::Vector3d center_map = Eigen::Vector3d::Zero();     ///< box centre, m
  Eigen::Matrix3d R_map_box = Eigen::Matrix3d::Identity();  ///< box orientation
  Eigen::Vector3d half_extent_m = Eigen::Vector3d::Ones();  ///< box half sizes, m
  Eigen::Vector3d start_map = Eigen::Vector3d::Zero();      ///< cylinder axis start, m
  Eigen::Vector3d end_map = Eigen::Vector3d::UnitZ();       ///< cylinder axis end, m
  double radius_m = 0.1;                                    ///< cylinder radius, m
  Eigen::Vector3d axis_unit = Eigen::Vector3d::UnitZ();     ///< cylinder: cached unit axis
  double length_m = 1.0;                                    ///< cylinder: cached axis length, m
  float reflectivity = 0.4f;  ///< diffuse reflectivity in [0, 1] (drives intensity)
  int32_t object_id = -1;     ///< the site object this part belongs to
};

/// A box of size `size_m` (full lengths) centred at `center_map`, rotated by `yaw_rad` about z.
Primitive MakeBox(const Eigen::Vector3d& center_map, const Eigen::Vector3d& size_m, double yaw_rad,
                  float reflectivity);
/// A cylinder from `start_map` to `end_map` of radius `radius_m`.
Primitive MakeCylinder(const Eigen::Vector3d& start_map, const Eigen::Vector3d& end_map,
                       double radius_m, float reflectivity);

/// Bounding box of a primitive.
Aabb BoundsOf(const Primitive& primitive);

/// First crossing with t in (t_min, t_max); false when the ray misses in that interval.
bool Intersect(const Primitive& primitive, const Ray& ray, double t_min, double t_max,
               SurfaceHit* hit);

/// Signed distance of `point_map` to the primitive surface (negative inside), m. Exact for
/// boxes; exact for cylinders (distance to the finite solid, caps included).
double SignedDistance(const Primitive& primitive, const Eigen::Vector3d& point_map);

/// Total surface area, m^2 (for sampling the reference cloud).
double SurfaceArea(const Primitive& primitive);

}  // namespace hylo::sim
