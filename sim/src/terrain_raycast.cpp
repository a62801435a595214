// Exact ray / height-field intersection. Inside one grid cell the ground is the bilinear
// patch h(u, v) = h00 + a u + b v + c u v; along the ray u, v and z are linear in t, so
// z(t) - h(t) is a quadratic whose first root in the cell is the hit (no marching error).
#include <algorithm>
#include <cmath>

#include "hylo/sim/terrain.h"

namespace hylo::sim {
namespace {

// Smallest root of A x^2 + B x + C in [0, limit], given C > 0 (ray above ground at x = 0).
bool FirstRoot(double A, double B, double C, double limit, double* root) {
  double best = limit + 1.0;
  if (std::abs(A) < 1e-14) {
    if (B < 0.0) best = -C / B;
  } else {
    const double disc = B * B - 4.0 * A * C;
    if (disc < 0.0) return false;
    // Numerically stable pair (Press et al., Numerical Recipes 5.6).
    const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
    const double r1 = q / A;
    const double r2 = q != 0.0 ? C / q : r1;
    for (const double r : {r1, r2}) {
      if (r >= 0.0 && r < best) best = r;
    }
  }
  if (best > limit) return false;
  *root = best;
  return true;
}

}  // namespace

bool Terrain::IntersectCell(const Ray& ray, int ix, int iy, double t0, double t1,
                            SurfaceHit* hit) const {
  const double h00 = At(ix, iy), h10 = At(ix + 1, iy), h01 = At(ix, iy + 1),
               h11 = At(ix + 1, iy + 1);
  const double z0 = ray.origin.z() + t0 * ray.direction.z();
  const double z1 = ray.origin.z() + t1 * ray.direction.z();
  const double cell_top = std::max(std::max(h00, h10), std::max(h01, h11));
  if (std::min(z0, z1) > cell_top) return false;  // passes above the whole patch
  const double res = options_.resolution_m;
  const double u0 = (ray.origin.x() + t0 * ray.direction.x() - options_.min_m.x()) / res - ix;
  const double v0 = (ray.origin.y() + t0 * ray.direction.y() - options_.min_m.y()) / res - iy;
  const double du = ray.direction.x() / res, dv = ray.direction.y() / res;
  const double a = h10 - h00, b = h01 - h00, c = h00 - h10 - h01 + h11;
  const double C = z0 - (h00 + a * u0 + b * v0 + c * u0 * v0);
  const double B = ray.direction.z() - (a * du + b * dv + c * (u0 * dv + v0 * du));
  const double A = -c * du * dv;
  double tau = 0.0;
  if (C > 0.0 && !FirstRoot(A, B, C, t1 - t0, &tau)) return false;
  hit->t = t0 + tau;
  const double u = u0 + du * tau, v = v0 + dv * tau;
  hit->normal_map = Eigen::Vector3d(-(a + c * v) / res, -(b + c * u) / res, 1.0).normalized();
  return true;
}

bool Terrain::Intersect(const Ray& ray, double t_start, double t_end, SurfaceHit* hit) const {
  GridWalk2d walk(cells_, ray, t_start, t_end);
  int ix = 0, iy = 0;
  double t0 = 0.0, t1 = 0.0;
  while (walk.Next(&ix, &iy, &t0, &t1)) {
    if (IntersectCell(ray, ix, iy, t0, t1, hit)) return true;
  }
  return false;
}

double Terrain::MaxHeightIn(const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m) const {
  const double res = options_.resolution_m;
  const auto index = [&](double v, double o, int n, bool up) {
    const double g = (v - o) / res;
    return std::clamp(static_cast<int>(up ? std::ceil(g) : std::floor(g)), 0, n - 1);
  };
  const int x0 = index(min_m.x(), options_.min_m.x(), vx_, false);
  const int x1 = index(max_m.x(), options_.min_m.x(), vx_, true);
  const int y0 = index(min_m.y(), options_.min_m.y(), vy_, false);
  const int y1 = index(max_m.y(), options_.min_m.y(), vy_, true);
  double top = -1e300;
  for (int iy = y0; iy <= y1; ++iy) {
    for (int ix = x0; ix <= x1; ++ix) top = std::max(top, At(ix, iy));
  }
  return top;
}

}  // namespace hylo::sim
