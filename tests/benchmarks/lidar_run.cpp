#include "lidar_run.h"

#include <algorithm>
#include <array>
#include <unordered_map>

#include "hylo/mapping/ikd_tree.h"
#include "lidar_like_scene.h"
#include "static_trees.h"

namespace hylo::benchmarks {
namespace {
constexpr int kK = 5;
constexpr float kMaxDistance = 5.f;  // m, as a point-to-plane match would use

// The map a static-tree user keeps: one point per voxel, nearest the centre (the same rule as
// the ikd-tree's on-tree downsampling), so both sides hold identical content.
class VoxelMap {
 public:
  explicit VoxelMap(float voxel_m) : voxel_m_(voxel_m) {}
  void Insert(const PointCloud& scan) {
    for (const Eigen::Vector3f& p : scan) {
      const auto v = VoxelOf(p, voxel_m_);
      const Eigen::Vector3f centre = VoxelCentre(v, voxel_m_);
      auto [it, fresh] = cells_.try_emplace(Key{v[0], v[1], v[2]}, p);
      if (!fresh && (p - centre).squaredNorm() < (it->second - centre).squaredNorm())
        it->second = p;
    }
  }
  void DeleteBox(const mapping::Box3f& box) {
    for (auto it = cells_.begin(); it != cells_.end();) {
      const Eigen::Vector3f& p = it->second;
      const bool inside =
          (p.array() >= box.min.array()).all() && (p.array() <= box.max.array()).all();
      it = inside ? cells_.erase(it) : std::next(it);
    }
  }
  PointCloud Points() const {
    PointCloud points;
    points.reserve(cells_.size());
    for (const auto& cell : cells_) points.push_back(cell.second);
    return points;
  }
  std::size_t Size() const { return cells_.size(); }

 private:
  using Key = std::array<int64_t, 3>;
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      return static_cast<std::size_t>(k[0] * 73856093LL ^ k[1] * 19349663LL ^ k[2] * 83492791LL);
    }
  };
  float voxel_m_;
  std::unordered_map<Key, Eigen::Vector3f, KeyHash> cells_;
};

struct StaticSample {
  double map_points = 0;
  double nanoflann_rebuild_ms = 0, nanoflann_query_ms = 0;
  double pcl_rebuild_ms = 0, pcl_query_ms = 0;
};

double Percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * (v.size() - 1))];
}

// Rebuilds and queries one static tree on the current map; counts queries whose neighbours
// (within kMaxDistance) differ from the ikd-tree's.
void MeasureStatic(StaticTree* tree, const PointCloud& map, const PointCloud& scan,
                   const std::vector<std::vector<float>>& ikd_d2, double* rebuild_ms,
                   double* query_ms, std::size_t* disagreements) {
  double t0 = NowMs();
  tree->Build(map);
  *rebuild_ms = NowMs() - t0;
  std::vector<float> d2;
  t0 = NowMs();
  for (std::size_t i = 0; i < scan.size(); ++i) {
    tree->KNearest(scan[i], kK, &d2);
    while (!d2.empty() && d2.back() > kMaxDistance * kMaxDistance) d2.pop_back();
    bool same = d2.size() == ikd_d2[i].size();
    for (std::size_t j = 0; same && j < d2.size(); ++j) {
      same = std::abs(d2[j] - ikd_d2[i][j]) <= 1e-5f * (1.f + d2[j]);
    }
    *disagreements += !same;
  }
  *query_ms = NowMs() - t0;
}
}  // namespace

