#include "hylo/terrain/cloth_filter_cloth.h"

#include <algorithm>
#include <cmath>

#include "hylo/common/check.h"

namespace hylo::terrain::cloth {

ClothGrid ClothGrid::Covering(const Eigen::Vector2d& min_xy, const Eigen::Vector2d& max_xy,
                              double resolution_m, int buffer_cells) {
  HYLO_CHECK(resolution_m > 0.0 && buffer_cells >= 0, "grid resolution and buffer");
  HYLO_CHECK((max_xy.array() >= min_xy.array()).all(), "bounding box min <= max");
  ClothGrid grid;
  grid.resolution_m = resolution_m;
  grid.origin_xy = min_xy - Eigen::Vector2d::Constant(buffer_cells * resolution_m);
  const Eigen::Vector2d extent = (max_xy - min_xy) / resolution_m;
  grid.cols = static_cast<int>(std::floor(extent.x())) + 2 * buffer_cells;
  grid.rows = static_cast<int>(std::floor(extent.y())) + 2 * buffer_cells;
  return grid;
}

namespace {

// Springs of a particle as (dcol, drow) offsets: first the 8 immediate neighbours (grid
// distance 1 and sqrt(2)), then the 8 secondary ones (distance 2 and 2 sqrt(2)), the model of
// the reference implementation (jianboqi/CSF). The order is the order in which that
// implementation ends up visiting a particle's springs; it matters a little because the
// constraint sweep updates heights in place.
constexpr int kSpringOffsets[16][2] = {{-1, -1}, {-1, 0}, {-1, 1},  {0, -1}, {1, -1}, {1, 0},
                                       {0, 1},   {1, 1},  {-2, -2}, {-2, 0}, {-2, 2}, {0, -2},
                                       {2, -2},  {2, 0},  {0, 2},   {2, 2}};

// The paper's rigidness RI is the number of times a constraint is satisfied per step (Sec. 2.2).
// The reference implementation moves a particle by 0.3 of the height gap per pass and applies
// the RI passes in one go: a movable particle tied to a pinned one closes 1 - 0.7^RI of the gap;
// two movable particles close 1 - 0.4^RI of it together, half each.
constexpr double kPassFraction = 0.3;

double SingleFactor(int rigidness) { return 1.0 - std::pow(1.0 - kPassFraction, rigidness); }

double PairFactor(int rigidness) {
  return 0.5 * (1.0 - std::pow(1.0 - 2.0 * kPassFraction, rigidness));
}

}  // namespace

Cloth::Cloth(const ClothGrid& grid, double start_height_m, const ClothDynamics& dynamics)
    : grid_(grid),
      dynamics_(dynamics),
      pair_factor_(PairFactor(dynamics.rigidness)),
      single_factor_(SingleFactor(dynamics.rigidness)),
      height_(grid.Size(), start_height_m),
      previous_height_(grid.Size(), start_height_m),
      movable_(grid.Size(), 1) {
  HYLO_CHECK(grid.cols > 0 && grid.rows > 0, "non-empty grid");
  HYLO_CHECK(dynamics.rigidness >= 1, "rigidness >= 1");
  BuildSprings();
}

void Cloth::BuildSprings() {
  spring_begin_.assign(grid_.Size() + 1, 0);
  spring_end_.clear();
  spring_end_.reserve(grid_.Size() * 16);
  for (int row = 0; row < grid_.rows; ++row) {
    for (int col = 0; col < grid_.cols; ++col) {
      for (const auto& offset : kSpringOffsets) {
        const int c = col + offset[0], r = row + offset[1];
        if (grid_.Contains(c, r)) spring_end_.push_back(static_cast<uint32_t>(grid_.Index(c, r)));
      }
      spring_begin_[grid_.Index(col, row) + 1] = static_cast<uint32_t>(spring_end_.size());
    }
  }
}

double Cloth::Step(const std::vector<double>& surface_height_m) {
  HYLO_CHECK(surface_height_m.size() == height_.size(), "one surface height per particle");
  ApplyGravity();
  SatisfyConstraints();
  // previous_height_ holds the height before this step for every movable particle.
  double max_move_m = 0.0;
  for (std::size_t i = 0; i < height_.size(); ++i) {
    if (movable_[i]) max_move_m = std::max(max_move_m, std::abs(height_[i] - previous_height_[i]));
  }
  Collide(surface_height_m);
  return max_move_m;
}

// Paper Eq. (3), vertical only: X(t+dT) = X(t) + (1 - damping)(X(t) - X(t-dT)) + G dT^2.
void Cloth::ApplyGravity() {
  const double fall_m = dynamics_.gravity * dynamics_.time_step * dynamics_.time_step;
  const double keep = 1.0 - dynamics_.damping;
  for (std::size_t i = 0; i < height_.size(); ++i) {
    if (!movable_[i]) continue;
    const double current = height_[i];
    height_[i] = current + keep * (current - previous_height_[i]) - fall_m;
    previous_height_[i] = current;
  }
}

// Internal forces (paper Sec. 2.2, Eq. (5)-(6)): particles move vertically towards the
// particles they are tied to. One sweep per step over the particles in grid order; each
// particle relaxes each of its springs in place (Gauss-Seidel), so every spring is relaxed
// from both of its ends, with the RI passes folded into the factors (see PairFactor).
void Cloth::SatisfyConstraints() {
  const std::size_t count = height_.size();
  for (std::size_t a = 0; a < count; ++a) {
    const bool a_moves = movable_[a] != 0;
    for (uint32_t s = spring_begin_[a]; s < spring_begin_[a + 1]; ++s) {
      const uint32_t b = spring_end_[s];
      const bool b_moves = movable_[b] != 0;
      const double gap_m = height_[b] - height_[a];
      if (a_moves && b_moves) {
        height_[a] += pair_factor_ * gap_m;
        height_[b] -= pair_factor_ * gap_m;
      } else if (a_moves) {
        height_[a] += single_factor_ * gap_m;
      } else if (b_moves) {
        height_[b] -= single_factor_ * gap_m;
      }
    }
  }
}

// Collision (paper Sec. 2.2): a particle that falls below the surface under it is put on the
// surface and stops moving.
void Cloth::Collide(const std::vector<double>& surface_height_m) {
  for (std::size_t i = 0; i < height_.size(); ++i) {
    if (movable_[i] && height_[i] < surface_height_m[i]) Pin(i, surface_height_m[i]);
  }
}

void Cloth::Pin(std::size_t index, double height_m) {
  HYLO_CHECK(index < height_.size(), "particle index");
  height_[index] = height_m;
  previous_height_[index] = height_m;
  movable_[index] = 0;
}

double Cloth::HeightAt(const Eigen::Vector2d& xy) const {
  const Eigen::Vector2d cell = (xy - grid_.origin_xy) / grid_.resolution_m;
  const int col =
      std::clamp(static_cast<int>(std::floor(cell.x())), 0, std::max(grid_.cols - 2, 0));
  const int row =
      std::clamp(static_cast<int>(std::floor(cell.y())), 0, std::max(grid_.rows - 2, 0));
  const int col1 = std::min(col + 1, grid_.cols - 1);
  const int row1 = std::min(row + 1, grid_.rows - 1);
  const double fx = std::clamp(cell.x() - col, 0.0, 1.0);
  const double fy = std::clamp(cell.y() - row, 0.0, 1.0);
  const double h00 = height_[grid_.Index(col, row)];
  const double h10 = height_[grid_.Index(col1, row)];
  const double h01 = height_[grid_.Index(col, row1)];
  const double h11 = height_[grid_.Index(col1, row1)];
  return (1 - fy) * ((1 - fx) * h00 + fx * h10) + fy * ((1 - fx) * h01 + fx * h11);
}

Eigen::Vector2d Cloth::GradientAt(const Eigen::Vector2d& xy) const {
  const double h = 0.5 * grid_.resolution_m;
  const Eigen::Vector2d dx(h, 0.0), dy(0.0, h);
  return Eigen::Vector2d(HeightAt(xy + dx) - HeightAt(xy - dx),
                         HeightAt(xy + dy) - HeightAt(xy - dy)) /
         (2.0 * h);
}

}  // namespace hylo::terrain::cloth
