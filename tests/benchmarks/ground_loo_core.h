#pragma once
// Choosing a ground back-end's defaults honestly on the 7 held ISPRS samples: every setting
// of a small grid is scored on every sample; each sample in turn is held out, the setting
// with the best mean total error on the other six is chosen, and the held-out sample is
// scored with it. The mean of those held-out errors estimates what the setting does on
// samples nobody tuned it on; the in-sample figure (the best mean over all seven) is printed
// beside it. Shared by hylo_ground_loo_benchmark and ground_filter_data_test.

#include <cstddef>
#include <string>
#include <vector>

#include "benchmarks/isprs_eval.h"
#include "hylo/terrain/ground_filter.h"

namespace hylo::terrain::isprs {

/// One setting of a grid: a label for the tables and the options it stands for.
struct Setting {
  std::string label;
  GroundFilterOptions options;
};

/// The SMRF grid: cell_m x slope x max_window_m x elevation_threshold_m x elevation_scaler,
/// the rest at SmrfOptions' defaults. `Describe` names the values.
std::vector<Setting> SmrfGrid();
/// The cloth filter grid: cloth_resolution_m x rigidness x hole_fill, the rest at defaults.
std::vector<Setting> CsfGrid();
/// One line per grid axis ("cell_m: 0.5 1 2"), for the tables and the README.
std::string DescribeSmrfGrid();
std::string DescribeCsfGrid();

/// confusion[setting][sample].
using ConfusionTable = std::vector<std::vector<Confusion>>;

/// Runs every setting on every sample. SMRF settings that differ only in the elevation
/// scaler share one provisional surface per sample (the elevation threshold is also the
/// DEM's re-admission tolerance), so the SMRF grid costs one surface per (cell, slope, window,
/// elevation threshold).
ConfusionTable EvaluateGrid(const std::vector<Setting>& grid, const std::vector<Sample>& samples);

/// Mean over samples of the per-sample total error of `setting`, % (the ISPRS convention).
double MeanTotalPercent(const ConfusionTable& table, std::size_t setting);

struct LeaveOneOutResult {
  std::vector<std::size_t> chosen;       ///< per held-out sample: the setting with the best
                                         ///< mean total error on the other samples
  std::vector<double> held_out_percent;  ///< per sample: its total error under that setting, %
  double held_out_mean_percent = 0.0;    ///< the mean of held_out_percent, %
  std::size_t in_sample_best = 0;        ///< the setting with the best mean over all samples
  double in_sample_mean_percent = 0.0;   ///< that best mean, %
  std::size_t most_chosen = 0;           ///< chosen for the most held-out samples (ties: the
                                         ///< better mean over all samples)
};

/// Ties between settings go to the first in grid order.
LeaveOneOutResult LeaveOneOut(const ConfusionTable& table);

/// Lines (each starting with `indent`): every held-out sample with its error and the setting
/// chosen without it, the left-out and in-sample means, the setting chosen most often.
std::string FormatLeaveOneOut(const std::vector<Setting>& grid, const std::vector<Sample>& samples,
                              const ConfusionTable& table, const LeaveOneOutResult& loo,
                              const std::string& indent);

}  // namespace hylo::terrain::isprs
