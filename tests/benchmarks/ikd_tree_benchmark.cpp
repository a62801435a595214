// hylo_ikd_tree_benchmark: the ikd-tree map against nanoflann and PCL KdTreeFLANN on three
// workloads: 1. build from 1M points; 2. 5-NN on a 1M-point map; 3. a lidar-like
// run (see lidar_run.cpp). Prints a table with the targets and, with --json PATH, writes the
// same figures as JSON. --quick shrinks every size for a smoke test.
//
//   hylo_ikd_tree_benchmark [--quick] [--steps N] [--json PATH]
// --steps N overrides the number of workload-3 scans (2000; 40 with --quick).

#include <cstdlib>
#include <cstring>
#include <iostream>
#include <limits>
#include <memory>
#include <string>

#include "benchmark_common.h"
#include "hylo/mapping/ikd_tree.h"
#include "lidar_like_scene.h"
#include "lidar_run.h"
#include "static_trees.h"

namespace hylo::benchmarks {
namespace {

struct Config {
  int map_points = 1'000'000;  // workloads 1 and 2
  int queries = 200'000;       // workload 2
  LidarRunConfig run;
};

Config QuickConfig() {
  Config c;
  c.map_points = 20'000;
  c.queries = 5'000;
  c.run.steps = 40;
  c.run.window_m = 20.f;
  c.run.static_every = 10;
  return c;
}

// Workload 1: build each index from the same 1M points; heap growth gives bytes per point.
void RunBuild(const PointCloud& map, Report* report) {
  const std::string s = "workload1_build";
  const double n = static_cast<double>(map.size());
  report->Set(s, "points", n);
  {
    const std::size_t heap0 = HeapBytes();
    const double t0 = NowMs();
    mapping::IkdTree tree;
    tree.Build(map);
    report->Set(s, "ikd_tree_ms", NowMs() - t0);
    report->Set(s, "ikd_tree_heap_bytes_per_point", (HeapBytes() - heap0) / n);
    report->Set(s, "ikd_tree_reported_bytes_per_point", tree.MemoryBytes() / n);
  }
  {
    NanoflannTree tree;
    const std::size_t heap0 = HeapBytes();
    const double t0 = NowMs();
    tree.Build(map);
    report->Set(s, "nanoflann_ms", NowMs() - t0);
    // The index refers to the caller's cloud, which it needs: count its 12 B/point too.
    report->Set(s, "nanoflann_heap_bytes_per_point", (HeapBytes() - heap0) / n + 12.0);
  }
  {
    PclTree tree;
    const std::size_t heap0 = HeapBytes();
    tree.SetCloud(PclTree::ToPcl(map));
    const std::size_t heap1 = HeapBytes();
    const double t0 = NowMs();
    tree.Build(map);
    report->Set(s, "pcl_ms", NowMs() - t0);
    report->Set(s, "pcl_heap_bytes_per_point", (HeapBytes() - heap0) / n);
    report->Set(s, "pcl_conversion_bytes_per_point", (heap1 - heap0) / n);
  }
}

// Workload 2: 5-NN for points near the surfaces (map samples + noise) on the 1M map; the
// ikd-tree is called through registration::NeighborSearch, as registration code calls it.
void RunKnn(const PointCloud& map, const PointCloud& queries, Report* report) {
  const std::string s = "workload2_knn5";
  constexpr int kK = 5;
  const double nq = static_cast<double>(queries.size());
  report->Set(s, "map_points", static_cast<double>(map.size()));
  report->Set(s, "queries", nq);
  std::vector<double> kth_d2(queries.size(), 0.0);
  {
    mapping::IkdTree tree;
    tree.Build(map);
    const registration::NeighborSearch& search = tree;
    std::vector<registration::Neighbor> nn;
    const double t0 = NowMs();
    for (std::size_t i = 0; i < queries.size(); ++i) {
      search.KNearest(queries[i], kK, std::numeric_limits<float>::infinity(), &nn);
      kth_d2[i] = nn.back().squared_distance;
    }
    report->Set(s, "ikd_tree_ns_per_query", (NowMs() - t0) * 1e6 / nq);
  }
  auto run_static = [&](StaticTree* tree, const std::string& name) {
    tree->Build(map);
    std::vector<float> d2;
    std::size_t disagreements = 0;
    const double t0 = NowMs();
    for (std::size_t i = 0; i < queries.size(); ++i) {
      tree->KNearest(queries[i], kK, &d2);
      disagreements += std::abs(d2.back() - kth_d2[i]) > 1e-5 * (1.0 + kth_d2[i]);
    }
    report->Set(s, name + "_ns_per_query", (NowMs() - t0) * 1e6 / nq);
    report->Set(s, name + "_kth_distance_disagreements", static_cast<double>(disagreements));
  };
  NanoflannTree nanoflann;
  run_static(&nanoflann, "nanoflann");
  PclTree pcl;
  pcl.SetCloud(PclTree::ToPcl(map));
  run_static(&pcl, "pcl");
}

void AddTargets(Report* report, const LidarRunResult& run, double ikd_ns, double nano_ns,
                double ikd_bytes) {
  const std::string s = "targets";
  report->Set(s, "knn5_ikd_over_nanoflann", ikd_ns / nano_ns);
  report->Set(s, "knn5_ratio_target_max", 1.3);
  report->Set(s, "step_speedup_vs_nanoflann_rebuild",
              run.static_rebuild_ms_at_max / run.ikd_step_ms_at_max);
  report->Set(s, "step_speedup_vs_pcl_rebuild", run.pcl_rebuild_ms_at_max / run.ikd_step_ms_at_max);
  report->Set(s, "step_speedup_target_min", 20.0);
  report->Set(s, "ikd_bytes_per_point_1m_build", ikd_bytes);
  report->Set(s, "ikd_bytes_per_point_lidar_run", run.ikd_bytes_per_point);
  report->Set(s, "bytes_per_point_target_max", 64.0);
}

}  // namespace
}  // namespace hylo::benchmarks

