// Map crafting: uniform sampling + MLS must make a noisy surface thinner without moving it,
// give normals, survive UTM coordinates and bad input, and not depend on the thread count.
#include "hylo/terrain/craft.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <utility>
#include <vector>

namespace hylo::terrain {
namespace {

// A height field z = f(x, y) with its exact gradient, sampled with Gaussian noise along z.
struct Surface {
  std::function<double(double, double)> height;
  std::function<Eigen::Vector2d(double, double)> gradient;
  double DistanceApprox(const Eigen::Vector3d& p) const {  // |dz| cos(slope): fine for gentle f
    const Eigen::Vector2d g = gradient(p.x(), p.y());
    return std::abs(p.z() - height(p.x(), p.y())) / std::sqrt(1.0 + g.squaredNorm());
  }
  Eigen::Vector3d Normal(double x, double y) const {
    const Eigen::Vector2d g = gradient(x, y);
    return Eigen::Vector3d(-g.x(), -g.y(), 1.0).normalized();
  }
};

std::vector<Eigen::Vector3d> SampleNoisy(const Surface& surface, double size_m, int count,
                                         double noise_m, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, size_m);
  std::normal_distribution<double> noise(0.0, noise_m);
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < count; ++i) {
    const double x = uniform(rng), y = uniform(rng);
    points.emplace_back(x, y, surface.height(x, y) + noise(rng));
  }
  return points;
}

// RMS distance to the true surface ("thickness"), away from the border where MLS is one-sided.
double Thickness(const Surface& surface, const std::vector<Eigen::Vector3d>& points, double size_m,
                 double margin_m) {
  double sum2 = 0;
  int n = 0;
  for (const Eigen::Vector3d& p : points) {
    if (p.x() < margin_m || p.y() < margin_m || p.x() > size_m - margin_m ||
        p.y() > size_m - margin_m) {
      continue;
    }
    sum2 += std::pow(surface.DistanceApprox(p), 2);
    ++n;
  }
  return std::sqrt(sum2 / n);
}

Surface Wavy() {
  return {[](double x, double y) { return 0.4 * std::sin(0.6 * x) + 0.05 * y; },
          [](double x, double) { return Eigen::Vector2d(0.24 * std::cos(0.6 * x), 0.05); }};
}

CraftOptions TestOptions() {
  CraftOptions options;
  options.voxel_size_m = 0.05;
  options.mls_search_radius_m = 0.3;
  options.polynomial_order = 2;
  return options;
}

TEST(CraftOptions, DefaultsValidAndBadFieldsNamed) {
  std::string why;
  EXPECT_TRUE(CraftOptions{}.IsValid(&why)) << why;
  const std::vector<std::pair<std::string, std::function<void(CraftOptions*)>>> bad = {
      {"mls_search_radius_m", [](CraftOptions* o) { o->mls_search_radius_m = 0.0; }},
      {"polynomial_order", [](CraftOptions* o) { o->polynomial_order = 7; }},
      {"mls_small_radius_m",
       [](CraftOptions* o) { o->mls_small_radius_m = o->mls_search_radius_m; }},
      {"mls_support_voxel_m", [](CraftOptions* o) { o->mls_support_voxel_m = -0.01; }},
      {"scale_consistency_sigmas", [](CraftOptions* o) { o->scale_consistency_sigmas = 0.0; }},
  };
  for (const auto& [field, spoil] : bad) {
    CraftOptions options;
    spoil(&options);
    EXPECT_FALSE(options.IsValid(&why)) << field;
    EXPECT_NE(why.find(field), std::string::npos) << why;
  }
  CraftOptions options;
  options.num_threads = 0;
  EXPECT_THROW(CraftMap({{0, 0, 0}}, options), std::invalid_argument);
}

TEST(Craft, NoisyWavySurfaceBecomesAtLeastTwiceThinner) {
  const Surface surface = Wavy();
  const double size_m = 12.0;
  const auto raw = SampleNoisy(surface, size_m, 60000, 0.02, 7);  // ~400 points/m^2, 2 cm
  const CraftResult result = CraftMap(raw, TestOptions());
  ASSERT_TRUE(result.ok) << result.message;
  const double before = Thickness(surface, raw, size_m, 0.5);
  const double after = Thickness(surface, result.points_world, size_m, 0.5);
  EXPECT_LT(after, before / 2.0) << "before " << before << " m, after " << after << " m";
  EXPECT_LT(result.num_sampled, raw.size());  // 5 cm voxels merge some of 400 points/m^2
  EXPECT_EQ(result.num_dropped_by_mls, 0u);
}

// A vertical pole (radius 0.06 m, seen from all sides, as an accumulated map sees a lattice
// tower's leg) standing on a flat yard, both with Gaussian noise along the surface normal.
struct PoleScene {
  static constexpr double kPoleRadius = 0.06, kPoleHeight = 2.0, kYard = 3.0;
  std::vector<Eigen::Vector3d> points;
  Eigen::Vector2d pole_xy{1.5, 1.5};

