// Lidar-only odometry on the real hand-held stretches (data README: the BALM walk, 2 Hz,
// ~75k points per scan, no IMU) with one configuration, every stretch through each back-end:
// ATE after SE(3) alignment, the worst one-scan step error (translation, rotation), CPU time
// per scan (one core: the pipeline is single-threaded; median and p99) and how often the
// robust registration retried. Figures are printed and written as JSON, never asserted
// (tests/estimation/handheld_robust_test asserts the accuracy bounds).
//
//   hylo_handheld_benchmark [--config YAML] [--data DIR] [--backend ieskf|sliding_window|both]
//                           [--stride N] [--stretch FOLDER]... [--json PATH] [--quick]
// --stride 2 keeps every other scan: the same walk at 1 Hz, twice the motion between scans.
// --stretch runs a scan folder with a poses.csv of its own instead of the three stretches.
// --quick: the first stretch's first 6 scans (the ctest smoke run).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "benchmark_common.h"
#include "estimation/handheld_stretch.h"
#include "hylo/config/run_config.h"
#include "test_data.h"

int main(int argc, char** argv) {
  using namespace hylo;  // NOLINT
  std::string config_path = std::string(HYLO_SOURCE_DIR) + "/config/presets/handheld_noimu.yaml";
  std::string data_dir = hylo::testing::DataDir(), backend = "both", json_path;
  int stride = 1;
  bool quick = false;
  std::vector<std::string> folders;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--config" && has_value) {
      config_path = argv[++i];
    } else if (a == "--data" && has_value) {
      data_dir = argv[++i];
    } else if (a == "--backend" && has_value) {
      backend = argv[++i];
    } else if (a == "--stride" && has_value) {
      stride = std::atoi(argv[++i]);
    } else if (a == "--stretch" && has_value) {
      folders.push_back(argv[++i]);
    } else if (a == "--json" && has_value) {
      json_path = argv[++i];
    } else if (a == "--quick") {
      quick = true;
    } else {
      std::fprintf(stderr, "unknown argument '%s'\n", a.c_str());
      return 2;
    }
  }
  const config::RunConfig run_config = config::LoadRunConfig(config_path);
  std::vector<std::string> backends = {"ieskf", "sliding_window"};
  if (backend != "both") backends = {backend};
  std::vector<std::string> stretches = hylo::testing::HandheldStretchDirs(data_dir);
  if (quick) stretches.resize(1);
  if (!folders.empty()) stretches = folders;

  benchmarks::Report report;
  std::printf("%s, stride %d\n%-20s %-15s %6s %9s %9s %10s %10s %9s %9s %8s\n", config_path.c_str(),
              stride, "stretch", "backend", "scans", "ATE cm", "ATE deg", "step cm", "step deg",
              "cpu med", "cpu p99", "retried");
  for (const std::string& dir : stretches) {
    const std::string stretch = std::filesystem::path(dir).filename().string();
    if (!std::filesystem::exists(dir + "/poses.csv")) {
      std::printf("real data absent: %s (set HYLO_DATA_DIR)\n", dir.c_str());
      return 0;
    }
    for (const std::string& name : backends) {
      config::RunConfig c = run_config;
      if (!estimation::ParseBackend(name, &c.pipeline.estimator.backend)) {
        std::fprintf(stderr, "unknown back-end '%s'\n", name.c_str());
        return 2;
      }
      const hylo::testing::StretchRun run =
          hylo::testing::RunStretch(dir, c.PipelineOptions(), stride, quick ? 6 : 0);
      const double median = hylo::testing::Quantile(run.cpu_ms, 0.5);
      const double p99 = hylo::testing::Quantile(run.cpu_ms, 0.99);
      std::printf("%-20s %-15s %6zu %9.2f %9.3f %10.2f %10.3f %9.1f %9.1f %8zu\n", stretch.c_str(),
                  name.c_str(), run.scans, 100.0 * run.ate.rmse_m, run.ate.rotation_rmse_deg,
                  100.0 * run.worst_step_m, run.worst_step_deg, median, p99, run.retried_scans);
      const std::string section = stretch + "/" + name;
      report.Set(section, "scans", static_cast<double>(run.scans));
      report.Set(section, "ate_m", run.ate.ok ? run.ate.rmse_m : std::nan(""));
      report.Set(section, "ate_rotation_deg", run.ate.rotation_rmse_deg);
      report.Set(section, "worst_step_m", run.worst_step_m);
      report.Set(section, "worst_step_deg", run.worst_step_deg);
      report.Set(section, "cpu_ms_median", median);
      report.Set(section, "cpu_ms_p99", p99);
      report.Set(section, "retried_scans", static_cast<double>(run.retried_scans));
      report.Set(section, "unchecked_scans", static_cast<double>(run.unchecked_scans));
      report.Set(section, "not_applied_scans", static_cast<double>(run.not_applied));
    }
  }
  if (!json_path.empty() && !report.WriteJson(json_path)) {
    std::fprintf(stderr, "cannot write %s\n", json_path.c_str());
    return 1;
  }
  return 0;
}