LidarRunResult RunLidar(const LidarRunConfig& config, Report* report) {
  LidarLikeScene scene(LidarLikeScene::Options{});
  mapping::IkdTree tree;
  VoxelMap model(config.voxel_m);
  NanoflannTree nanoflann;
  PclTree pcl;
  std::vector<double> step_ms, query_ms, insert_ms, delete_ms, upkeep_ms, map_size;
  std::vector<StaticSample> samples;
  std::vector<registration::Neighbor> nn;
  std::vector<std::vector<float>> ikd_d2(config.scan_points);
  std::size_t disagreements = 0;
  for (int step = 0; step < config.steps; ++step) {
    const PointCloud scan = scene.Scan(step, config.scan_points);
    const Eigen::Vector3f sensor = scene.SensorAt(step);
    const float behind = sensor.x() - config.window_m;
    const mapping::Box3f box{{behind - 3.f, -1e4f, -1e4f}, {behind, 1e4f, 1e4f}};
    const registration::NeighborSearch& search = tree;
    const double t0 = NowMs();
    for (std::size_t i = 0; i < scan.size(); ++i) {
      search.KNearest(scan[i], kK, kMaxDistance, &nn);
      ikd_d2[i].clear();
      for (const auto& n : nn) ikd_d2[i].push_back(n.squared_distance);
    }
    const double t1 = NowMs();
    tree.Insert(scan, config.voxel_m);
    const double t2 = NowMs();
    tree.DeleteBox(box);
    const double t3 = NowMs();
    query_ms.push_back(t1 - t0);
    insert_ms.push_back(t2 - t1);
    delete_ms.push_back(t3 - t2);
    step_ms.push_back(t3 - t0);
    if (step > 0 && step % config.static_every == 0 && model.Size() > 0) {
      StaticSample sample;
      const PointCloud map = model.Points();
      sample.map_points = static_cast<double>(map.size());
      MeasureStatic(&nanoflann, map, scan, ikd_d2, &sample.nanoflann_rebuild_ms,
                    &sample.nanoflann_query_ms, &disagreements);
      pcl.SetCloud(PclTree::ToPcl(map));
      MeasureStatic(&pcl, map, scan, ikd_d2, &sample.pcl_rebuild_ms, &sample.pcl_query_ms,
                    &disagreements);
      samples.push_back(sample);
    }
    const double u0 = NowMs();
    model.Insert(scan);
    model.DeleteBox(box);
    upkeep_ms.push_back(NowMs() - u0);
    map_size.push_back(static_cast<double>(tree.Size()));
    if (tree.Size() != model.Size()) ++disagreements;
  }
  const std::string s = "workload3_lidar";
  const double max_size = *std::max_element(map_size.begin(), map_size.end());
  LidarRunResult result;
  double n_at_max = 0, ikd_sum = 0, ikd_query_sum = 0;
  for (std::size_t i = 0; i < step_ms.size(); ++i) {
    if (map_size[i] < 0.9 * max_size) continue;
    ikd_sum += step_ms[i];
    ikd_query_sum += query_ms[i];
    ++n_at_max;
  }
  result.ikd_step_ms_at_max = ikd_sum / n_at_max;
  double largest_sample = 0;
  for (const StaticSample& x : samples) largest_sample = std::max(largest_sample, x.map_points);
  double static_n = 0, nano_q = 0, pcl_q = 0, map_at_max = 0;
  for (const StaticSample& x : samples) {
    if (x.map_points < 0.9 * largest_sample) continue;
    result.static_rebuild_ms_at_max += x.nanoflann_rebuild_ms;
    result.pcl_rebuild_ms_at_max += x.pcl_rebuild_ms;
    nano_q += x.nanoflann_query_ms;
    pcl_q += x.pcl_query_ms;
    map_at_max += x.map_points;
    ++static_n;
  }
  result.static_rebuild_ms_at_max /= static_n;
  result.pcl_rebuild_ms_at_max /= static_n;
  result.ikd_bytes_per_point = static_cast<double>(tree.MemoryBytes()) / tree.Size();
  auto mean = [](const std::vector<double>& v) {
    double sum = 0;
    for (double x : v) sum += x;
    return v.empty() ? 0.0 : sum / v.size();
  };
  report->Set(s, "steps", config.steps);
  report->Set(s, "scan_points", config.scan_points);
  report->Set(s, "map_points_max", max_size);
  report->Set(s, "map_points_final", map_size.back());
  report->Set(s, "ikd_step_ms_mean", mean(step_ms));
  report->Set(s, "ikd_step_ms_p50", Percentile(step_ms, 0.5));
  report->Set(s, "ikd_step_ms_p99", Percentile(step_ms, 0.99));
  report->Set(s, "ikd_step_ms_max", Percentile(step_ms, 1.0));
  report->Set(s, "ikd_query_ms_mean", mean(query_ms));
  report->Set(s, "ikd_insert_ms_mean", mean(insert_ms));
  report->Set(s, "ikd_delete_box_ms_mean", mean(delete_ms));
  report->Set(s, "ikd_step_ms_mean_at_max_map", result.ikd_step_ms_at_max);
  report->Set(s, "ikd_query_ms_mean_at_max_map", ikd_query_sum / n_at_max);
  report->Set(s, "ikd_rebuilds", static_cast<double>(tree.stats().num_rebuilds));
  report->Set(s, "ikd_points_rebuilt_per_step",
              static_cast<double>(tree.stats().num_points_rebuilt) / config.steps);
  report->Set(s, "ikd_largest_rebuild_points", static_cast<double>(tree.stats().largest_rebuild));
  report->Set(s, "ikd_bytes_per_point_final", result.ikd_bytes_per_point);
  const mapping::IkdTree::Stats& stats = tree.stats();
  const double decided = static_cast<double>(
      stats.num_voxel_cache_hits + stats.num_voxels_proven_empty + stats.num_voxel_searches);
  report->Set(s, "ikd_voxel_cache_hit_fraction",
              static_cast<double>(stats.num_voxel_cache_hits) / std::max(decided, 1.0));
  report->Set(s, "ikd_voxel_proven_empty_fraction",
              static_cast<double>(stats.num_voxels_proven_empty) / std::max(decided, 1.0));
  report->Set(s, "static_samples_at_max_map", static_n);
  report->Set(s, "static_map_points_at_max_map", map_at_max / static_n);
  report->Set(s, "static_voxel_map_upkeep_ms_mean", mean(upkeep_ms));
  report->Set(s, "nanoflann_rebuild_ms_at_max_map", result.static_rebuild_ms_at_max);
  report->Set(s, "nanoflann_query_ms_at_max_map", nano_q / static_n);
  report->Set(s, "pcl_rebuild_ms_at_max_map", result.pcl_rebuild_ms_at_max);
  report->Set(s, "pcl_query_ms_at_max_map", pcl_q / static_n);
  report->Set(s, "disagreements_with_static_trees", static_cast<double>(disagreements));
  return result;
}

}  // namespace hylo::benchmarks
