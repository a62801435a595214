// The `threads` setting on every kind of head: one scenario per sensor kind of the generator
// (VLP-16, RS-16, XT32, OS-64, OS-128, Livox rosette), SLAM with each back-end at 1 and 2 threads
// (and 4 where the machine has that many cores), all fed by one simulation pass. Per scan: wall
// time (what a live node waits), the process's CPU time (every thread's work) and the scan thread's
// CPU time, median and p99; the ATE after SE(3) alignment; and, per head and back-end, the wall
// median at n threads over the one at 1 thread; the scans whose solve its wall-time budget stopped
// (the sliding window). The poses must not depend on the number of threads: the ATE is printed to
// six digits, and a difference is an error unless a solve was stopped by its budget (then the poses
// depend on the machine's speed at any thread count). Figures are printed and written as JSON,
// never asserted. Other processes on the machine make the wall and the p99 figures worse; run it on
// a quiet one.
//
//   hylo_threads_benchmark [--scenarios 0,2,4,6,8,10] [--backends ieskf,sliding_window]
//                          [--threads 1,2] [--max-drive S] [--preset-dir DIR] [--json PATH]

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "estimation/scenario_run.h"
#include "hylo/io/json.h"
#include "hylo/sim/scan_pattern.h"

namespace {

using hylo::estimation::Estimator;
using hylo::testing::BackendFigures;
using hylo::testing::ModeFigures;
using hylo::testing::ScenarioFigures;

struct Args {
  std::vector<uint64_t> scenarios = {0, 2, 4, 6, 8, 10};  // the first of each sensor kind
  std::vector<Estimator::Backend> backends = {Estimator::Backend::kIeskf,
                                              Estimator::Backend::kSlidingWindow};
  std::vector<int> threads;
  double max_drive_s = 0.0;  // 0: the scenario's own drive
  std::string preset_dir = HYLO_PRESET_DIR;
  std::string json_path = "threads_benchmark.json";
};

std::vector<std::string> Split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string part; std::getline(in, part, ',');) parts.push_back(part);
  return parts;
}

bool ParseArgs(int argc, char** argv, Args* args) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--scenarios" && has_value) {
      args->scenarios.clear();
      for (const std::string& n : Split(argv[++i])) args->scenarios.push_back(std::stoull(n));
    } else if (a == "--backends" && has_value) {
      args->backends.clear();
      for (const std::string& name : Split(argv[++i])) {
        Estimator::Backend backend;
        if (!hylo::estimation::ParseBackend(name, &backend)) return false;
        args->backends.push_back(backend);
      }
    } else if (a == "--threads" && has_value) {
      for (const std::string& n : Split(argv[++i])) args->threads.push_back(std::stoi(n));
    } else if (a == "--max-drive" && has_value) {
      args->max_drive_s = std::stod(argv[++i]);
    } else if (a == "--preset-dir" && has_value) {
      args->preset_dir = argv[++i];
    } else if (a == "--json" && has_value) {
      args->json_path = argv[++i];
    } else {
      std::fprintf(stderr, "unknown or incomplete argument '%s'\n", a.c_str());
      return false;
    }
  }
  if (args->threads.empty()) {
    args->threads = {1, 2};
    if (std::thread::hardware_concurrency() >= 4) args->threads.push_back(4);
  }
  return !args->scenarios.empty() && !args->backends.empty() &&
         std::all_of(args->threads.begin(), args->threads.end(), [](int t) { return t >= 1; });
}

std::string VariantName(int threads) { return std::to_string(threads) + "t"; }

}  // namespace

int main(int argc, char** argv) {
  Args args;
  if (!ParseArgs(argc, argv, &args)) {
    std::fprintf(stderr,
                 "usage: hylo_threads_benchmark [--scenarios N,...] [--backends ieskf,...] "
                 "[--threads 1,2,...] [--max-drive S] [--preset-dir DIR] [--json PATH]\n");
    return 2;
  }
  hylo::testing::ScenarioRunOptions options;
  options.preset_dir = args.preset_dir;
  options.backends = args.backends;
  options.localization = false;
  options.variants.clear();
  for (const int threads : args.threads) {
    hylo::testing::Variant v;
    v.name = VariantName(threads);
    v.adjust = [threads](hylo::odometry::OdometryPipelineOptions* o) { o->threads = threads; };
    options.variants.push_back(v);
  }
  std::printf("%u cores; threads %s\n\n", std::thread::hardware_concurrency(),
              [&] {
                std::string s;
                for (const int t : args.threads) s += (s.empty() ? "" : ",") + std::to_string(t);
                return s;
              }()
                  .c_str());
  std::printf(
      "| head | scenario | back-end | threads | wall ms median | wall ms p99 | process CPU ms "
      "median | p99 | scan thread CPU ms median | ATE cm | wall vs 1 thread | solves out of "
      "time |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  hylo::io::Json json = hylo::io::Json::array();
  int differing = 0;
  for (const uint64_t number : args.scenarios) {
    hylo::sim::Scenario scenario = hylo::sim::DrawScenario(number);
    if (args.max_drive_s > 0) scenario.max_drive_a_s = args.max_drive_s;
    const ScenarioFigures figures = hylo::testing::RunScenario(scenario, options);
    const std::string head = hylo::sim::ToString(scenario.lidar.kind);
    for (const Estimator::Backend backend : args.backends) {
      const ModeFigures* one = nullptr;
      for (const BackendFigures& run : figures.runs) {
        if (run.backend != backend) continue;
        const ModeFigures& f = run.slam;
        if (one == nullptr) one = &f;
        const double ratio = f.wall_ms_median / one->wall_ms_median;
        std::printf(
            "| %s | #%llu | %s | %s | %.1f | %.1f | %.1f | %.1f | %.1f | %s | %.2f | %zu |\n",
            head.c_str(), static_cast<unsigned long long>(number),
            hylo::estimation::ToString(backend).c_str(), run.variant.c_str(), f.wall_ms_median,
            f.wall_ms_p99, f.process_cpu_ms_median, f.process_cpu_ms_p99, f.cpu_ms_median,
            f.failed ? "FAILED" : std::to_string(100 * f.ate_m).c_str(), ratio, f.out_of_time);
        if (f.failed != one->failed || (!f.failed && f.ate_m != one->ate_m)) {
          // A solve stopped by its wall-time budget depends on the machine's speed: such runs
          // differ from each other at any thread count, and say so instead.
          const std::size_t out_of_time = f.out_of_time + one->out_of_time;
          std::fprintf(
              stderr, "%s: #%llu %s: the poses at %s differ from those at %s%s\n",
              out_of_time > 0 ? "note" : "error", static_cast<unsigned long long>(number),
              hylo::estimation::ToString(backend).c_str(), run.variant.c_str(),
              VariantName(args.threads.front()).c_str(),
              out_of_time > 0 ? " (solves stopped at their time budget: see the table)" : "");
          if (out_of_time == 0) ++differing;
        }
      }
    }
    std::fflush(stdout);
    hylo::io::Json j = hylo::testing::ToJson(figures);
    j["head"] = head;
    json.push_back(j);
    hylo::io::WriteJsonFile(args.json_path, json);
  }
  std::printf("\nJSON: %s\n", args.json_path.c_str());
  if (differing > 0) {
    std::fprintf(stderr, "%d run(s) gave other poses than at %d thread(s)\n", differing,
                 args.threads.front());
    return 1;
  }
  return 0;
}
