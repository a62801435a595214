#pragma once
// The route as a robot drives it: a cell path (8-connected, cell centre to cell centre) cut
// into straight segments between cell centres wherever the straight line stays on passable
// cells. A segment is kept only when every cell it touches is passable, corners included: its
// supercover (every cell whose closed square the segment meets) is checked, so a straight
// segment never grazes a lethal or unknown cell either.

#include <cstddef>
#include <vector>

#include "hylo/inspection/cost_grid_search.h"

namespace hylo::inspection {

/// Calls visit(cell) for every cell of the segment between the centres of cells `a` and `b`'s
/// supercover; stops and returns false as soon as visit returns false.
template <class Visit>
bool WalkSupercover(const terrain::GridGeometry& g, std::size_t a, std::size_t b, Visit&& visit);

/// True when every cell the segment between the centres of `a` and `b` touches is passable.
bool SegmentPassable(const CostGrid& costs, std::size_t a, std::size_t b);

/// The cells of `path` kept as corners: the first, then greedily the farthest cell still in a
/// straight passable line from the last corner, ..., the last.
std::vector<std::size_t> StraightenPath(const CostGrid& costs, const std::vector<std::size_t>& path);

template <class Visit>
bool WalkSupercover(const terrain::GridGeometry& g, std::size_t a, std::size_t b, Visit&& visit) {
  int col = g.Col(a), row = g.Row(a);
  const int col_end = g.Col(b), row_end = g.Row(b);
  const int dx = std::abs(col_end - col), dy = std::abs(row_end - row);
  const int sx = col_end > col ? 1 : -1, sy = row_end > row ? 1 : -1;
  // Centre to centre: the line crosses a vertical cell edge every 1/dx of its length and a
  // horizontal one every 1/dy; compare the crossings in integers (error = dy*x - dx*y scaled).
  int crossed_x = 0, crossed_y = 0;
  if (!visit(g.Index(col, row))) return false;
  while (crossed_x < dx || crossed_y < dy) {
    // Next vertical edge at t = (2 crossed_x + 1) / (2 dx), next horizontal at (2 crossed_y + 1) / (2 dy).
    const long long tx = static_cast<long long>(2 * crossed_x + 1) * dy;
    const long long ty = static_cast<long long>(2 * crossed_y + 1) * dx;
    if (crossed_x < dx && (crossed_y >= dy || tx < ty)) {
      col += sx, ++crossed_x;
    } else if (crossed_y < dy && (crossed_x >= dx || ty < tx)) {
      row += sy, ++crossed_y;
    } else {  // through a corner: both cells beside it are touched
      if (!visit(g.Index(col + sx, row)) || !visit(g.Index(col, row + sy))) return false;
      col += sx, row += sy, ++crossed_x, ++crossed_y;
    }
    if (!visit(g.Index(col, row))) return false;
  }
  return true;
}

}  // namespace hylo::inspection
