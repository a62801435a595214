// Inspection planning on the simulated substation: 100 targets on the ~150 m x 100 m site
// (the site's equipment targets plus points drawn on its structures' surfaces), planned on one
// core from session A's returns at the true poses (tests/inspection/sim_site.h). Prints the
// stage times (thread CPU and wall), the plan, and how the plan holds against the simulator's
// true geometry: planned views that are not line of sight in the truth, route samples on
// lethal or unknown cells. Speed is reported, never asserted; the target is <= 10 s.
//   hylo_inspection_benchmark [--quick] [--targets N] [--seed S] [--sweep] [--json PATH]
// --sweep also plans with clearances 0.10 / 0.15 / 0.25 m on two map densities (every 10th
// scan at 1 deg and at 0.5 deg columns) and counts the views that fail in the truth.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "benchmark_common.h"
#include "inspection/sim_site.h"

namespace {

using hylo::benchmarks::NowMs;
using hylo::benchmarks::Report;
namespace insp = hylo::inspection;
namespace isim = hylo::inspection_sim;
namespace sim = hylo::sim;

// A point on a primitive's surface, drawn uniformly over its faces (boxes) or its mantle
// (cylinders).
Eigen::Vector3d SurfacePoint(const sim::Primitive& p, std::mt19937* rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  if (p.shape == sim::Primitive::Shape::kCylinder) {
    const Eigen::Vector3d a = p.axis_unit;
    const Eigen::Vector3d n = a.unitOrthogonal(), m = a.cross(n);
    const double angle = M_PI * u(*rng);
    return p.start_map + 0.5 * (1.0 + u(*rng)) * p.length_m * a +
           p.radius_m * (std::cos(angle) * n + std::sin(angle) * m);
  }
  Eigen::Vector3d local(u(*rng), u(*rng), u(*rng));
  const int face = std::uniform_int_distribution<int>(0, 2)(*rng);
  local[face] = local[face] < 0.0 ? -1.0 : 1.0;
  return p.center_map + p.R_map_box * local.cwiseProduct(p.half_extent_m);
}

// The site's equipment targets, then points on the structures above 1 m until `count`: every
// 5th a box of 0.5 m, every 7th to be seen from a drawn direction (+-60 deg).
std::vector<insp::Target> BenchmarkTargets(const isim::SimSite& s, int count, uint32_t seed) {
  std::vector<insp::Target> targets =
      isim::LocalTargets(sim::EquipmentTargets(s.site, sim::SessionId::kA), s.origin);
  if (static_cast<int>(targets.size()) > count) targets.resize(count);
  const std::vector<sim::Primitive>& parts = s.world->primitives();
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, parts.size() - 1);
  for (int n = 0; static_cast<int>(targets.size()) < count; ++n) {
    const Eigen::Vector3d p = SurfacePoint(parts[pick(rng)], &rng);
    const Eigen::Vector2d min = s.site.site_min_m, max = s.site.site_max_m;
    const double ground = s.site.terrain->BaseHeight(p.x(), p.y());
    if (p.x() < min.x() || p.y() < min.y() || p.x() > max.x() || p.y() > max.y() ||
        p.z() < ground + 1.0) {
      continue;
    }
    insp::Target t;
    t.id = "surface_" + std::to_string(targets.size() + 1);
    t.position = p - s.origin;
    if (n % 5 == 0) t.box_size_m = Eigen::Vector3d::Constant(0.5);
    if (n % 7 == 0) {
      t.view_azimuth_deg = std::uniform_real_distribution<double>(-180.0, 180.0)(rng);
      t.view_tolerance_deg = 60.0;
    }
    targets.push_back(t);
  }
  return targets;
}

// Planned views whose sight lines are blocked in the truth.
int ViewsNotInSight(const isim::SimSite& s, const std::vector<insp::Target>& targets,
                    const insp::InspectionPlan& plan, const insp::InspectionOptions& options) {
  int failed = 0;
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const insp::TargetPlan& t = plan.targets[i];
    if (t.status != insp::TargetStatus::kPlanned) continue;
    const insp::TargetShape shape = insp::ShapeOf(targets[i], options.visibility);
    const Eigen::Vector3d camera =
        isim::TrueCamera(s, t.view_cell, options.visibility.camera_height_m);
    if (isim::ClearLinesInTruth(s, shape, camera, 0.0) < shape.min_clear_lines) {
      ++failed;
      std::printf("  view of %s not in sight in the truth: %s\n", targets[i].id.c_str(),
                  isim::DescribeFirstHit(s, shape, camera).c_str());
    }
  }
  return failed;
}

// Samples (every 5 mm along each straight segment, nudged 1 mm to both sides) on cells that
// are neither free nor cost.
int RouteSamplesOffCostmap(const isim::SimSite& s, const insp::InspectionPlan& plan) {
  const hylo::terrain::GridGeometry& g = s.costmap.grid.geometry();
  int bad = 0;
  for (std::size_t k = 1; k < plan.waypoints.size(); ++k) {
    const Eigen::Vector2d a = plan.waypoints[k - 1].xy, b = plan.waypoints[k].xy;
    if ((b - a).norm() < 1e-9) continue;
    const Eigen::Vector2d normal = Eigen::Vector2d(a.y() - b.y(), b.x() - a.x()).normalized();
    const int n = 1 + static_cast<int>((b - a).norm() / 0.005);
    for (int i = 0; i <= n; ++i) {
      for (const double side : {-1e-3, 1e-3}) {
        const Eigen::Vector2d q = a + (b - a) * (double(i) / n) + side * normal;
        const auto cell = g.CellOfLocal(q.x(), q.y());
        const auto c = cell ? s.costmap.classes[g.Index(cell->x(), cell->y())]
                            : hylo::terrain::CellClass::kUnknown;
        bad += c != hylo::terrain::CellClass::kFree && c != hylo::terrain::CellClass::kCost;
      }
    }
  }
  return bad;
}

