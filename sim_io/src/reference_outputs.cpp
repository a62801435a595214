// Reference cloud (surface sampling) and the slope grid file.
#include "hylo/sim_io/reference_outputs.h"

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <stdexcept>

#include "hylo/io/atomic_file.h"
#include "hylo/sim/random.h"

namespace hylo::sim {
namespace {

// A uniform point on the surface of `p` (faces/caps chosen in proportion to their area).
Eigen::Vector3d SampleSurface(const Primitive& p, Rng* rng) {
  if (p.shape == Primitive::Shape::kBox) {
    const Eigen::Vector3d s = 2.0 * p.half_extent_m;
    const double areas[3] = {s.y() * s.z(), s.x() * s.z(),
                             s.x() * s.y()};  // faces normal to x, y, z
    double pick = rng->Uniform(0.0, areas[0] + areas[1] + areas[2]);
    int axis = 0;
    while (axis < 2 && pick > areas[axis]) pick -= areas[axis++];
    Eigen::Vector3d local(rng->Uniform(-1, 1), rng->Uniform(-1, 1), rng->Uniform(-1, 1));
    local[axis] = rng->Uniform() < 0.5 ? -1.0 : 1.0;
    return p.center_map + p.R_map_box * local.cwiseProduct(p.half_extent_m);
  }
  const Eigen::Vector3d u = p.axis_unit;
  const Eigen::Vector3d a = u.unitOrthogonal(), b = u.cross(a);
  const double side = 2.0 * M_PI * p.radius_m * p.length_m, cap = M_PI * p.radius_m * p.radius_m;
  const double angle = rng->Uniform(0.0, 2.0 * M_PI);
  const Eigen::Vector3d radial = std::cos(angle) * a + std::sin(angle) * b;
  if (rng->Uniform(0.0, side + 2.0 * cap) < side) {
    return p.start_map + rng->Uniform(0.0, p.length_m) * u + p.radius_m * radial;
  }
  const double r = p.radius_m * std::sqrt(rng->Uniform());  // uniform on the disc
  return (rng->Uniform() < 0.5 ? p.start_map : p.end_map) + r * radial;
}

bool InSite(const Site& site, const Eigen::Vector3d& p) {
  return p.x() >= site.site_min_m.x() && p.y() >= site.site_min_m.y() &&
         p.x() <= site.site_max_m.x() && p.y() <= site.site_max_m.y();
}

}  // namespace

io::CloudFile ReferenceCloud(const Site& site, const World& world, double object_spacing_m,
                             uint64_t seed) {
  io::CloudFile cloud;
  const Terrain& terrain = world.terrain();
  const Grid2d& cells = terrain.cells();
  for (int iy = 0; iy <= cells.ny; ++iy) {
    for (int ix = 0; ix <= cells.nx; ++ix) {
      const Eigen::Vector2d xy = cells.origin_m + cells.cell_m * Eigen::Vector2d(ix, iy);
      const Eigen::Vector3d p(xy.x(), xy.y(), terrain.Height(xy.x(), xy.y()));
      if (!InSite(site, p) || world.InsideAnyPrimitive(p, 0.01)) continue;
      cloud.positions.push_back(p);
      cloud.intensity.push_back(255.f * terrain.options().reflectivity);
      cloud.labels.push_back(kLabelGround);
    }
  }
  Rng rng = Rng::Derive(seed, 0x2ef);
  const double per_m2 = 1.0 / (object_spacing_m * object_spacing_m);
  for (int32_t id = 0; id < static_cast<int32_t>(world.primitives().size()); ++id) {
    const Primitive& prim = world.primitives()[id];
    const int n = static_cast<int>(std::ceil(SurfaceArea(prim) * per_m2));
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector3d p = SampleSurface(prim, &rng);
      if (!InSite(site, p) || p.z() < terrain.Height(p.x(), p.y()) - 0.01 ||
          world.InsideAnyPrimitive(p, 0.005, id)) {
        continue;
      }
      cloud.positions.push_back(p);
      cloud.intensity.push_back(255.f * prim.reflectivity);
      cloud.labels.push_back(kLabelObject);
    }
  }
  return cloud;
}

void WriteSlopeGrid(const std::string& path, const Site& site, double resolution_m) {
  io::AtomicFile file(path);
  std::ofstream& out = file.stream();
  const Eigen::Vector2d extent = site.site_max_m - site.site_min_m;
  const int cols = static_cast<int>(std::ceil(extent.x() / resolution_m));
  const int rows = static_cast<int>(std::ceil(extent.y() / resolution_m));
  out << "# hylo simulator: true terrain slope in degrees, atan(|grad h|) of the ground\n"
      << "# without gravel roughness (trenches included), central differences over\n"
      << "# +-resolution/2 at each cell centre. Row 0 is the southmost; values go east.\n"
      << "origin_m " << site.site_min_m.x() << " " << site.site_min_m.y() << "\n"
      << "resolution_m " << resolution_m << "\n"
      << "size " << cols << " " << rows << "\n"
      << std::fixed << std::setprecision(2);
  const Terrain& terrain = *site.terrain;
  const double h = 0.5 * resolution_m;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const double x = site.site_min_m.x() + (c + 0.5) * resolution_m;
      const double y = site.site_min_m.y() + (r + 0.5) * resolution_m;
      const double gx = (terrain.CleanHeight(x + h, y) - terrain.CleanHeight(x - h, y)) / (2 * h);
      const double gy = (terrain.CleanHeight(x, y + h) - terrain.CleanHeight(x, y - h)) / (2 * h);
      out << (c ? " " : "") << std::atan(std::hypot(gx, gy)) * 180.0 / M_PI;
    }
    out << "\n";
  }
  file.Commit();
}

}  // namespace hylo::sim