int main(int argc, char** argv) {
  using namespace hylo::benchmarks;  // NOLINT
  bool quick = false;
  int steps = 0;
  std::string json_path;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) {
      quick = true;
    } else if (std::strcmp(argv[i], "--json") == 0 && i + 1 < argc) {
      json_path = argv[++i];
    } else if (std::strcmp(argv[i], "--steps") == 0 && i + 1 < argc) {
      steps = std::atoi(argv[++i]);
    } else {
      std::cerr << "usage: " << argv[0] << " [--quick] [--steps N] [--json PATH]\n";
      return 2;
    }
  }
  Config config = quick ? QuickConfig() : Config();
  if (steps > 0) config.run.steps = steps;
  Report report;
  report.Set("config", "quick", quick ? 1.0 : 0.0);
  report.Set("config", "times_are_thread_cpu_ms", 1.0);
  LidarLikeScene scene(LidarLikeScene::Options{});
  const int map_steps = 300;  // the 1M map spans 300 m of drive
  const hylo::PointCloud map = scene.Map(map_steps, config.map_points);
  hylo::PointCloud queries = scene.Map(map_steps, config.queries);
  RunBuild(map, &report);
  RunKnn(map, queries, &report);
  const LidarRunResult run = RunLidar(config.run, &report);
  // Re-read the figures the targets are computed from.
  AddTargets(&report, run, report.Get("workload2_knn5", "ikd_tree_ns_per_query"),
             report.Get("workload2_knn5", "nanoflann_ns_per_query"),
             report.Get("workload1_build", "ikd_tree_heap_bytes_per_point"));
  report.Print(std::cout);
  if (!json_path.empty() && !report.WriteJson(json_path)) {
    std::cerr << "cannot write " << json_path << "\n";
    return 1;
  }
  return 0;
}
