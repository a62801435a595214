// Leave-one-out choice of each ground back-end's defaults on the 7 held ISPRS samples
// (ground_loo_core.h): prints the grid, its best settings in-sample, the best setting of each
// sample on its own, the setting chosen with each sample held out and that sample's error, the
// means, and the per-sample table of the setting chosen most often. Skips (exit 0, says so) when
// ../shared/data/isprs is absent.
//   hylo_ground_loo_benchmark [--method smrf|csf|both] [--top N] [--json FILE]
//                             [--csv PREFIX]  (PREFIX_smrf.csv, PREFIX_csf.csv: every setting
//                                              on every sample)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numeric>
#include <string>
#include <vector>

#include "benchmarks/ground_loo_core.h"
#include "hylo/io/json.h"
#include "test_data.h"

namespace {

using hylo::io::Json;
using namespace hylo::terrain::isprs;

void PrintTable(const std::vector<Sample>& samples, const ConfusionTable& table, std::size_t s) {
  std::printf("  %s\n", TableHeader());
  for (std::size_t k = 0; k < samples.size(); ++k) {
    std::printf("  %s\n", TableRow(samples[k].name, table[s][k]).c_str());
  }
  std::printf("  mean    %24.2f\n", MeanTotalPercent(table, s));
}

// One row per setting and sample: type I, type II, total error and kappa, %.
void WriteCsv(const std::string& path, const std::vector<Setting>& grid,
              const std::vector<Sample>& samples, const ConfusionTable& table) {
  FILE* file = std::fopen(path.c_str(), "w");
  if (file == nullptr) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    return;
  }
  std::fprintf(file, "setting,sample,type_i,type_ii,total,kappa\n");
  for (std::size_t s = 0; s < grid.size(); ++s) {
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const Confusion& c = table[s][k];
      std::fprintf(file, "%s,%s,%.4f,%.4f,%.4f,%.4f\n", grid[s].label.c_str(),
                   samples[k].name.c_str(), 100 * c.TypeI(), 100 * c.TypeII(), 100 * c.Total(),
                   100 * c.Kappa());
    }
  }
  std::fclose(file);
}

Json RunBackEnd(const char* name, const std::vector<Setting>& grid, const std::string& described,
                const std::vector<Sample>& samples, int top, const std::string& csv_path) {
  std::printf("\n== %s: %zu settings (%s)\n", name, grid.size(), described.c_str());
  const auto start = std::chrono::steady_clock::now();
  const ConfusionTable table = EvaluateGrid(grid, samples);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("  %zu runs in %.1f s\n", grid.size() * samples.size(), seconds);
  if (!csv_path.empty()) WriteCsv(csv_path, grid, samples, table);
  std::vector<std::size_t> order(grid.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return MeanTotalPercent(table, a) < MeanTotalPercent(table, b);
  });
  std::printf("  best in-sample means:\n");
  for (int i = 0; i < top && i < static_cast<int>(order.size()); ++i) {
    std::printf("    %6.2f %%  %s\n", MeanTotalPercent(table, order[i]),
                grid[order[i]].label.c_str());
  }
  // What tuning per sample would give (as the papers' tables do): the ceiling of the grid.
  std::printf("  best setting per sample (tuned on the sample itself):\n");
  double tuned_sum = 0.0;
  for (std::size_t k = 0; k < samples.size(); ++k) {
    std::size_t best = 0;
    for (std::size_t s = 1; s < grid.size(); ++s) {
      if (table[s][k].Total() < table[best][k].Total()) best = s;
    }
    tuned_sum += 100 * table[best][k].Total();
    std::printf("    %-7s %6.2f %%  %s\n", samples[k].name.c_str(), 100 * table[best][k].Total(),
                grid[best].label.c_str());
  }
  std::printf("    mean    %6.2f %%\n", tuned_sum / samples.size());
  const LeaveOneOutResult loo = LeaveOneOut(table);
  std::printf("  leave-one-out:\n%s", FormatLeaveOneOut(grid, samples, table, loo, "    ").c_str());
  PrintTable(samples, table, loo.most_chosen);
  Json j = Json::object();
  j["settings"] = grid.size();
  j["grid"] = described;
  j["seconds"] = seconds;
  j["left_out_mean_total_percent"] = loo.held_out_mean_percent;
  j["in_sample_mean_total_percent"] = loo.in_sample_mean_percent;
  j["in_sample_best"] = grid[loo.in_sample_best].label;
  j["most_chosen"] = grid[loo.most_chosen].label;
  return j;
}

}  // namespace

int main(int argc, char** argv) {
  std::string method = "both", json_path, csv_prefix;
  int top = 10;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--method" && i + 1 < argc)
      method = argv[++i];
    else if (a == "--top" && i + 1 < argc)
      top = std::atoi(argv[++i]);
    else if (a == "--json" && i + 1 < argc)
      json_path = argv[++i];
    else if (a == "--csv" && i + 1 < argc)
      csv_prefix = argv[++i];
    else {
      std::fprintf(stderr,
                   "usage: %s [--method smrf|csf|both] [--top N] [--json FILE] "
                   "[--csv PREFIX]\n",
                   argv[0]);
      return 2;
    }
  }
  const std::string probe = hylo::testing::DataPath("isprs/samp11-utm.pcd");
  if (!std::filesystem::exists(probe)) {
    std::printf("skipped: real data absent: %s (set HYLO_DATA_DIR)\n", probe.c_str());
    return 0;
  }
  std::vector<Sample> samples;
  for (const std::string& name : SampleNames()) samples.push_back(LoadSample(name));
  Json summary = Json::object();
  if (method == "smrf" || method == "both") {
    summary["smrf"] = RunBackEnd("SMRF", SmrfGrid(), DescribeSmrfGrid(), samples, top,
                                 csv_prefix.empty() ? "" : csv_prefix + "_smrf.csv");
  }
  if (method == "csf" || method == "both") {
    summary["csf"] = RunBackEnd("CSF", CsfGrid(), DescribeCsfGrid(), samples, top,
                                csv_prefix.empty() ? "" : csv_prefix + "_csf.csv");
  }
  if (!json_path.empty()) hylo::io::WriteJsonFile(json_path, summary);
  return 0;
}
