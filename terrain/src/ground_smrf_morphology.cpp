#include "hylo/terrain/ground_smrf_morphology.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "hylo/common/check.h"

namespace hylo::terrain::smrf {
namespace {

struct MinOp {
  static constexpr float kNeutral = std::numeric_limits<float>::infinity();
  static float Apply(float a, float b) { return std::min(a, b); }
};
struct MaxOp {
  static constexpr float kNeutral = -std::numeric_limits<float>::infinity();
  static float Apply(float a, float b) { return std::max(a, b); }
};

// Running minima (or maxima) over windows of 2r + 1 along a line, by van Herk / Gil-Werman:
// the line is cut into blocks of w = 2r + 1; g holds the prefix extremum within each block,
// h the suffix extremum; any window spans at most two blocks, so its extremum is
// Op(h[first], g[last]). Windows are clipped at the line's ends.
template <class Op>
void FilterLine(const float* in, int n, int r, float* g, float* h, float* out) {
  const int w = 2 * r + 1;
  for (int begin = 0; begin < n; begin += w) {
    const int end = std::min(begin + w, n);
    g[begin] = in[begin];
    for (int i = begin + 1; i < end; ++i) g[i] = Op::Apply(g[i - 1], in[i]);
    h[end - 1] = in[end - 1];
    for (int i = end - 2; i >= begin; --i) h[i] = Op::Apply(h[i + 1], in[i]);
  }
  const int head = std::min(r, n);
  for (int i = 0; i < head; ++i) out[i] = g[std::min(i + r, n - 1)];  // [0, i + r]: one block
  // The window [first, last] lies in one block when `first` starts a block or lies in the
  // last one (which the window then reaches the end of); h alone covers it then.
  const int last_block = ((n - 1) / w) * w;
  for (int i = head, offset = 0; i < n; ++i, offset = offset + 1 == w ? 0 : offset + 1) {
    const int first = i - r;
    if (offset == 0 || first >= last_block) {
      out[i] = h[first];
    } else {
      out[i] = Op::Apply(h[first], g[std::min(i + r, n - 1)]);
    }
  }
}

// A grid being filtered: cols x rows values, row-major, with scratch rows for the passes.
struct Work {
  int cols = 0, rows = 0;
  std::vector<float> z, g, h, out;
  float* Row(std::vector<float>& v, int row) {
    return v.data() + static_cast<std::size_t>(row) * cols;
  }
};

// Lines along x, each filtered on its own (windows clipped at the row's ends).
template <class Op>
void FilterRows(int r, Work* work) {
  if (r == 0) return;
  for (int row = 0; row < work->rows; ++row) {
    float* line = work->Row(work->z, row);
    FilterLine<Op>(line, work->cols, r, work->g.data(), work->h.data(), work->out.data());
    std::copy_n(work->out.data(), work->cols, line);
  }
}

// Lines that go one row down and `dc` (-1, 0, +1) columns across per step: the columns and
// the two diagonals, filtered row by row so that the inner loops run along memory. The
// blocks of van Herk / Gil-Werman are cut at rows that are multiples of w on every line;
// lines end at the side edges as if continued by Op's neutral value. A window that leaves the
// grid at the top or bottom is not computed (the cell keeps its value): Apply pads the grid so
// that no cell it reads back depends on one.
template <class Op>
void FilterDownLines(int dc, int r, Work* work) {
  if (r == 0) return;
  const int w = 2 * r + 1, cols = work->cols, rows = work->rows;
  const int from = std::max(0, dc), to = cols + std::min(0, dc);  // cols with a (col - dc)
  for (int row = 0; row < rows; ++row) {
    const float* in = work->Row(work->z, row);
    float* g = work->Row(work->g, row);
    if (row % w == 0) {
      std::copy_n(in, cols, g);
      continue;
    }
    const float* above = work->Row(work->g, row - 1);
    for (int col = 0; col < from; ++col) g[col] = in[col];  // lines starting on this row
    for (int col = from; col < to; ++col) g[col] = Op::Apply(above[col - dc], in[col]);
    for (int col = to; col < cols; ++col) g[col] = in[col];
  }
  for (int row = rows - 1; row >= 0; --row) {
    const float* in = work->Row(work->z, row);
    float* h = work->Row(work->h, row);
    if (row % w == w - 1 || row == rows - 1) {
      std::copy_n(in, cols, h);
      continue;
    }
    const float* below = work->Row(work->h, row + 1);
    for (int col = 0; col < cols - to; ++col) h[col] = in[col];  // lines ending on this row
    for (int col = cols - to; col < cols - from; ++col) {        // cols with a (col + dc)
      h[col] = Op::Apply(below[col + dc], in[col]);
    }
    for (int col = cols - from; col < cols; ++col) h[col] = in[col];
  }
  const int shift = dc * r;
  const int margin = std::abs(shift);
  for (int row = r; row + r < rows; ++row) {
    const float* h = work->Row(work->h, row - r);
    const float* g = work->Row(work->g, row + r);
    float* out = work->Row(work->z, row);
    // [row - r, row + r] spans two blocks, or is one block that h and g both cover whole.
    for (int col = margin; col < cols - margin; ++col) {
      out[col] = Op::Apply(h[col - shift], g[col + shift]);
    }
  }
}

// Erosion or dilation by the octagon: the four line passes on a copy of the grid padded with
// Op's neutral value. A sum of lines equals the octagon only if the intermediate results may
// pass outside the grid (the offset (0, 2) is one step along each diagonal, through (1, 1)),
// and the row-wise passes leave a margin of r cells unfiltered. The cells each pass must get
// right lie within the reach of the passes after it (<= reach - r) of the grid, so a margin
// of `reach` (axis + 2 diagonal) keeps them clear of the unfiltered margin. `work` keeps its
// buffers from call to call (the progressive filter makes dozens of these on one grid).

int PadFor(const Octagon& element) { return element.axis + 2 * element.diagonal; }

// Copies the cols x rows grid into the middle of `work`, padded with `neutral`.
void Load(int cols, int rows, int pad, float neutral, const std::vector<float>& z, Work* work) {
  HYLO_CHECK(z.size() == static_cast<std::size_t>(cols) * rows, "one value per cell");
  work->cols = cols + 2 * pad;
  work->rows = rows + 2 * pad;
  const std::size_t size = static_cast<std::size_t>(work->cols) * work->rows;
  work->z.assign(size, neutral);
  if (work->g.size() < size) work->g.resize(size);
  if (work->h.size() < size) work->h.resize(size);
  work->out.resize(static_cast<std::size_t>(work->cols));
  for (int row = 0; row < rows; ++row) {
    std::copy_n(z.data() + static_cast<std::size_t>(row) * cols, cols,
                work->Row(work->z, row + pad) + pad);
  }
}

// Sets the pad of `work` (everything outside the middle cols x rows) to `neutral`.
void Repad(int cols, int rows, int pad, float neutral, Work* work) {
  for (int row = 0; row < work->rows; ++row) {
    float* line = work->Row(work->z, row);
    if (row < pad || row >= rows + pad) {
      std::fill_n(line, work->cols, neutral);
    } else {
      std::fill_n(line, pad, neutral);
      std::fill_n(line + pad + cols, pad, neutral);
    }
  }
}

void Store(int cols, int rows, int pad, Work* work, std::vector<float>* z) {
  for (int row = 0; row < rows; ++row) {
    std::copy_n(work->Row(work->z, row + pad) + pad, cols,
                z->data() + static_cast<std::size_t>(row) * cols);
  }
}

template <class Op>
void Passes(const Octagon& element, Work* work) {
  HYLO_CHECK(element.axis >= 0 && element.diagonal >= 0, "line half-lengths");
  FilterRows<Op>(element.axis, work);
  FilterDownLines<Op>(0, element.axis, work);
  FilterDownLines<Op>(1, element.diagonal, work);
  FilterDownLines<Op>(-1, element.diagonal, work);
}

template <class Op>
void Apply(int cols, int rows, const Octagon& element, std::vector<float>* z, Work* work) {
  const int pad = PadFor(element);
  Load(cols, rows, pad, Op::kNeutral, *z, work);
  Passes<Op>(element, work);
  Store(cols, rows, pad, work, z);
}

// The erosion stays in `work`: only its pad changes to the dilation's neutral value.
void Open(int cols, int rows, const Octagon& element, std::vector<float>* z, Work* work) {
  const int pad = PadFor(element);
  Load(cols, rows, pad, MinOp::kNeutral, *z, work);
  Passes<MinOp>(element, work);
  Repad(cols, rows, pad, MaxOp::kNeutral, work);
  Passes<MaxOp>(element, work);
  Store(cols, rows, pad, work, z);
}

}  // namespace

Octagon OctagonForRadius(int radius_cells) {
  HYLO_CHECK(radius_cells >= 1, "a radius of at least one cell");
  // A regular octagon of inradius k has its diagonal faces at k along the diagonals when the
  // diagonal lines take k (1 - 1/sqrt 2) of the reach along the axes.
  const int ideal = static_cast<int>(std::lround(radius_cells * (1.0 - 1.0 / std::sqrt(2.0))));
  Octagon octagon;
  octagon.diagonal = std::min(ideal, (radius_cells - 1) / 2);
  octagon.axis = radius_cells - 2 * octagon.diagonal;
  return octagon;
}

void Erode(int cols, int rows, const Octagon& element, std::vector<float>* z) {
  Work work;
  Apply<MinOp>(cols, rows, element, z, &work);
}

void Dilate(int cols, int rows, const Octagon& element, std::vector<float>* z) {
  Work work;
  Apply<MaxOp>(cols, rows, element, z, &work);
}

void Open(int cols, int rows, const Octagon& element, std::vector<float>* z) {
  Work work;
  Open(cols, rows, element, z, &work);
}

std::vector<uint8_t> ProgressiveFilter(const Raster& surface, double slope, int max_radius_cells,
                                       const std::function<void(int, int)>& progress) {
  // Beyond the border the surface continues flat at the border's height. Left out of the
  // windows instead (a cliff to the opening), a slope rising to the border would be opened
  // down by slope x radius there at every step and its upper edge flagged.
  const int pad = max_radius_cells;
  const int cols = surface.cols + 2 * pad, rows = surface.rows + 2 * pad;
  std::vector<float> previous(static_cast<std::size_t>(cols) * rows);
  for (int row = 0; row < rows; ++row) {
    const int r = std::clamp(row - pad, 0, surface.rows - 1);
    for (int col = 0; col < cols; ++col) {
      const int c = std::clamp(col - pad, 0, surface.cols - 1);
      previous[static_cast<std::size_t>(row) * cols + col] = surface.z[surface.Index(c, r)];
    }
  }
  std::vector<uint8_t> object(surface.Size(), 0);
  std::vector<float> opened;
  Work work;
  for (int radius = 1; radius <= max_radius_cells; ++radius) {
    opened = previous;
    Open(cols, rows, OctagonForRadius(radius), &opened, &work);
    const float threshold = static_cast<float>(slope * radius * surface.cell_m);
    for (int row = 0; row < surface.rows; ++row) {
      const std::size_t padded = static_cast<std::size_t>(row + pad) * cols + pad;
      for (int col = 0; col < surface.cols; ++col) {
        if (previous[padded + col] - opened[padded + col] > threshold) {
          object[surface.Index(col, row)] = 1;
        }
      }
    }
    previous.swap(opened);
    if (progress) progress(radius, max_radius_cells);
  }
  return object;
}

}  // namespace hylo::terrain::smrf