  explicit PoleScene(uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    std::normal_distribution<double> noise(0.0, 0.015);
    for (int i = 0; i < 1500; ++i) {  // ~1000 points/m^2 of pole surface
      const double angle = 2.0 * M_PI * uniform(rng), r = kPoleRadius + noise(rng);
      points.emplace_back(pole_xy.x() + r * std::cos(angle), pole_xy.y() + r * std::sin(angle),
                          kPoleHeight * uniform(rng));
    }
    for (int i = 0; i < 9000; ++i) {  // 1000 points/m^2 of yard, outside the pole
      const Eigen::Vector2d xy(kYard * uniform(rng), kYard * uniform(rng));
      if ((xy - pole_xy).norm() < kPoleRadius) continue;
      points.emplace_back(xy.x(), xy.y(), noise(rng));
    }
  }
  // RMS distance to the pole's mantle (points at mid height) and to the yard (points 0.5 m
  // or more from the pole and from the border), m.
  std::pair<double, double> Thickness(const std::vector<Eigen::Vector3d>& cloud) const {
    double pole_sq = 0, yard_sq = 0;
    int pole_n = 0, yard_n = 0;
    for (const Eigen::Vector3d& p : cloud) {
      const double from_axis = (p.head<2>() - pole_xy).norm();
      if (p.z() > 0.3 && p.z() < kPoleHeight - 0.3 && from_axis < 0.3) {
        pole_sq += std::pow(from_axis - kPoleRadius, 2);
        ++pole_n;
      } else if (from_axis > 0.5 && p.head<2>().minCoeff() > 0.5 &&
                 p.head<2>().maxCoeff() < kYard - 0.5) {
        yard_sq += p.z() * p.z();
        ++yard_n;
      }
    }
    return {std::sqrt(pole_sq / pole_n), std::sqrt(yard_sq / yard_n)};
  }
};

// The scale test's purpose: a single 0.15 m MLS neighbourhood holds the whole circumference of
// a 0.12 m pole, so its height polynomial cuts through the pole and drags points towards the
// axis; the two-scale rule keeps the small fit there and the large one on the yard.
TEST(Craft, TwoScalesKeepAThinPoleWhereOneScaleCollapsesIt) {
  const PoleScene scene(21);
  CraftOptions single;  // defaults: 0.05 m voxel, 0.15 m radius, order 2
  single.mls_small_radius_m = 0.0;
  const CraftResult one = CraftMap(scene.points, single);
  const CraftResult two = CraftMap(scene.points, CraftOptions{});
  ASSERT_TRUE(one.ok && two.ok) << one.message << " / " << two.message;
  const auto [raw_pole, raw_yard] = scene.Thickness(scene.points);
  const auto [one_pole, one_yard] = scene.Thickness(one.points_world);
  const auto [two_pole, two_yard] = scene.Thickness(two.points_world);
  SCOPED_TRACE(::testing::Message()
               << "pole raw " << raw_pole << " one scale " << one_pole << " two scales " << two_pole
               << "; yard raw " << raw_yard << " one " << one_yard << " two " << two_yard << " m");
  EXPECT_GT(one_pole, raw_pole);  // the failure mode this rule exists for
  EXPECT_LT(two_pole, raw_pole);  // no worse than leaving the pole alone
  EXPECT_LT(two_pole, 0.5 * one_pole);
  EXPECT_LT(two_yard, 0.5 * raw_yard);  // the yard keeps the large scale's smoothing
  EXPECT_LT(two_yard, 1.15 * one_yard);
  EXPECT_GT(two.num_small_scale, 0u);
  EXPECT_LT(two.num_small_scale, two.points_world.size() / 2);  // most points are yard
}

// MLS fitted to the denser input (not only to the one-per-voxel sample) averages more noise.
TEST(Craft, DenserSupportMakesTheSurfaceThinner) {
  const Surface surface = Wavy();
  const auto raw = SampleNoisy(surface, 6.0, 60000, 0.02, 12);  // ~1700 points/m^2
  CraftOptions options = TestOptions();
  options.mls_small_radius_m = 0.0;  // one scale: only the support differs
  const CraftResult dense = CraftMap(raw, options);
  options.mls_support_voxel_m = options.voxel_size_m;
  const CraftResult sparse = CraftMap(raw, options);
  ASSERT_TRUE(sparse.ok && dense.ok);
  EXPECT_EQ(sparse.num_support, sparse.num_sampled);
  EXPECT_GT(dense.num_support, 2 * dense.num_sampled);
  const double thin_sparse = Thickness(surface, sparse.points_world, 6.0, 0.5);
  const double thin_dense = Thickness(surface, dense.points_world, 6.0, 0.5);
  EXPECT_LT(thin_dense, 0.8 * thin_sparse) << thin_sparse << " m vs " << thin_dense << " m";
}

