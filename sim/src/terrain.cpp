// Terrain construction: analytic base shape sampled on the grid, trenches cut, gravel added.
#include "hylo/sim/terrain.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "hylo/common/check.h"
#include "hylo/sim/random.h"

namespace hylo::sim {
namespace {

// Distance from p to segment [a, b] and the clamped segment parameter in [0, 1].
double SegmentDistance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                       double* param) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  if (param != nullptr) *param = s;
  return (p - (a + s * ab)).norm();
}

// Smooth step from 0 (v << 0) to 1 (v >> 0) with tanh scale w.
double Rise(double v, double w) { return 0.5 * (1.0 + std::tanh(v / w)); }

double PlateauHeight(const Plateau& p, double x, double y) {
  const double s_x = Rise(x - p.x_min_m, p.bank_width_m);
  const double s_bank = Rise(p.y_max_m - y, p.bank_width_m);
  const double r = std::clamp((p.y_max_m + p.ramp_length_m - y) / p.ramp_length_m, 0.0, 1.0);
  const double s_ramp = r * r * (3.0 - 2.0 * r);  // smoothstep: C1 at both ends
  // Lateral window of the ramp (1 between ramp_x_min and ramp_x_max, steep side walls).
  const double w_x = Rise(x - p.ramp_x_min_m, 0.4) - Rise(x - p.ramp_x_max_m, 0.4);
  const double s_y = s_bank + w_x * std::max(s_ramp - s_bank, 0.0);
  return p.height_m * s_x * s_y;
}

}  // namespace

bool TerrainOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  if (!(resolution_m > 0.0))
    os << "resolution_m = " << resolution_m << " must be > 0";
  else if (!((max_m - min_m).array() > 2.0 * resolution_m).all())
    os << "max_m must exceed min_m by at least two cells";
  else if (!(gravel_sigma_m >= 0.0))
    os << "gravel_sigma_m = " << gravel_sigma_m << " < 0";
  else if (!(reflectivity >= 0.f && reflectivity <= 1.f))
    os << "reflectivity = " << reflectivity << " must be in [0, 1]";
  if (why != nullptr) *why = os.str();
  return os.str().empty();
}

Terrain::Terrain(const TerrainShape& shape, const TerrainOptions& options, uint64_t seed)
    : shape_(shape), options_(options) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument("TerrainOptions: " + why);
  const double res = options.resolution_m;
  vx_ = static_cast<int>(std::lround((options.max_m.x() - options.min_m.x()) / res)) + 1;
  vy_ = static_cast<int>(std::lround((options.max_m.y() - options.min_m.y()) / res)) + 1;
  cells_ = Grid2d{options.min_m, res, vx_ - 1, vy_ - 1};
  height_.resize(static_cast<size_t>(vx_) * vy_);
  clean_.resize(height_.size());
  Rng rng = Rng::Derive(seed, 0x7e11a1);
  max_height_m_ = -1e300;
  for (int iy = 0; iy < vy_; ++iy) {
    for (int ix = 0; ix < vx_; ++ix) {
      const Eigen::Vector2d p = options.min_m + res * Eigen::Vector2d(ix, iy);
      double h = BaseHeight(p.x(), p.y());
      for (const Trench& trench : shape.trenches) {
        double s = 0.0;
        const double d = SegmentDistance(p, trench.start_m, trench.end_m, &s);
        if (d <= 0.5 * trench.width_m && s > 0.0 && s < 1.0) h -= trench.depth_m;
      }
      const size_t i = static_cast<size_t>(iy) * vx_ + ix;
      clean_[i] = h;
      height_[i] = h + rng.Gaussian(options.gravel_sigma_m);
      max_height_m_ = std::max(max_height_m_, height_[i]);
    }
  }
}

double Terrain::BaseHeight(double x, double y) const {
  const Eigen::Vector2d p(x, y);
  double h = 0.0;
  for (const Hill& hill : shape_.hills) {
    h += hill.height_m *
         std::exp(-(p - hill.center_m).squaredNorm() / (2.0 * hill.sigma_m * hill.sigma_m));
  }
  for (const Ditch& ditch : shape_.ditches) {
    const double d = SegmentDistance(p, ditch.start_m, ditch.end_m, nullptr);
    h -= ditch.depth_m * std::exp(-d * d / (2.0 * ditch.sigma_m * ditch.sigma_m));
  }
  for (const Plateau& plateau : shape_.plateaus) h += PlateauHeight(plateau, x, y);
  for (const RaisedBed& bed : shape_.beds) {
    const double w = bed.edge_width_m;
    const double in_x = Rise(x - bed.min_m.x(), w) - Rise(x - bed.max_m.x(), w);
    const double in_y = Rise(y - bed.min_m.y(), w) - Rise(y - bed.max_m.y(), w);
    h += bed.raise_m * in_x * in_y;
  }
  const double k = 2.0 * M_PI / shape_.undulation_wavelength_m;
  h += shape_.undulation_m * std::sin(k * x + shape_.undulation_phase.x()) *
       std::sin(0.8 * k * y + shape_.undulation_phase.y());
  return h;
}

bool Terrain::Contains(double x, double y) const {
  return x >= options_.min_m.x() && y >= options_.min_m.y() && x <= cells_.Max().x() &&
         y <= cells_.Max().y();
}

double Terrain::Bilinear(const std::vector<double>& values, double x, double y) const {
  const double gx = std::clamp((x - options_.min_m.x()) / options_.resolution_m, 0.0,
                               static_cast<double>(vx_ - 1));
  const double gy = std::clamp((y - options_.min_m.y()) / options_.resolution_m, 0.0,
                               static_cast<double>(vy_ - 1));
  const int ix = std::min(static_cast<int>(gx), vx_ - 2);
  const int iy = std::min(static_cast<int>(gy), vy_ - 2);
  const double u = gx - ix, v = gy - iy;
  const size_t i = static_cast<size_t>(iy) * vx_ + ix;
  return (1 - u) * (1 - v) * values[i] + u * (1 - v) * values[i + 1] +
         (1 - u) * v * values[i + vx_] + u * v * values[i + vx_ + 1];
}

double Terrain::Height(double x, double y) const { return Bilinear(height_, x, y); }
double Terrain::CleanHeight(double x, double y) const { return Bilinear(clean_, x, y); }

Eigen::Vector3d Terrain::Normal(double x, double y) const {
  const double res = options_.resolution_m;
  const double gx = std::clamp((x - options_.min_m.x()) / res, 0.0, vx_ - 1.0);
  const double gy = std::clamp((y - options_.min_m.y()) / res, 0.0, vy_ - 1.0);
  const int ix = std::min(static_cast<int>(gx), vx_ - 2);
  const int iy = std::min(static_cast<int>(gy), vy_ - 2);
  const double u = gx - ix, v = gy - iy;
  const double h00 = At(ix, iy), h10 = At(ix + 1, iy), h01 = At(ix, iy + 1),
               h11 = At(ix + 1, iy + 1);
  const double c = h00 - h10 - h01 + h11;
  const double dh_dx = (h10 - h00 + c * v) / res, dh_dy = (h01 - h00 + c * u) / res;
  return Eigen::Vector3d(-dh_dx, -dh_dy, 1.0).normalized();
}

}  // namespace hylo::sim
