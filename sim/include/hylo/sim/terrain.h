#pragma once
// The rough terrain of the site: a smooth analytic "base" shape (hills, ditches, a raised
// plateau with steep banks and a ramp, the gravel bed's raised edge, gentle undulation),
// sampled on a regular grid, plus sharp cable trenches and gravel roughness on the grid.
// The grid, bilinearly interpolated, *is* the ground that rays hit (exact intersection per
// cell); the vehicle rides on the smooth base (its tyres and suspension filter the gravel).

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/sim/primitives.h"
#include "hylo/sim/spatial_index.h"

namespace hylo::sim {

/// A Gaussian hill: height_m * exp(-r^2 / (2 sigma^2)); max slope = 0.607 height / sigma.
struct Hill {
  Eigen::Vector2d center_m = Eigen::Vector2d::Zero();
  double height_m = 1.0;  ///< peak height (negative: a hollow), m
  double sigma_m = 5.0;   ///< radius scale, m
};

/// A ditch along a segment: -depth * exp(-d^2 / (2 sigma^2)), d = distance to the segment.
struct Ditch {
  Eigen::Vector2d start_m = Eigen::Vector2d::Zero(), end_m = Eigen::Vector2d::UnitX();
  double depth_m = 0.5;  ///< depth at the centre line, m
  double sigma_m = 1.0;  ///< cross-section width scale, m
};

/// A raised plateau x >= x_min_m, y <= y_max_m with steep tanh banks (max slope
/// height / (2 bank_width)), climbable only by a ramp on its north side.
struct Plateau {
  double x_min_m = 0.0, y_max_m = 0.0;            ///< bank lines, m
  double height_m = 2.5;                          ///< plateau height above the surroundings, m
  double bank_width_m = 0.6;                      ///< tanh scale of the banks, m
  double ramp_x_min_m = 0.0, ramp_x_max_m = 0.0;  ///< ramp footprint along x, m
  double ramp_length_m = 12.0;                    ///< ramp run north of y_max_m, m
};

/// A rectangular area raised by `raise_m` with a smooth edge (the gravel bed's border).
struct RaisedBed {
  Eigen::Vector2d min_m = Eigen::Vector2d::Zero(), max_m = Eigen::Vector2d::Ones();
  double raise_m = 0.08;      ///< height of the bed above its surroundings, m
  double edge_width_m = 0.1;  ///< tanh scale of the edge, m
};

/// A cable trench: a sharp-walled cut (grid only) along a segment.
struct Trench {
  Eigen::Vector2d start_m = Eigen::Vector2d::Zero(), end_m = Eigen::Vector2d::UnitX();
  double width_m = 0.6;  ///< full width, m
  double depth_m = 0.5;  ///< depth below the base surface, m
};

/// Everything that shapes the ground.
struct TerrainShape {
  std::vector<Hill> hills;
  std::vector<Ditch> ditches;
  std::vector<Plateau> plateaus;
  std::vector<RaisedBed> beds;
  std::vector<Trench> trenches;
  double undulation_m = 0.25;             ///< amplitude of the gentle undulation, m
  double undulation_wavelength_m = 23.0;  ///< its wavelength, m
  Eigen::Vector2d undulation_phase = Eigen::Vector2d::Zero();  ///< phases, rad
};

struct TerrainOptions {
  Eigen::Vector2d min_m = Eigen::Vector2d(-15.0, -15.0);  ///< grid lower-left corner, m
  Eigen::Vector2d max_m = Eigen::Vector2d(135.0, 95.0);   ///< grid upper-right corner, m
  double resolution_m = 0.2;                              ///< grid spacing, m
  double gravel_sigma_m = 0.015;  ///< gravel roughness (per grid vertex, Gaussian), m
  float reflectivity = 0.3f;      ///< diffuse reflectivity of gravel/soil

  bool IsValid(std::string* why) const;
};

class Terrain {
 public:
  Terrain(const TerrainShape& shape, const TerrainOptions& options, uint64_t seed);

  /// Smooth analytic ground (no trenches, no gravel), m. The vehicle rides on this.
  double BaseHeight(double x_m, double y_m) const;
  /// The ground that rays hit: bilinear interpolation of the grid (trenches, gravel), m.
  double Height(double x_m, double y_m) const;
  /// Grid height without gravel (base + trenches), for the true slope.
  double CleanHeight(double x_m, double y_m) const;
  /// Upward unit normal of the ray-cast ground at (x, y).
  Eigen::Vector3d Normal(double x_m, double y_m) const;

  /// First ground crossing of the ray for t in [t_start, t_end]; false if none.
  bool Intersect(const Ray& ray, double t_start, double t_end, SurfaceHit* hit) const;
  /// Highest grid vertex within the xy rectangle (inclusive of touching vertices), m.
  double MaxHeightIn(const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m) const;

  /// Ground crossing inside height cell (ix, iy) for t in [t0, t1] (the ray's interval in
  /// that cell), for callers that walk the cells themselves.
  bool IntersectCell(const Ray& ray, int ix, int iy, double t0, double t1, SurfaceHit* hit) const;
  /// The height cells (vertices at their corners).
  const Grid2d& cells() const { return cells_; }

  bool Contains(double x_m, double y_m) const;
  const TerrainOptions& options() const { return options_; }
  const TerrainShape& shape() const { return shape_; }
  double max_height_m() const { return max_height_m_; }

 private:
  double Bilinear(const std::vector<double>& values, double x_m, double y_m) const;
  double At(int ix, int iy) const { return height_[iy * vx_ + ix]; }

  TerrainShape shape_;
  TerrainOptions options_;
  Grid2d cells_;                // height cells: vertices are the cell corners
  int vx_ = 0, vy_ = 0;         // vertices along x and y
  std::vector<double> height_;  // with trenches and gravel
  std::vector<double> clean_;   // with trenches, no gravel
  double max_height_m_ = 0.0;
};

}  // namespace hylo::sim
