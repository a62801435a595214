// plan.png: the costmap's colours with the route, the viewpoints and the targets drawn on.
#include <algorithm>
#include <array>
#include <cmath>

#include "hylo/io/inspection_io.h"

namespace hylo::io {
namespace {

using Rgb = std::array<uint8_t, 3>;
constexpr Rgb kRoute{30, 80, 255}, kView{255, 255, 255}, kPlanned{0, 230, 255},
    kOccluded{230, 0, 230}, kUnreachable{255, 140, 0}, kStart{30, 80, 255}, kOutline{0, 0, 0};

class Canvas {
 public:
  Canvas(const terrain::GridGeometry& g, int scale)
      : g_(g), scale_(scale), width_(g.width * scale), height_(g.height * scale),
        rgb_(static_cast<std::size_t>(width_) * height_ * 3, 0) {}

  void FillCell(int col, int row, const uint8_t colour[3]) {
    const int y0 = (g_.height - 1 - row) * scale_;
    for (int y = y0; y < y0 + scale_; ++y)
      for (int x = col * scale_; x < (col + 1) * scale_; ++x) Set(x, y, {colour[0], colour[1], colour[2]});
  }
  /// Pixel coordinates (continuous) of a local xy.
  Eigen::Vector2d Pixel(const Eigen::Vector2d& xy) const {
    const Eigen::Vector2d cells = (xy - g_.corner_local) / g_.resolution_m;
    return {cells.x() * scale_, height_ - cells.y() * scale_};
  }
  void Line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Rgb& colour, int half) {
    const Eigen::Vector2d pa = Pixel(a), pb = Pixel(b);
    const int steps = 1 + static_cast<int>(2.0 * (pb - pa).norm());
    for (int k = 0; k <= steps; ++k) Dot(pa + (pb - pa) * (double(k) / steps), half, colour);
  }
  void Square(const Eigen::Vector2d& xy, int half, const Rgb& fill) {
    Dot(Pixel(xy), half + 1, kOutline);
    Dot(Pixel(xy), half, fill);
  }
  void Cross(const Eigen::Vector2d& xy, int half, const Rgb& colour) {
    const Eigen::Vector2d p = Pixel(xy);
    for (int k = -half; k <= half; ++k) {
      for (const int w : {-1, 0, 1}) {
        Set(static_cast<int>(p.x()) + k, static_cast<int>(p.y()) + k + w, colour);
        Set(static_cast<int>(p.x()) + k, static_cast<int>(p.y()) - k + w, colour);
      }
    }
  }
  std::string Encode() const { return EncodePngRgb(width_, height_, rgb_); }

 private:
  void Dot(const Eigen::Vector2d& p, int half, const Rgb& colour) {
    const int cx = static_cast<int>(std::floor(p.x())), cy = static_cast<int>(std::floor(p.y()));
    for (int y = cy - half; y <= cy + half; ++y)
      for (int x = cx - half; x <= cx + half; ++x) Set(x, y, colour);
  }
  void Set(int x, int y, const Rgb& colour) {
    if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
    std::copy(colour.begin(), colour.end(), &rgb_[(static_cast<std::size_t>(y) * width_ + x) * 3]);
  }

  const terrain::GridGeometry& g_;
  int scale_, width_, height_;
  std::vector<uint8_t> rgb_;
};

}  // namespace

std::string PlanPng(const inspection::InspectionPlan& plan,
                    const std::vector<inspection::Target>& targets, const CostmapLayers& costmap) {
  const terrain::GridGeometry& g = costmap.grid.geometry();
  const int longest = std::max(g.width, g.height);
  const int scale = std::clamp((1000 + longest - 1) / std::max(1, longest), 1, 4);
  Canvas canvas(g, scale);
  const std::vector<float>& cost = costmap.grid.Layer(terrain::layers::kCost);
  for (std::size_t cell = 0; cell < g.NumCells(); ++cell) {
    uint8_t rgb[3];
    CostColour(costmap.classes[cell], cost[cell], rgb);
    canvas.FillCell(g.Col(cell), g.Row(cell), rgb);
  }
  const int half = std::max(1, scale / 2);
  for (std::size_t k = 1; k < plan.waypoints.size(); ++k)
    canvas.Line(plan.waypoints[k - 1].xy, plan.waypoints[k].xy, kRoute, half / 2);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const inspection::TargetPlan& t = plan.targets[i];
    if (t.status == inspection::TargetStatus::kPlanned)
      canvas.Line(t.camera.head<2>(), targets[i].position.head<2>(), kView, 0);
  }
  canvas.Square(g.CentreLocal(g.Col(plan.start_cell), g.Row(plan.start_cell)), 3 * half, kStart);
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const inspection::TargetPlan& t = plan.targets[i];
    if (t.status == inspection::TargetStatus::kPlanned) canvas.Square(t.camera.head<2>(), half, kView);
    const Rgb& colour = t.status == inspection::TargetStatus::kPlanned    ? kPlanned
                        : t.status == inspection::TargetStatus::kOccluded ? kOccluded
                                                                          : kUnreachable;
    canvas.Cross(targets[i].position.head<2>(), 3 * half, colour);
  }
  return canvas.Encode();
}

}  // namespace hylo::io