TEST(Craft, NormalsFollowTheTrueSurface) {
  const Surface surface = Wavy();
  const CraftResult result = CraftMap(SampleNoisy(surface, 12.0, 60000, 0.02, 8), TestOptions());
  ASSERT_TRUE(result.ok) << result.message;
  ASSERT_EQ(result.normals.size(), result.points_world.size());
  int good = 0;
  for (std::size_t i = 0; i < result.normals.size(); ++i) {
    const Eigen::Vector3d& p = result.points_world[i];
    const double cos_angle =
        std::abs(result.normals[i].cast<double>().dot(surface.Normal(p.x(), p.y())));
    good += cos_angle > std::cos(5.0 * M_PI / 180.0);
    EXPECT_NEAR(result.normals[i].norm(), 1.0, 1e-4);
  }
  EXPECT_GE(good, 0.95 * result.normals.size());
}

TEST(Craft, UtmCoordinatesGiveTheSameSurfaceAsNearZero) {
  const Surface surface = Wavy();
  const auto raw = SampleNoisy(surface, 6.0, 15000, 0.02, 9);
  const Eigen::Vector3d utm(612345.25, 5712345.5, 310.0);
  std::vector<Eigen::Vector3d> shifted;
  for (const Eigen::Vector3d& p : raw) shifted.push_back(p + utm);
  const CraftResult near_zero = CraftMap(raw, TestOptions());
  const CraftResult in_utm = CraftMap(shifted, TestOptions());
  ASSERT_TRUE(in_utm.ok) << in_utm.message;
  // Voxel boundaries fall elsewhere after the shift, so compare surfaces, not point lists.
  const double thick_zero = Thickness(surface, near_zero.points_world, 6.0, 0.5);
  std::vector<Eigen::Vector3d> back;
  for (const Eigen::Vector3d& p : in_utm.points_world) back.push_back(p - utm);
  EXPECT_NEAR(Thickness(surface, back, 6.0, 0.5), thick_zero, 0.2 * thick_zero);
  EXPECT_LT(Thickness(surface, back, 6.0, 0.5), 0.012);  // float at 5e6 m would be ~0.5 m
}

TEST(Craft, TwoThreadsGiveTheSameResultAsOne) {
  const auto raw = SampleNoisy(Wavy(), 6.0, 15000, 0.02, 10);
  CraftOptions options = TestOptions();
  const CraftResult one = CraftMap(raw, options);
  options.num_threads = 2;
  const CraftResult two = CraftMap(raw, options);
  ASSERT_EQ(one.points_world.size(), two.points_world.size());
  for (std::size_t i = 0; i < one.points_world.size(); ++i) {
    EXPECT_LT((one.points_world[i] - two.points_world[i]).norm(), 1e-5) << i;
  }
}

TEST(Craft, BadInputIsReported) {
  EXPECT_FALSE(CraftMap({}, CraftOptions{}).ok);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const CraftResult all_nan = CraftMap({{nan, 0, 0}, {0, 0, nan}}, CraftOptions{});
  EXPECT_FALSE(all_nan.ok);
  EXPECT_EQ(all_nan.num_invalid, 2u);
  auto raw = SampleNoisy(Wavy(), 4.0, 5000, 0.01, 11);
  raw.push_back({nan, 1.0, 1.0});
  const CraftResult some_nan = CraftMap(raw, TestOptions());
  EXPECT_TRUE(some_nan.ok) << some_nan.message;
  EXPECT_EQ(some_nan.num_invalid, 1u);
  // Isolated points far apart: nothing to fit, reported rather than invented.
  const CraftResult sparse = CraftMap({{0, 0, 0}, {10, 0, 0}, {0, 10, 0}}, TestOptions());
  EXPECT_FALSE(sparse.ok);
  EXPECT_EQ(sparse.num_dropped_by_mls, 3u);
}

TEST(Craft, SingleHeightEverywhereStaysPut) {
  std::vector<Eigen::Vector3d> flat;
  for (int i = 0; i < 60; ++i) {
    for (int j = 0; j < 60; ++j) flat.emplace_back(0.05 * i, 0.05 * j, 2.5);
  }
  const CraftResult result = CraftMap(flat, TestOptions());
  ASSERT_TRUE(result.ok) << result.message;
  for (const Eigen::Vector3d& p : result.points_world) EXPECT_NEAR(p.z(), 2.5, 1e-4);
  for (const Eigen::Vector3f& n : result.normals) EXPECT_NEAR(std::abs(n.z()), 1.0, 1e-4);
}

}  // namespace
}  // namespace hylo::terrain
