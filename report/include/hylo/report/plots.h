#pragma once
// The report's figures, drawn by gnuplot (gnuplot.h) from a data file written beside each PNG:
//  - top view: the map's points (subsampled, grey) under every back-end's trajectory and the
//    ground truth, x/y in metres, equal axes;
//  - position error over time, one curve per back-end.
// A plot that cannot be drawn comes back with ok = false and the reason; its data and script
// stay on disk so it can be redrawn by hand.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "hylo/report/gnuplot.h"

namespace hylo::report {

/// One trajectory in the top view, positions in the map frame.
struct TrajectoryLine {
  std::string label;                           ///< legend text ("ieskf", "ground truth")
  std::vector<Eigen::Vector3d> positions_map;  ///< m
};

/// One curve of error over time.
struct ErrorCurve {
  std::string label;            ///< legend text
  std::vector<double> t_s;      ///< time since the start of the run, s
  std::vector<double> error_m;  ///< translation error, m (same length as t_s)
};

struct PlotOptions {
  std::size_t max_map_points = 40000;  ///< map points drawn at most (even stride), >= 1
  GnuplotOptions gnuplot;              ///< program and image size
};

/// A figure of the report.
struct PlotFile {
  std::string title;    ///< caption
  std::string path;     ///< the PNG
  bool ok = false;      ///< drawn; else see message
  std::string message;  ///< why it is missing (one line)
};

/// Draws the top view into `png_path` (data in `<stem>.dat`, script `<stem>.gp`).
PlotFile PlotTopView(const std::string& png_path, const std::string& title,
                     const std::vector<Eigen::Vector3d>& map_points,
                     const std::vector<TrajectoryLine>& lines, const PlotOptions& options = {});

/// Draws the error curves into `png_path`.
PlotFile PlotErrorOverTime(const std::string& png_path, const std::string& title,
                           const std::vector<ErrorCurve>& curves, const PlotOptions& options = {});

}  // namespace hylo::report
