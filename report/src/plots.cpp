// Data files and gnuplot scripts of the report's figures. Each data set is one gnuplot
// "index" block (two blank lines apart), so one file holds a whole figure.
#include "hylo/report/plots.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace hylo::report {
namespace {

// Distinct, colour-blind-safe colours (Okabe & Ito 2008); ground truth is drawn in black.
const char* const kColours[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9"};
constexpr int kNumColours = sizeof(kColours) / sizeof(kColours[0]);

std::string DataPath(const std::string& png_path) {
  const std::size_t dot = png_path.rfind(".png");
  return (dot == std::string::npos ? png_path : png_path.substr(0, dot)) + ".dat";
}

// gnuplot runs in the image's folder (gnuplot.h): scripts name the data by file name.
std::string FileName(const std::string& path) {
  return std::filesystem::path(path).filename().string();
}

bool IsTruth(const std::string& label) { return label == "ground truth"; }

std::string LineStyle(const std::string& label, int index, int width) {
  std::ostringstream s;
  s << "lw " << width << " lc rgb '" << (IsTruth(label) ? "#000000" : kColours[index % kNumColours])
    << "'" << (IsTruth(label) ? " dt 2" : "");
  return s.str();
}

// Writes the map block (index 0) and one block per line; false when the file cannot be written.
bool WriteTopViewData(const std::string& path, const std::vector<Eigen::Vector3d>& map_points,
                      const std::vector<TrajectoryLine>& lines, std::size_t max_points) {
  const std::size_t stride = std::max<std::size_t>(
      1, (map_points.size() + max_points - 1) / std::max<std::size_t>(1, max_points));
  std::ofstream out(path);
  out << "# x_m y_m\n# map points (every " << stride << ". of " << map_points.size() << ")\n";
  for (std::size_t i = 0; i < map_points.size(); i += stride) {
    out << map_points[i].x() << ' ' << map_points[i].y() << '\n';
  }
  if (map_points.empty()) out << "NaN NaN\n";  // keeps the block numbering
  for (const TrajectoryLine& line : lines) {
    out << "\n\n# " << line.label << '\n';
    for (const Eigen::Vector3d& p : line.positions_map) out << p.x() << ' ' << p.y() << '\n';
    if (line.positions_map.empty()) out << "NaN NaN\n";
  }
  return static_cast<bool>(out);
}

bool WriteErrorData(const std::string& path, const std::vector<ErrorCurve>& curves) {
  std::ofstream out(path);
  out << "# t_s error_m\n";
  for (std::size_t c = 0; c < curves.size(); ++c) {
    if (c > 0) out << "\n\n";
    out << "# " << curves[c].label << '\n';
    const std::size_t n = std::min(curves[c].t_s.size(), curves[c].error_m.size());
    for (std::size_t i = 0; i < n; ++i)
      out << curves[c].t_s[i] << ' ' << curves[c].error_m[i] << '\n';
    if (n == 0) out << "NaN NaN\n";
  }
  return static_cast<bool>(out);
}

PlotFile Draw(const std::string& png_path, const std::string& title, const std::string& body,
              const PlotOptions& options) {
  PlotFile file;
  file.title = title;
  file.path = png_path;
  const GnuplotResult result = RenderPng(png_path, body, options.gnuplot);
  file.ok = result.ok;
  file.message = result.message;
  return file;
}

PlotFile NoData(const std::string& png_path, const std::string& title, const std::string& why) {
  PlotFile file;
  file.title = title;
  file.path = png_path;
  file.message = why;
  return file;
}

}  // namespace

PlotFile PlotTopView(const std::string& png_path, const std::string& title,
                     const std::vector<Eigen::Vector3d>& map_points,
                     const std::vector<TrajectoryLine>& lines, const PlotOptions& options) {
  bool any_line = false;
  for (const TrajectoryLine& line : lines) any_line |= !line.positions_map.empty();
  if (map_points.empty() && !any_line) return NoData(png_path, title, "no map and no trajectory");
  const std::string data = DataPath(png_path);
  if (!WriteTopViewData(data, map_points, lines,
                        std::max<std::size_t>(1, options.max_map_points))) {
    return NoData(png_path, title, "cannot write the plot data '" + data + "'");
  }
  std::ostringstream body;
  body << "set title " << GnuplotQuote(title) << "\n"
       << "set xlabel 'x [m]'\nset ylabel 'y [m]'\nset size ratio -1\nset grid\n"
       << "set key outside right top box opaque\n"
       << "plot " << GnuplotQuote(FileName(data))
       << " index 0 using 1:2 with points pt 7 ps 0.2 lc rgb '#B0B0B0' "
       << "title 'map'";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    body << ", \\\n  '' index " << i + 1 << " using 1:2 with lines "
         << LineStyle(lines[i].label, static_cast<int>(i), 2) << " title "
         << GnuplotQuote(lines[i].label);
  }
  body << "\n";
  return Draw(png_path, title, body.str(), options);
}

PlotFile PlotErrorOverTime(const std::string& png_path, const std::string& title,
                           const std::vector<ErrorCurve>& curves, const PlotOptions& options) {
  if (curves.empty()) return NoData(png_path, title, "no back-end produced a trajectory");
  const std::string data = DataPath(png_path);
  if (!WriteErrorData(data, curves)) {
    return NoData(png_path, title, "cannot write the plot data '" + data + "'");
  }
  std::ostringstream body;
  body << "set title " << GnuplotQuote(title) << "\n"
       << "set xlabel 'time since start [s]'\nset ylabel 'position error [m]'\nset grid\n"
       << "set yrange [0:*]\nset key top left box opaque\nplot ";
  for (std::size_t i = 0; i < curves.size(); ++i) {
    body << (i == 0 ? "" : ", \\\n  ") << GnuplotQuote(FileName(data)) << " index " << i
         << " using 1:2 with lines " << LineStyle(curves[i].label, static_cast<int>(i), 2)
         << " title " << GnuplotQuote(curves[i].label);
  }
  body << "\n";
  return Draw(png_path, title, body.str(), options);
}

}  // namespace hylo::report
