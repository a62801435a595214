#pragma once
// The cloth of the cloth simulation filter (Zhang et al. 2016, Sec. 2.2): a regular grid of
// particles that move only vertically, under gravity (Verlet integration) and internal
// constraints (structural, shear and bend springs, as in the reference implementation
// jianboqi/CSF), and stop when they reach the inverted surface.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace hylo::terrain::cloth {

/// Horizontal layout: particle (col, row) sits at origin_xy + resolution_m * (col, row).
struct ClothGrid {
  Eigen::Vector2d origin_xy = Eigen::Vector2d::Zero();  ///< position of particle (0, 0), m
  double resolution_m = 1.0;                            ///< particle spacing, m
  int cols = 0;                                         ///< particles along x
  int rows = 0;                                         ///< particles along y

  /// Grid covering [min_xy, max_xy] with `buffer_cells` extra particles on every side, so
  /// that points at the border have particles all around them.
  static ClothGrid Covering(const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy,
                            double resolution_m, int buffer_cells);

  std::size_t Size() const { return static_cast<std::size_t>(cols) * rows; }
  std::size_t Index(int col, int row) const { return static_cast<std::size_t>(row) * cols + col; }
  bool Contains(int col, int row) const { return col >= 0 && row >= 0 && col < cols && row < rows; }
};

/// Dynamics parameters (taken from ClothFilterOptions by the filter).
struct ClothDynamics {
  double gravity = 0.2;     ///< acceleration, cloth units per step^2
  double time_step = 0.65;  ///< paper dT
  double damping = 0.01;    ///< velocity fraction lost per step
  int rigidness = 3;        ///< paper RI: constraint passes per step, applied in closed form
};

class Cloth {
 public:
  /// All particles start movable, at rest, at `start_height_m` (above the inverted surface).
  Cloth(const ClothGrid& grid, double start_height_m, const ClothDynamics& dynamics);

  /// One simulation step: gravity, internal constraints, collision with `surface_height_m`
  /// (one height per particle). Returns the largest vertical move, over gravity and
  /// constraints, of the particles still movable before the collision check, m (0 when none
  /// is movable: the cloth has settled).
  double Step(const std::vector<double>& surface_height_m);

  /// Fixes particle `index` at `height_m` (it no longer moves).
  void Pin(std::size_t index, double height_m);

  /// Cloth height at a horizontal position, bilinear between the 4 surrounding particles
  /// (clamped to the grid).
  double HeightAt(const Eigen::Vector2d& xy) const;

  /// Horizontal gradient of HeightAt (m per m), by central differences half a particle
  /// spacing either side of `xy`.
  Eigen::Vector2d GradientAt(const Eigen::Vector2d& xy) const;

  const ClothGrid& grid() const { return grid_; }
  const std::vector<double>& heights() const { return height_; }
  bool IsMovable(std::size_t index) const { return movable_[index] != 0; }

 private:
  void BuildSprings();
  void ApplyGravity();
  void SatisfyConstraints();
  void Collide(const std::vector<double>& surface_height_m);

  ClothGrid grid_;
  ClothDynamics dynamics_;
  double pair_factor_ = 0.0;             ///< gap fraction each of two movable particles closes
  double single_factor_ = 0.0;           ///< gap fraction a movable particle closes to a pinned one
  std::vector<uint32_t> spring_begin_;   ///< springs of particle i: spring_end_[begin[i]..[i+1])
  std::vector<uint32_t> spring_end_;     ///< the particle at the other end of each spring
  std::vector<double> height_;           ///< current height per particle, m
  std::vector<double> previous_height_;  ///< height one step ago (Verlet), m
  std::vector<uint8_t> movable_;         ///< 1 while the particle may move
};

}  // namespace hylo::terrain::cloth