double WallMs() {
  return 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
                   .count();
}

void RunMain(const isim::SimSite& s, int count, uint32_t seed, Report* report) {
  const hylo::terrain::GridGeometry& g = s.costmap.grid.geometry();
  report->Set("site", "width_m", g.width * g.resolution_m);
  report->Set("site", "height_m", g.height * g.resolution_m);
  report->Set("site", "cells", static_cast<double>(g.NumCells()));
  report->Set("site", "map_points", static_cast<double>(s.map_local.size()));
  report->Set("site", "build_s", s.seconds);
  const std::vector<insp::Target> targets = BenchmarkTargets(s, count, seed);
  const insp::InspectionOptions options;
  const Eigen::Vector2d start = s.site.route_a.front() - s.origin.head<2>();
  const double cpu0 = NowMs(), wall0 = WallMs();
  const insp::InspectionPlan plan = insp::PlanInspection(s.map_local, s.costmap.grid,
                                                         s.costmap.classes, targets, start, options);
  const double cpu_s = (NowMs() - cpu0) / 1e3, wall_s = (WallMs() - wall0) / 1e3;
  const insp::InspectionSummary& m = plan.summary;
  report->Set("plan", "targets", static_cast<double>(targets.size()));
  report->Set("plan", "planned", static_cast<double>(m.planned));
  report->Set("plan", "occluded", static_cast<double>(m.occluded));
  report->Set("plan", "unreachable", static_cast<double>(m.unreachable));
  report->Set("plan", "stops", static_cast<double>(plan.stops.size()));
  report->Set("plan", "route_length_m", m.route_length_m);
  report->Set("plan", "occupancy_voxels_million",
              m.occupancy.dims.cast<double>().prod() / 1e6);
  report->Set("plan", "cpu_s", cpu_s);
  report->Set("plan", "wall_s", wall_s);
  report->Set("stages_wall_s", "reach", m.seconds_reach);
  report->Set("stages_wall_s", "occupancy", m.seconds_occupancy);
  report->Set("stages_wall_s", "visibility", m.seconds_visibility);
  report->Set("stages_wall_s", "travel_costs", m.seconds_travel_costs);
  report->Set("stages_wall_s", "tour", m.seconds_tour);
  report->Set("stages_wall_s", "route", m.seconds_route);
  report->Set("truth", "planned_views_not_in_sight",
              ViewsNotInSight(s, targets, plan, options));
  report->Set("truth", "route_samples_off_free_or_cost", RouteSamplesOffCostmap(s, plan));
  report->Set("targets", "cpu_budget_s", 10.0);
  report->Set("targets", "within_budget", cpu_s <= 10.0 ? 1.0 : 0.0);
}

// Views that fail in the truth against the clearance, on two map densities.
void RunSweep(int count, uint32_t seed, Report* report) {
  for (const double column_deg : {1.0, 0.5}) {
    isim::SimSiteOptions o;
    o.column_deg = column_deg;
    const isim::SimSite s = isim::BuildSimSite(o);
    const std::vector<insp::Target> targets = BenchmarkTargets(s, count, seed);
    for (const double clearance : {0.10, 0.15, 0.25}) {
      insp::InspectionOptions options;
      options.visibility.occupancy.clearance_m = clearance;
      const insp::InspectionPlan plan =
          insp::PlanInspection(s.map_local, s.costmap.grid, s.costmap.classes, targets,
                               s.site.route_a.front() - s.origin.head<2>(), options);
      char section[64];
      std::snprintf(section, sizeof(section), "sweep_col%.1f_clear%.2f", column_deg, clearance);
      std::printf("%s:\n", section);
      report->Set(section, "planned", static_cast<double>(plan.summary.planned));
      report->Set(section, "views_not_in_sight", ViewsNotInSight(s, targets, plan, options));
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false, sweep = false;
  int count = 100;
  uint32_t seed = 1;
  std::string json_path;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) {
      quick = true;
    } else if (std::strcmp(argv[i], "--sweep") == 0) {
      sweep = true;
    } else if (std::strcmp(argv[i], "--targets") == 0 && i + 1 < argc) {
      count = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--seed") == 0 && i + 1 < argc) {
      seed = static_cast<uint32_t>(std::atoi(argv[++i]));
    } else if (std::strcmp(argv[i], "--json") == 0 && i + 1 < argc) {
      json_path = argv[++i];
    } else {
      std::cerr << "usage: " << argv[0]
                << " [--quick] [--targets N] [--seed S] [--sweep] [--json PATH]\n";
      return 2;
    }
  }
  isim::SimSiteOptions site_options;
  site_options.seed = seed;
  if (quick) {  // a coarse map and 20 targets: the smoke test
    site_options.scan_stride = 30;
    site_options.column_deg = 1.0;
    count = std::min(count, 20);
  }
  std::printf("building the simulated site (seed %u)...\n", seed);
  const isim::SimSite site = isim::BuildSimSite(site_options);
  Report report;
  report.Set("config", "quick", quick ? 1.0 : 0.0);
  report.Set("config", "seed", seed);
  RunMain(site, count, seed, &report);
  if (sweep && !quick) RunSweep(count, seed, &report);
  report.Print(std::cout);
  if (!json_path.empty() && !report.WriteJson(json_path)) {
    std::cerr << "cannot write " << json_path << "\n";
    return 1;
  }
  return 0;
}
