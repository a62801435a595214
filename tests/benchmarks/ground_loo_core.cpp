#include "benchmarks/ground_loo_core.h"

#include <algorithm>
#include <iomanip>
#include <map>
#include <sstream>
#include <tuple>

#include "hylo/common/local_origin.h"

namespace hylo::terrain::isprs {
namespace {

// The grids. SMRF: one step either side of the paper's single parameter set (s 0.15, w 18 m,
// et 0.5 m, es 1.25) on each axis, the cell at the paper's 1 m (the samples hold 0.2-1.5
// points/m^2). CSF: the paper's resolution and a finer one, its rigidness range and stiffer
// cloths, both hole fills.
const std::vector<double> kSmrfCells = {1.0};
const std::vector<double> kSmrfSlopes = {0.1, 0.15, 0.2};
const std::vector<double> kSmrfWindows = {12.0, 18.0, 24.0};
const std::vector<double> kSmrfThresholds = {0.3, 0.5, 0.7};
const std::vector<double> kSmrfScalers = {0.5, 1.25, 2.0};

const std::vector<double> kCsfResolutions = {0.5, 1.0};
const std::vector<int> kCsfRigidness = {1, 2, 3, 6, 10};
const std::vector<ClothHoleFill> kCsfFills = {ClothHoleFill::kNeighbourMean,
                                              ClothHoleFill::kNearest};

const char* FillName(ClothHoleFill fill) {
  return fill == ClothHoleFill::kNearest ? "nearest" : "mean";
}

template <typename T>
std::string Join(const char* name, const std::vector<T>& values) {
  std::ostringstream os;
  os << name << ":";
  for (const T& v : values) os << " " << v;
  return os.str();
}

// SMRF settings that share a provisional surface differ only in the elevation scaler (the
// elevation threshold is also the DEM's re-admission tolerance).
using SurfaceKey = std::tuple<double, double, double, double, double, double>;
SurfaceKey KeyOf(const SmrfOptions& o) {
  return {o.cell_m,
          o.slope,
          o.max_window_m,
          o.low_outlier_slope,
          o.low_outlier_window_m,
          o.elevation_threshold_m};
}

void EvaluateSmrfSample(const std::vector<Setting>& grid, const std::vector<std::size_t>& members,
                        const Sample& sample, std::size_t sample_index, ConfusionTable* table) {
  const PointCloud local = ToLocal(sample.points, ChooseOrigin(sample.points));
  std::map<SurfaceKey, SmrfSurface> surfaces;
  for (const std::size_t s : members) {
    const SmrfOptions& o = grid[s].options.smrf;
    auto it = surfaces.find(KeyOf(o));
    if (it == surfaces.end()) it = surfaces.emplace(KeyOf(o), ComputeSmrfSurface(local, o)).first;
    SmrfResult result;
    ClassifySmrf(local, it->second, o.elevation_threshold_m, o.elevation_scaler, &result);
    (*table)[s][sample_index] = Score(sample, result.labels);
  }
}

}  // namespace

std::vector<Setting> SmrfGrid() {
  std::vector<Setting> grid;
  for (const double cell : kSmrfCells) {
    for (const double slope : kSmrfSlopes) {
      for (const double window : kSmrfWindows) {
        for (const double threshold : kSmrfThresholds) {
          for (const double scaler : kSmrfScalers) {
            Setting s;
            s.options.method = GroundMethod::kSmrf;
            s.options.smrf.cell_m = cell;
            s.options.smrf.slope = slope;
            s.options.smrf.max_window_m = window;
            s.options.smrf.elevation_threshold_m = threshold;
            s.options.smrf.elevation_scaler = scaler;
            std::ostringstream label;
            label << "c " << cell << " s " << slope << " w " << window << " et " << threshold
                  << " es " << scaler;
            s.label = label.str();
            grid.push_back(s);
          }
        }
      }
    }
  }
  return grid;
}

std::vector<Setting> CsfGrid() {
  std::vector<Setting> grid;
  for (const double resolution : kCsfResolutions) {
    for (const int rigidness : kCsfRigidness) {
      for (const ClothHoleFill fill : kCsfFills) {
        Setting s;
        s.options.method = GroundMethod::kCsf;
        s.options.csf.cloth_resolution_m = resolution;
        s.options.csf.rigidness = rigidness;
        s.options.csf.hole_fill = fill;
        std::ostringstream label;
        label << "GR " << resolution << " RI " << rigidness << " " << FillName(fill) << " fill";
        s.label = label.str();
        grid.push_back(s);
      }
    }
  }
  return grid;
}

std::string DescribeSmrfGrid() {
  return Join("cell_m", kSmrfCells) + "; " + Join("slope", kSmrfSlopes) + "; " +
         Join("max_window_m", kSmrfWindows) + "; " +
         Join("elevation_threshold_m", kSmrfThresholds) + "; " +
         Join("elevation_scaler", kSmrfScalers);
}

std::string DescribeCsfGrid() {
  std::vector<std::string> fills;
  for (const ClothHoleFill fill : kCsfFills) fills.push_back(FillName(fill));
  return Join("cloth_resolution_m", kCsfResolutions) + "; " + Join("rigidness", kCsfRigidness) +
         "; " + Join("hole_fill", fills);
}

ConfusionTable EvaluateGrid(const std::vector<Setting>& grid, const std::vector<Sample>& samples) {
  ConfusionTable table(grid.size(), std::vector<Confusion>(samples.size()));
  std::vector<std::size_t> smrf;
  for (std::size_t s = 0; s < grid.size(); ++s) {
    if (grid[s].options.method == GroundMethod::kSmrf) smrf.push_back(s);
  }
  for (std::size_t k = 0; k < samples.size(); ++k) {
    EvaluateSmrfSample(grid, smrf, samples[k], k, &table);
    for (std::size_t s = 0; s < grid.size(); ++s) {
      if (grid[s].options.method == GroundMethod::kSmrf) continue;
      const GroundFilterResult result = ExtractGround(samples[k].points, grid[s].options);
      table[s][k] = Score(samples[k], result.labels);
    }
  }
  return table;
}

double MeanTotalPercent(const ConfusionTable& table, std::size_t setting) {
  double sum = 0.0;
  for (const Confusion& c : table[setting]) sum += c.Total();
  return 100.0 * sum / table[setting].size();
}

LeaveOneOutResult LeaveOneOut(const ConfusionTable& table) {
  LeaveOneOutResult r;
  const std::size_t num_samples = table.front().size();
  std::vector<double> sum(table.size(), 0.0);
  for (std::size_t s = 0; s < table.size(); ++s) {
    for (const Confusion& c : table[s]) sum[s] += 100.0 * c.Total();
  }
  std::vector<int> times_chosen(table.size(), 0);
  for (std::size_t held = 0; held < num_samples; ++held) {
    std::size_t best = 0;
    double best_rest = sum[0] - 100.0 * table[0][held].Total();
    for (std::size_t s = 1; s < table.size(); ++s) {
      const double rest = sum[s] - 100.0 * table[s][held].Total();
      if (rest < best_rest) best = s, best_rest = rest;
    }
    r.chosen.push_back(best);
    r.held_out_percent.push_back(100.0 * table[best][held].Total());
    ++times_chosen[best];
  }
  for (const double e : r.held_out_percent) r.held_out_mean_percent += e / num_samples;
  r.in_sample_best =
      static_cast<std::size_t>(std::min_element(sum.begin(), sum.end()) - sum.begin());
  r.in_sample_mean_percent = sum[r.in_sample_best] / num_samples;
  for (std::size_t s = 0; s < table.size(); ++s) {
    const bool more = times_chosen[s] > times_chosen[r.most_chosen];
    const bool tie_better =
        times_chosen[s] == times_chosen[r.most_chosen] && sum[s] < sum[r.most_chosen];
    if (more || tie_better) r.most_chosen = s;
  }
  return r;
}

std::string FormatLeaveOneOut(const std::vector<Setting>& grid, const std::vector<Sample>& samples,
                              const ConfusionTable& table, const LeaveOneOutResult& loo,
                              const std::string& indent) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(2);
  os << indent << "held out  total%  setting chosen on the other samples\n";
  for (std::size_t k = 0; k < samples.size(); ++k) {
    os << indent << std::left << std::setw(7) << samples[k].name << std::right << std::setw(8)
       << loo.held_out_percent[k] << "   " << grid[loo.chosen[k]].label << "\n";
  }
  os << indent << "mean total error: left out " << loo.held_out_mean_percent << " %, in-sample "
     << loo.in_sample_mean_percent << " % (" << grid[loo.in_sample_best].label << ")\n";
  os << indent << "most often chosen: " << grid[loo.most_chosen].label << " (in-sample mean "
     << MeanTotalPercent(table, loo.most_chosen) << " %)\n";
  return os.str();
}

}  // namespace hylo::terrain::isprs
