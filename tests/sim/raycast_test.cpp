// Ray casting: every hit lies on the surface it reports, and the grid index returns exactly
// what a brute-force loop over all primitives and the whole ground returns.
#include <gtest/gtest.h>

#include <cmath>

#include "hylo/sim/primitives.h"
#include "hylo/sim/random.h"
#include "hylo/sim/site_layout.h"
#include "hylo/sim/world.h"

namespace hylo::sim {
namespace {

constexpr double kOnSurfaceTol = 1e-6;  // m

Eigen::Vector3d RandomUnit(Rng* rng) {
  Eigen::Vector3d v(rng->Gaussian(), rng->Gaussian(), rng->Gaussian());
  return v.normalized();
}

TEST(Primitives, HitsLieOnTheSurfaceAndNormalsPointOut) {
  Rng rng(7);
  const Primitive shapes[] = {
      MakeBox({1, 2, 3}, {2.0, 0.5, 1.0}, 0.7, 0.5f),
      MakeCylinder({0, 0, 0}, {1, 2, 3}, 0.4, 0.5f),
      MakeCylinder({-1, 0, 2}, {4, 0, 2}, 0.05, 0.5f),
  };
  int hits = 0;
  for (const Primitive& shape : shapes) {
    for (int i = 0; i < 2000; ++i) {
      Ray ray;
      ray.origin = shape.center_map + 6.0 * RandomUnit(&rng);
      // Aim near the centre so that most rays hit, some graze, some miss.
      const Eigen::Vector3d target = shape.center_map + 0.8 * RandomUnit(&rng);
      ray.direction = (target - ray.origin).normalized();
      SurfaceHit hit;
      if (!Intersect(shape, ray, 0.0, 100.0, &hit)) continue;
      ++hits;
      const Eigen::Vector3d p = ray.origin + hit.t * ray.direction;
      EXPECT_LT(std::abs(SignedDistance(shape, p)), kOnSurfaceTol);
      EXPECT_LE(hit.normal_map.dot(ray.direction), 1e-9) << "normal must face the ray";
      // Nothing of the solid lies before the hit: the midpoint to it is outside.
      EXPECT_GT(SignedDistance(shape, ray.origin + 0.5 * hit.t * ray.direction), 0.0);
    }
  }
  EXPECT_GT(hits, 2000);
}

TEST(Primitives, RayFromInsideReportsTheExit) {
  const Primitive box = MakeBox({0, 0, 0}, {2, 2, 2}, 0.0, 0.5f);
  Ray ray;
  ray.direction = Eigen::Vector3d::UnitX();
  SurfaceHit hit;
  ASSERT_TRUE(Intersect(box, ray, 0.0, 10.0, &hit));
  EXPECT_NEAR(hit.t, 1.0, 1e-12);
}

class SiteRaycast : public ::testing::Test {
 protected:
  void SetUp() override {
    TerrainOptions terrain;
    terrain.resolution_m = 0.4;
    site_ = BuildSite(11, terrain);
    world_ = std::make_unique<World>(site_.terrain, SessionPrimitives(site_, SessionId::kA));
  }
  // A sensor-like ray from 1.5 m above a random point of the site.
  Ray RandomRay(Rng* rng) const {
    Ray ray;
    const double x = rng->Uniform(5, 115), y = rng->Uniform(5, 75);
    ray.origin = Eigen::Vector3d(x, y, site_.terrain->Height(x, y) + 1.5);
    const double az = rng->Uniform(0, 2 * M_PI), el = rng->Uniform(-0.4, 0.5);
    ray.direction =
        Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
    return ray;
  }
  Site site_;
  std::unique_ptr<World> world_;
};

TEST_F(SiteRaycast, EachHitLiesOnThePrimitiveItHit) {
  Rng rng(3);
  int ground = 0, objects = 0;
  for (int i = 0; i < 20000; ++i) {
    const Ray ray = RandomRay(&rng);
    RayHit hit;
    if (!world_->Raycast(ray, 100.0, &hit)) continue;
    EXPECT_NEAR((hit.point_map - ray.origin).norm(), hit.range_m, 1e-9);
    if (hit.IsGround()) {
      ++ground;
      EXPECT_NEAR(hit.point_map.z(), site_.terrain->Height(hit.point_map.x(), hit.point_map.y()),
                  kOnSurfaceTol);
    } else {
      ++objects;
      EXPECT_LT(std::abs(SignedDistance(world_->primitives()[hit.primitive], hit.point_map)),
                kOnSurfaceTol);
    }
  }
  EXPECT_GT(ground, 5000);
  EXPECT_GT(objects, 500);
}

TEST_F(SiteRaycast, IndexAgreesWithBruteForce) {
  Rng rng(5);
  const double max_range = 100.0;
  for (int i = 0; i < 3000; ++i) {
    const Ray ray = RandomRay(&rng);
    double best = max_range;
    int32_t best_id = -2;
    SurfaceHit s;
    for (size_t p = 0; p < world_->primitives().size(); ++p) {
      if (Intersect(world_->primitives()[p], ray, 1e-9, best, &s)) {
        best = s.t;
        best_id = static_cast<int32_t>(p);
      }
    }
    if (site_.terrain->Intersect(ray, 0.0, best, &s) && s.t < best) {
      best = s.t;
      best_id = -1;
    }
    RayHit hit;
    const bool found = world_->Raycast(ray, max_range, &hit);
    ASSERT_EQ(found, best_id != -2) << "ray " << i;
    if (!found) continue;
    EXPECT_NEAR(hit.range_m, best, 1e-9) << "ray " << i;
    if (hit.primitive != best_id) {  // a tie on coplanar faces: both must hold the point
      ASSERT_GE(hit.primitive, 0);
      ASSERT_GE(best_id, 0);
      EXPECT_LT(std::abs(SignedDistance(world_->primitives()[best_id], hit.point_map)), 1e-6);
    }
  }
}

}  // namespace
}  // namespace hylo::sim
