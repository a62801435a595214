// The repeated simulated site and its sampled prior map (repeated_site.h).
#include "repeated_site.h"

#include <cmath>
#include <memory>

#include "hylo/io/cloud_stream.h"
#include "hylo/sim/world.h"
#include "hylo/sim_io/reference_outputs.h"

namespace hylo::benchmarks {
namespace {

bool InAnnex(const sim::Site& base, const sim::Primitive& part) {
  const sim::Aabb box = sim::BoundsOf(part);
  return box.max.x() > base.annex_min_m.x() - 2.0 && box.min.y() < base.annex_max_m.y() + 2.0;
}

sim::Primitive Moved(sim::Primitive p, const Eigen::Vector3d& offset) {
  p.center_map += offset;
  p.start_map += offset;
  p.end_map += offset;
  return p;
}

}  // namespace

double RoadX(const RepeatedSiteOptions& options, int column) {
  // The fenced site spans x in [0, 120]; the next copy's fence starts one period on.
  return column * options.period_m.x() + 0.5 * (120.0 + options.period_m.x());
}

sim::Site RepeatedSite(const sim::Site& base, const RepeatedSiteOptions& options,
                       const std::vector<Eigen::Vector2d>& route_m, uint64_t seed) {
  const sim::TerrainShape& one = base.terrain->shape();
  sim::TerrainShape shape;
  shape.undulation_m = one.undulation_m;
  shape.undulation_wavelength_m = one.undulation_wavelength_m;
  shape.undulation_phase = one.undulation_phase;
  sim::Site site;
  for (int iy = 0; iy < options.copies_y; ++iy) {
    for (int ix = 0; ix < options.copies_x; ++ix) {
      const Eigen::Vector2d d(ix * options.period_m.x(), iy * options.period_m.y());
      for (sim::Hill h : one.hills) {
        h.center_m += d;
        shape.hills.push_back(h);
      }
      for (sim::Ditch c : one.ditches) {
        c.start_m += d;
        c.end_m += d;
        shape.ditches.push_back(c);
      }
      for (sim::RaisedBed b : one.beds) {
        b.min_m += d;
        b.max_m += d;
        shape.beds.push_back(b);
      }
      for (sim::Trench t : one.trenches) {
        t.start_m += d;
        t.end_m += d;
        shape.trenches.push_back(t);
      }
      for (const sim::SiteObject& object : base.objects) {
        bool annex = false;
        for (const sim::Primitive& part : object.parts) annex = annex || InAnnex(base, part);
        if (annex) continue;
        sim::SiteObject copy = object;
        for (sim::Primitive& part : copy.parts)
          part = Moved(part, Eigen::Vector3d(d.x(), d.y(), 0));
        site.objects.push_back(copy);
      }
    }
  }
  sim::TerrainOptions terrain = base.terrain->options();
  terrain.resolution_m = options.terrain_resolution_m;
  terrain.min_m = Eigen::Vector2d(-15.0, -15.0);
  terrain.max_m = Eigen::Vector2d(options.copies_x * options.period_m.x() - 15.0,
                                  options.copies_y * options.period_m.y() - 15.0);
  site.terrain = std::make_shared<const sim::Terrain>(shape, terrain, seed);
  site.site_min_m = terrain.min_m;
  site.site_max_m = terrain.max_m;
  site.route_a = route_m;
  site.route_b = route_m;
  return site;
}

SiteMapSummary WriteSiteMap(const sim::Site& site, const std::string& path, double ground_spacing_m,
                            double object_spacing_m, uint64_t seed) {
  const sim::World world(site.terrain, sim::SessionPrimitives(site, sim::SessionId::kA));
  const sim::Terrain& terrain = world.terrain();
  io::PcdXyzWriter writer(path);
  SiteMapSummary summary;
  const Eigen::Vector2d lo = site.site_min_m, hi = site.site_max_m;
  const double band_m = 100.0;
  for (double y0 = lo.y(); y0 < hi.y(); y0 += band_m) {
    const double y1 = std::min(hi.y(), y0 + band_m);
    PointCloud points;
    for (double y = y0 + 0.5 * ground_spacing_m; y < y1; y += ground_spacing_m) {
      for (double x = lo.x() + 0.5 * ground_spacing_m; x < hi.x(); x += ground_spacing_m) {
        const Eigen::Vector3d p(x, y, terrain.Height(x, y));
        if (world.InsideAnyPrimitive(p, 0.01)) continue;
        points.push_back(p.cast<float>());
      }
    }
    summary.ground_points += points.size();
    sim::Site band = site;
    band.site_min_m = Eigen::Vector2d(lo.x(), y0);
    band.site_max_m = Eigen::Vector2d(hi.x(), std::nextafter(y1, y0));  // bands do not overlap
    const io::CloudFile reference = sim::ReferenceCloud(band, world, object_spacing_m, seed);
    for (std::size_t i = 0; i < reference.positions.size(); ++i) {
      if (reference.labels[i] != sim::kLabelObject) continue;
      points.push_back(reference.positions[i].cast<float>());
      ++summary.object_points;
    }
    writer.Add(points);
  }
  writer.Commit();
  return summary;
}

}  // namespace hylo::benchmarks
