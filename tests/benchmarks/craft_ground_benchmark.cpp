// Map crafting and ground filtering on 1M-point synthetic maps: wall time of CraftMap with 1
// and 2 MLS threads (and the thickness before/after against the known surface), and of the
// cloth simulation filter. Prints figures; asserts nothing (speed is not a unit test).
//   hylo_craft_ground_benchmark [num_points=1000000]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>

#include "hylo/terrain/cloth_filter.h"
#include "hylo/terrain/craft.h"

namespace {

using hylo::terrain::ClothFilterOptions;
using hylo::terrain::CraftOptions;

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

}  // namespace

int main(int argc, char** argv) {
  const int count = argc > 1 ? std::atoi(argv[1]) : 1000000;
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
  // Ground: 25 points/m^2 (airborne-like density), defaults (GR 1, RI 3, ST on).
  const double ground_size_m = std::sqrt(count / 25.0);
  const std::vector<Eigen::Vector3d> site = SiteWithBuildings(count, ground_size_m, 2);
  hylo::terrain::ClothFilterResult ground;
  const double ground_s =
      Seconds([&] { ground = hylo::terrain::FilterGround(site, ClothFilterOptions{}); });
  std::printf("ground: %d points, %.0f x %.0f m: %.2f s (%s)\n", count, ground_size_m,
              ground_size_m, ground_s, ground.message.c_str());
  // The fine-cloth setting for sparse airborne data (ISPRS, cloth_filter_test): 4x particles.
  ClothFilterOptions fine;
  fine.cloth_resolution_m = 0.5;
  fine.rigidness = 6;
  fine.hole_fill = hylo::terrain::ClothHoleFill::kNearest;
  const double fine_s = Seconds([&] { ground = hylo::terrain::FilterGround(site, fine); });
  std::printf("ground, GR 0.5 RI 6 nearest fill: %.2f s (%s)\n", fine_s, ground.message.c_str());
  return 0;
}
