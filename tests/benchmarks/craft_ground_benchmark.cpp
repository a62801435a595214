// Map crafting and ground filtering on 1M-point synthetic maps: wall time of CraftMap with 1
// and 2 MLS threads (and the thickness before/after against the known surface), and the CPU
// time of each ground back-end (SMRF and the cloth filter side by side, one core). Prints
// figures; asserts nothing (speed is not a unit test).
//   hylo_craft_ground_benchmark [num_points=1000000] [--ground-only]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "benchmark_common.h"
#include "hylo/terrain/craft.h"
#include "hylo/terrain/ground_filter.h"

namespace {

using hylo::terrain::CraftOptions;
using hylo::terrain::GroundFilterOptions;
using hylo::terrain::GroundMethod;

double Terrain(double x, double y) { return 0.3 * std::sin(0.2 * x) + 0.02 * y; }

// A dense ground-robot map: terrain with 3 cm noise along z, over a square of `size_m`.
std::vector<Eigen::Vector3d> NoisyTerrain(int count, double size_m, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, size_m);
  std::normal_distribution<double> noise(0.0, 0.03);
  std::vector<Eigen::Vector3d> points;
  points.reserve(count);
  for (int i = 0; i < count; ++i) {
    const double x = uniform(rng), y = uniform(rng);
    points.emplace_back(x, y, Terrain(x, y) + noise(rng));
  }
  return points;
}

// The same terrain with 20 box-shaped buildings (roofs replace the ground under them).
std::vector<Eigen::Vector3d> SiteWithBuildings(int count, double size_m, uint32_t seed) {
  std::vector<Eigen::Vector3d> points = NoisyTerrain(count, size_m, seed);
  std::mt19937 rng(seed + 1);
  std::uniform_real_distribution<double> corner(0.0, size_m - 20.0), side(5.0, 20.0);
  for (int b = 0; b < 20; ++b) {
    const double x0 = corner(rng), y0 = corner(rng), x1 = x0 + side(rng), y1 = y0 + side(rng);
    for (Eigen::Vector3d& p : points) {
      if (p.x() >= x0 && p.x() <= x1 && p.y() >= y0 && p.y() <= y1) p.z() += 6.0;
    }
  }
  return points;
}

// Sparse airborne-like sampling: `count` points at 1 per m^2 with the same buildings.
std::vector<Eigen::Vector3d> SparseSite(int count, uint32_t seed) {
  return SiteWithBuildings(count, std::sqrt(static_cast<double>(count)), seed);
}

double RmsToTerrain(const std::vector<Eigen::Vector3d>& points) {
  double sum2 = 0;
  for (const Eigen::Vector3d& p : points) sum2 += std::pow(p.z() - Terrain(p.x(), p.y()), 2);
  return std::sqrt(sum2 / points.size());
}

template <typename F>
double Seconds(F&& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Times one ground back-end on `points`: thread CPU time (one core) and wall time.
void TimeGround(const char* label, const std::vector<Eigen::Vector3d>& points,
                const GroundFilterOptions& options) {
  hylo::terrain::GroundFilterResult result;
  const double cpu_start_ms = hylo::benchmarks::NowMs();
  const double wall_s = Seconds([&] { result = hylo::terrain::ExtractGround(points, options); });
  const double cpu_s = 1e-3 * (hylo::benchmarks::NowMs() - cpu_start_ms);
  std::printf("  %-44s %6.2f s CPU (%5.2f s wall)  %s\n", label, cpu_s, wall_s,
              result.message.c_str());
}

void CraftTimings(int count) {
  // Crafting: 400 points/m^2 (a dense accumulated SLAM map), 5 cm voxels, 15 cm MLS radius.
  const double craft_size_m = std::sqrt(count / 400.0);
  const std::vector<Eigen::Vector3d> raw = NoisyTerrain(count, craft_size_m, 1);
  CraftOptions craft;
  craft.voxel_size_m = 0.05;
  craft.mls_search_radius_m = 0.15;
  craft.polynomial_order = 2;
  std::printf("craft: %d points, %.0f x %.0f m, voxel %.2f m, MLS radius %.2f m, order %d\n", count,
              craft_size_m, craft_size_m, craft.voxel_size_m, craft.mls_search_radius_m,
              craft.polynomial_order);
  std::printf("  thickness (RMS to the true surface) before: %.4f m\n", RmsToTerrain(raw));
  for (const int threads : {1, 2}) {
    craft.num_threads = threads;
    hylo::terrain::CraftResult result;
    const double total = Seconds([&] { result = hylo::terrain::CraftMap(raw, craft); });
    std::printf(
        "  threads %d: total %.2f s (sampling %.2f s, MLS %.2f s), %zu -> %zu points, "
        "thickness after %.4f m\n",
        threads, total, result.sampling_seconds, result.mls_seconds, result.num_sampled,
        result.points_world.size(), RmsToTerrain(result.points_world));
  }
}

}  // namespace

int main(int argc, char** argv) {
  int count = 1000000;
  bool ground_only = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    char* end = nullptr;
    const long value = std::strtol(arg.c_str(), &end, 10);
    if (arg == "--ground-only") {
      ground_only = true;
    } else if (!arg.empty() && *end == '\0' && value > 0 && value <= 100000000) {
      count = static_cast<int>(value);
    } else {
      // --help, a typo or a count out of range: a usage line, never a run on 0 points.
      std::fprintf(arg == "--help" || arg == "-h" ? stdout : stderr,
                   "usage: %s [num_points=1000000, 1..1e8] [--ground-only]\n", argv[0]);
      return arg == "--help" || arg == "-h" ? 0 : 2;
    }
  }
  if (!ground_only) CraftTimings(count);
  // Ground, 25 points/m^2 (a dense airborne or a thinned robot map) with 20 buildings.
  const double ground_size_m = std::sqrt(count / 25.0);
  const std::vector<Eigen::Vector3d> site = SiteWithBuildings(count, ground_size_m, 2);
  std::printf("ground: %d points, %.0f x %.0f m, 25 points/m^2\n", count, ground_size_m,
              ground_size_m);
  GroundFilterOptions smrf;  // the defaults: SMRF, leave-one-out choice
  TimeGround("SMRF, defaults (c 1, w 24 m)", site, smrf);
  GroundFilterOptions csf;
  csf.method = GroundMethod::kCsf;
  TimeGround("cloth, defaults (GR 0.5, RI 6, nearest fill)", site, csf);
  csf.csf = {};
  TimeGround("cloth, the paper's (GR 1, RI 3)", site, csf);
  // The same number of points at airborne density (1 per m^2): SMRF's grid is 25x larger.
  // The cloth would need 4M particles at GR 0.5 (minutes), so it is left out here.
  const std::vector<Eigen::Vector3d> sparse = SparseSite(count, 3);
  std::printf("ground: %d points, %.0f x %.0f m, 1 point/m^2\n", count, std::sqrt(1.0 * count),
              std::sqrt(1.0 * count));
  TimeGround("SMRF, defaults (c 1, w 24 m)", sparse, smrf);
  return 0;
}
