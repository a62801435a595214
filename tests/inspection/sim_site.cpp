#include "sim_site.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "hylo/common/local_origin.h"
#include "hylo/registration/voxel_filter.h"

namespace hylo::inspection_sim {
namespace {

// One return per voxel, in order.
std::vector<Eigen::Vector3d> Thin(const std::vector<Eigen::Vector3d>& points, double voxel_m) {
  PointCloud f;
  f.reserve(points.size());
  for (const Eigen::Vector3d& p : points) f.push_back(p.cast<float>());
  std::vector<Eigen::Vector3d> out;
  for (const std::size_t i : registration::UniformSampleIndices(f, static_cast<float>(voxel_m)))
    out.push_back(points[i]);
  return out;
}

// Sphere tracing on the true surfaces' distance field: true when every point of a-b is
// farther than `margin` from them. The field finds every primitive within its cell, so a
// larger distance is only known to be at least that.
bool ClearWithMargin(const sim::SurfaceDistanceField& field, const Eigen::Vector3d& a,
                     const Eigen::Vector3d& b, double margin) {
  constexpr double kFieldCell = 2.0, kMinStep = 0.005;
  const double length = (b - a).norm();
  const Eigen::Vector3d dir = (b - a) / std::max(length, 1e-12);
  for (double t = 0.0;;) {
    const double d = std::min(field.Nearest(a + t * dir).distance_m, kFieldCell);
    if (d <= margin) return false;
    if (t >= length) return true;
    t = std::min(length, t + std::max(d - margin, kMinStep));
  }
}

}  // namespace

SimSite BuildSimSite(const SimSiteOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  SimSite s;
  s.sim = sim::SimulationOptions::Fast(o.duration_s);
  s.sim.seed = o.seed;
  s.sim.lidar.column_deg = o.column_deg;
  s.sim.terrain.resolution_m = o.terrain_resolution_m;
  s.site = sim::BuildSite(o.seed, s.sim.terrain);
  const sim::SessionSimulator session(s.sim, s.site, sim::SessionId::kA);
  const sim::LidarSimulator& lidar = session.lidar();
  const int64_t scans = session.trajectory().duration_ns() / lidar.period_ns();
  std::vector<Eigen::Vector3d> ground, objects;
  std::vector<sim::ReturnTruth> truth;
  for (int64_t index = 0; index < scans; index += o.scan_stride) {
    const LidarScan scan = lidar.Scan(static_cast<int>(index), session.start_ns(), &truth);
    const int64_t scan_true_ns = scan.t_ns - s.sim.lidar.time_offset_ns - session.start_ns();
    for (std::size_t k = 0; k < scan.points.size(); ++k) {
      const ScanPoint& p = scan.points[k];
      const Eigen::Isometry3d T_map_lidar =
          session.trajectory().PoseAt(scan_true_ns + p.offset_ns) * s.sim.lidar.T_imu_lidar;
      (truth[k].primitive < 0 ? ground : objects)
          .push_back(T_map_lidar * p.position_lidar.cast<double>());
    }
  }
  ground = Thin(ground, o.map_voxel_m);
  objects = Thin(objects, o.map_voxel_m);
  s.costmap = terrain::ComputeTraversability(ground, objects, o.traversability);
  s.origin = s.costmap.grid.geometry().origin_world;
  for (const auto* part : {&ground, &objects}) {
    for (const Eigen::Vector3d& p : *part) s.map_local.push_back((p - s.origin).cast<float>());
  }
  s.world = std::make_unique<sim::World>(
      s.site.terrain, sim::SessionPrimitives(s.site, sim::SessionId::kA), s.sim.index_cell_m);
  s.field = std::make_unique<sim::SurfaceDistanceField>(*s.world);
  s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

std::vector<inspection::Target> LocalTargets(const std::vector<sim::EquipmentTarget>& equipment,
                                             const Eigen::Vector3d& origin) {
  std::vector<inspection::Target> out;
  for (const sim::EquipmentTarget& e : equipment) {
    inspection::Target t;
    t.id = e.id;
    t.position = e.centre_m - origin;
    t.box_size_m = e.box_size_m;
    t.view_azimuth_deg = e.view_azimuth_deg;
    t.view_tolerance_deg = e.view_tolerance_deg;
    out.push_back(t);
  }
  return out;
}

Eigen::Vector3d TrueCamera(const SimSite& s, std::size_t cell, double camera_height_m) {
  const terrain::GridGeometry& g = s.costmap.grid.geometry();
  const Eigen::Vector2d xy = g.CentreLocal(g.Col(cell), g.Row(cell));
  const Eigen::Vector2d site_xy = xy + s.origin.head<2>();
  const double z = s.site.terrain->BaseHeight(site_xy.x(), site_xy.y()) + camera_height_m;
  return {xy.x(), xy.y(), z - s.origin.z()};
}

int ClearLinesInTruth(const SimSite& s, const inspection::TargetShape& shape,
                      const Eigen::Vector3d& camera_local, double margin_m) {
  int clear = 0;
  for (int k = 0; k < shape.num_samples; ++k) {
    Eigen::Vector3d end;
    if (!inspection::SightLineEnd(shape, k, camera_local, &end)) continue;
    const Eigen::Vector3d a = camera_local + s.origin, b = end + s.origin;
    if (margin_m > 0.0) {
      clear += ClearWithMargin(*s.field, a, b, margin_m);
      continue;
    }
    sim::Ray ray;
    ray.origin = a;
    ray.direction = (b - a).normalized();
    sim::RayHit hit;
    clear += !s.world->Raycast(ray, (b - a).norm(), &hit);
  }
  return clear;
}

std::string DescribeFirstHit(const SimSite& s, const inspection::TargetShape& shape,
                             const Eigen::Vector3d& camera_local) {
  for (int k = 0; k < shape.num_samples; ++k) {
    Eigen::Vector3d end;
    if (!inspection::SightLineEnd(shape, k, camera_local, &end)) return "camera inside the target";
    sim::Ray ray;
    ray.origin = camera_local + s.origin;
    ray.direction = (end - camera_local).normalized();
    sim::RayHit hit;
    if (!s.world->Raycast(ray, (end - camera_local).norm(), &hit)) continue;
    const int object = hit.IsGround() ? -1 : s.world->primitives()[hit.primitive].object_id;
    char text[200];
    std::snprintf(text, sizeof(text), "line %d hits %s at (%.2f, %.2f, %.2f), %.2f m of %.2f m", k,
                  object < 0 ? "the ground" : s.site.objects[object].kind.c_str(),
                  hit.point_map.x(), hit.point_map.y(), hit.point_map.z(), hit.range_m,
                  (end - camera_local).norm());
    return text;
  }
  return "no line hits anything";
}

}  // namespace hylo::inspection_sim
