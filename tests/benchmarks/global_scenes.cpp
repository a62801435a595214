// Start poses and the first seconds recorded there (global_scenes.h).
#include "global_scenes.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "hylo/sim/random.h"

namespace hylo::benchmarks {
namespace {

constexpr double kMapCellM = 2.0;        // ground coverage is judged per cell of this side
constexpr double kGroundBandM = 0.5;     // a map point this close to the terrain is ground
constexpr double kClearanceM = 1.0;      // structures keep this far from the vehicle
constexpr double kMaxSlope = 0.36;       // tan(20 deg): steeper terrain is not driven

int64_t CellKey(const Eigen::Vector2d& xy) {
  const int64_t x = static_cast<int64_t>(std::floor(xy.x() / kMapCellM));
  const int64_t y = static_cast<int64_t>(std::floor(xy.y() / kMapCellM));
  return (x << 32) ^ (y & 0xffffffff);
}

std::unordered_set<int64_t> GroundCells(const sim::Terrain& terrain, const PointCloud& map_site) {
  std::unordered_set<int64_t> cells;
  for (const Eigen::Vector3f& p : map_site) {
    const Eigen::Vector2d xy = p.head<2>().cast<double>();
    if (!terrain.Contains(xy.x(), xy.y())) continue;
    if (std::abs(p.z() - terrain.Height(xy.x(), xy.y())) < kGroundBandM) cells.insert(CellKey(xy));
  }
  return cells;
}

// No structure within kClearanceM of a 1.2 m x 1 m footprint, from 0.3 to 2 m above ground.
bool VehicleFits(const sim::World& world, const Eigen::Vector2d& xy) {
  const sim::Terrain& terrain = world.terrain();
  for (int ring = 0; ring < 2; ++ring) {
    const double radius = ring == 0 ? 0.0 : 0.8 + kClearanceM;
    for (int k = 0; k < (ring == 0 ? 1 : 12); ++k) {
      const double a = k * M_PI / 6.0;
      const Eigen::Vector2d q = xy + radius * Eigen::Vector2d(std::cos(a), std::sin(a));
      if (!terrain.Contains(q.x(), q.y())) return false;
      for (const double h : {0.3, 1.0, 2.0}) {
        const Eigen::Vector3d p(q.x(), q.y(), terrain.Height(q.x(), q.y()) + h);
        if (world.InsideAnyPrimitive(p, -0.3)) return false;
      }
    }
  }
  return true;
}

bool Drivable(const sim::Terrain& terrain, const Eigen::Vector2d& xy) {
  const double d = 0.5;
  const double gx = (terrain.BaseHeight(xy.x() + d, xy.y()) -
                     terrain.BaseHeight(xy.x() - d, xy.y())) / (2 * d);
  const double gy = (terrain.BaseHeight(xy.x(), xy.y() + d) -
                     terrain.BaseHeight(xy.x(), xy.y() - d)) / (2 * d);
  return std::hypot(gx, gy) <= kMaxSlope;
}

bool Excluded(const StartRegion& region, const Eigen::Vector2d& xy) {
  const bool has_exclusion = (region.exclude_max_m - region.exclude_min_m).minCoeff() > 0.0;
  return has_exclusion && (xy.array() >= region.exclude_min_m.array()).all() &&
         (xy.array() <= region.exclude_max_m.array()).all();
}

}  // namespace

std::vector<StartPose> SampleStartPoses(const sim::World& world, const PointCloud& map_site,
                                        const StartRegion& region, int count, uint64_t seed) {
  const std::unordered_set<int64_t> ground = GroundCells(world.terrain(), map_site);
  sim::Rng rng(seed);
  std::vector<StartPose> poses;
  const double s = region.spacing_m;
  for (double y = region.min_m.y(); y + s <= region.max_m.y() + 1e-9; y += s) {
    for (double x = region.min_m.x(); x + s <= region.max_m.x() + 1e-9; x += s) {
      const Eigen::Vector2d xy(x + rng.Uniform(0.0, s), y + rng.Uniform(0.0, s));
      const double heading = rng.Uniform(-M_PI, M_PI);
      if (Excluded(region, xy) || !Drivable(world.terrain(), xy) || !VehicleFits(world, xy)) {
        continue;
      }
      if (!map_site.empty() && ground.count(CellKey(xy)) == 0) continue;
      poses.push_back({xy, heading});
    }
  }
  // A fixed shuffle, so the first `count` are spread over the whole region.
  for (std::size_t i = poses.size(); i > 1; --i) {
    std::swap(poses[i - 1], poses[static_cast<std::size_t>(rng.NextU64() % i)]);
  }
  if (static_cast<int>(poses.size()) > count) poses.resize(static_cast<std::size_t>(count));
  return poses;
}

bool DriveIsClear(const sim::World& world, const StartPose& start, double length_m) {
  const Eigen::Vector2d dir(std::cos(start.heading_rad), std::sin(start.heading_rad));
  for (double d = 0.0; d <= length_m; d += 1.0) {
    const Eigen::Vector2d xy = start.xy_m + d * dir;
    if (!VehicleFits(world, xy) || !Drivable(world.terrain(), xy)) return false;
  }
  return true;
}

sim::SessionRecording SimulateStart(const sim::SimulationOptions& options, const sim::Site& site,
                                    sim::SessionId session, const StartPose& start,
                                    double duration_s, double drive_m) {
  sim::Site one_drive = site;
  const Eigen::Vector2d dir(std::cos(start.heading_rad), std::sin(start.heading_rad));
  // The route's first leg sets the heading; a leg of at least 2 m keeps it well defined.
  const std::vector<Eigen::Vector2d> route = {start.xy_m,
                                              start.xy_m + std::max(drive_m, 2.0) * dir};
  (session == sim::SessionId::kA ? one_drive.route_a : one_drive.route_b) = route;
  sim::SimulationOptions short_options = options;
  (session == sim::SessionId::kA ? short_options.duration_a_s : short_options.duration_b_s) =
      duration_s;
  sim::SessionRecording recording;
  sim::SessionSimulator(short_options, one_drive, session).Run(&recording);
  return recording;
}

}  // namespace hylo::benchmarks
