// Branch and bound over (yaw, x, y) on the GlobalMap pyramid (Hess et al. 2016, Algorithm 3:
// depth first, children in order of their bounds, a node pruned once its bound cannot beat
// the worst kept result).
#include "global_bnb.h"

#include <time.h>

#include <algorithm>
#include <cmath>

namespace hylo::localization::internal {
namespace {

constexpr int kBins = GlobalMap::kZBins;

// Bit i of the result is set when any of bits [i, i + w] of `mask` is (w >= 0).
uint64_t DilateDown(uint64_t mask, int w) {
  int covered = 1;
  while (covered < w + 1) {
    const int s = std::min(covered, w + 1 - covered);
    mask |= mask >> s;
    covered += s;
  }
  return mask;
}

uint64_t ShiftRight(uint64_t mask, int s) {
  if (s >= kBins || s <= -kBins) return 0;
  return s >= 0 ? mask >> s : mask << -s;
}

// The kept results: at most `max` mutually distinct candidates, best first.
class Results {
 public:
  explicit Results(const BnbOptions& options) : options_(options) {}

  // True when no leaf scoring at most `bound` could enter.
  bool Prunable(int bound) const { return bound <= Cutoff(); }
  // The largest bound that is prunable.
  int Cutoff() const {
    if (static_cast<int>(kept_.size()) < options_.max_candidates) return options_.min_score - 1;
    return kept_.back().score;
  }

  void Insert(const BnbCandidate& c, const DiscreteScan& scan) {
    if (Prunable(c.score)) return;
    for (const BnbCandidate& k : kept_) {
      if (!Distinct(c, k, scan) && k.score >= c.score) return;  // a better one nearby
    }
    kept_.erase(std::remove_if(kept_.begin(), kept_.end(),
                               [&](const BnbCandidate& k) { return !Distinct(c, k, scan); }),
                kept_.end());
    const auto at = std::find_if(kept_.begin(), kept_.end(),
                                 [&](const BnbCandidate& k) { return k.score < c.score; });
    kept_.insert(at, c);
    if (static_cast<int>(kept_.size()) > options_.max_candidates) kept_.pop_back();
  }

  const std::vector<BnbCandidate>& kept() const { return kept_; }

 private:
  bool Distinct(const BnbCandidate& a, const BnbCandidate& b, const DiscreteScan& scan) const {
    const double cells = std::hypot(a.x - b.x, a.y - b.y);
    const double dyaw =
        std::remainder(scan.yaws_rad[a.yaw_index] - scan.yaws_rad[b.yaw_index], 2.0 * M_PI);
    return cells > options_.distinct_cells || std::abs(dyaw) > options_.distinct_yaw_rad;
  }

  const BnbOptions& options_;
  std::vector<BnbCandidate> kept_;
};

struct Node {
  BnbCandidate pose;  // score = the node's bound
  int level = 0;
};

class Search {
 public:
  Search(const DiscreteScan& scan, const GlobalMap& map, const BnbOptions& options)
      : scan_(scan), map_(map), options_(options), results_(options) {}

  void Run() {
    const int top = map_.num_levels() - 1;
    const int32_t step = int32_t{1} << top;
    std::vector<Node> roots;
    for (int yaw = 0; yaw < static_cast<int>(scan_.yaws_rad.size()); ++yaw) {
      for (int32_t y = 0; y < map_.layout().height; y += step) {
        for (int32_t x = 0; x < map_.layout().width; x += step) {
          Node node{{yaw, x, y, Score(yaw, x, y, top)}, top};
          if (node.pose.score >= options_.min_score) roots.push_back(node);
        }
      }
    }
    SortByBound(&roots);
    for (const Node& root : roots) {
      if (results_.Prunable(root.pose.score)) break;
      Expand(root);
    }
  }

  const std::vector<BnbCandidate>& results() const { return results_.kept(); }
  std::size_t nodes_scored() const { return nodes_scored_; }
  std::size_t columns_scored() const { return columns_scored_; }

 private:
  int Score(int yaw, int32_t x, int32_t y, int level) {
    ++nodes_scored_;
    return ScoreNode(scan_, map_, yaw, x, y, level, options_.z_tolerance_m, results_.Cutoff(),
                     &columns_scored_);
  }

  static void SortByBound(std::vector<Node>* nodes) {
    std::stable_sort(nodes->begin(), nodes->end(),
                     [](const Node& a, const Node& b) { return a.pose.score > b.pose.score; });
  }

  void Expand(const Node& node) {
    if (node.level == 0) {
      results_.Insert(node.pose, scan_);
      return;
    }
    const int level = node.level - 1;
    const int32_t h = int32_t{1} << level;
    std::vector<Node> children;
    for (int32_t dy = 0; dy <= h; dy += h) {
      for (int32_t dx = 0; dx <= h; dx += h) {
        const int32_t x = node.pose.x + dx, y = node.pose.y + dy;
        if (x >= map_.layout().width || y >= map_.layout().height) continue;
        const int score = Score(node.pose.yaw_index, x, y, level);
        if (score >= 0) children.push_back({{node.pose.yaw_index, x, y, score}, level});
      }
    }
    SortByBound(&children);
    for (const Node& child : children) {
      if (results_.Prunable(child.pose.score)) break;
      Expand(child);
    }
  }

  const DiscreteScan& scan_;
  const GlobalMap& map_;
  const BnbOptions& options_;
  Results results_;
  std::size_t nodes_scored_ = 0;
  std::size_t columns_scored_ = 0;
};

}  // namespace

double ThreadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

DiscreteScan Discretize(const PointCloud& points_ground, const GlobalMapOptions& map_options,
                        double yaw_step_rad) {
  DiscreteScan scan;
  const int yaws = std::max(1, static_cast<int>(std::ceil(2.0 * M_PI / yaw_step_rad)));
  const double inv_cell = 1.0 / map_options.cell_m;
  // A dense window of cells around the vehicle collects each yaw's columns in one pass.
  float max_xy = 0.f;
  for (const Eigen::Vector3f& p : points_ground) max_xy = std::max(max_xy, p.head<2>().norm());
  const int32_t half = static_cast<int32_t>(std::ceil(max_xy * inv_cell)) + 1;
  const int32_t side = 2 * half + 1;
  std::vector<uint64_t> window(static_cast<std::size_t>(side) * side, 0);
  std::vector<std::size_t> touched;
  for (int k = 0; k < yaws; ++k) {
    const double yaw = 2.0 * M_PI * k / yaws;
    const double c = std::cos(yaw), s = std::sin(yaw);
    touched.clear();
    for (const Eigen::Vector3f& p : points_ground) {
      const int bin =
          static_cast<int>(std::floor(p.z() / map_options.z_bin_m)) + DiscreteScan::kGroundBin;
      if (bin < 0 || bin >= kBins) continue;
      const int32_t dx = static_cast<int32_t>(std::floor((c * p.x() - s * p.y()) * inv_cell + 0.5));
      const int32_t dy = static_cast<int32_t>(std::floor((s * p.x() + c * p.y()) * inv_cell + 0.5));
      const std::size_t i = static_cast<std::size_t>(dy + half) * side + (dx + half);
      if (window[i] == 0) touched.push_back(i);
      window[i] |= uint64_t{1} << bin;
    }
    // Window order is the map's row-major order: the lookups of one score then walk the
    // raster's rows instead of jumping across it.
    std::sort(touched.begin(), touched.end());
    std::vector<ScanColumn> columns;
    columns.reserve(touched.size());
    for (const std::size_t i : touched) {
      columns.push_back({static_cast<int32_t>(i % side) - half,
                         static_cast<int32_t>(i / side) - half, window[i]});
      window[i] = 0;
    }
    std::vector<int> voxels_from(columns.size() + 1, 0);
    for (std::size_t c = columns.size(); c-- > 0;) {
      voxels_from[c] = voxels_from[c + 1] + __builtin_popcountll(columns[c].bins);
    }
    if (k == 0) scan.total_voxels = voxels_from.front();
    scan.yaws_rad.push_back(yaw);
    scan.columns.push_back(std::move(columns));
    scan.voxels_from.push_back(std::move(voxels_from));
  }
  return scan;
}

// The search's inner loop: with the POPCNT instruction where the CPU has it (a portable build
// otherwise calls a library routine per column), chosen once at load time.
__attribute__((target_clones("popcnt", "default"))) int ScoreNode(
    const DiscreteScan& scan, const GlobalMap& map, int yaw_index, int32_t x, int32_t y, int level,
    double z_tolerance_m, int cutoff, std::size_t* columns_scored) {
  const GlobalMap::Layout& layout = map.layout();
  const GlobalMap::Level& grid = map.level(level);
  const std::size_t node = static_cast<std::size_t>(y) * layout.width + x;
  const float ground_min = grid.ground_min_m[node];
  if (!std::isfinite(ground_min)) return -1;
  // Scan bin j (heights above the vehicle's ground) meets map bins [lo + j, lo + j + w] for
  // every ground height of the block, widened by the tolerance.
  const int lo = map.ZBin(ground_min - z_tolerance_m);
  const int w = map.ZBin(grid.ground_max_m[node] + z_tolerance_m) + 1 - lo;
  const int shift = lo - DiscreteScan::kGroundBin;
  const int32_t block = int32_t{1} << level;
  int score = 0;
  const std::vector<ScanColumn>& columns = scan.columns[static_cast<std::size_t>(yaw_index)];
  const std::vector<int>& voxels_from = scan.voxels_from[static_cast<std::size_t>(yaw_index)];
  for (std::size_t c = 0; c < columns.size(); ++c) {
    // Every 16 columns: stop once even all the rest cannot lift the score above the cutoff.
    if ((c & 15) == 0 && score + voxels_from[c] <= cutoff) {
      if (columns_scored != nullptr) *columns_scored += c;
      return score + voxels_from[c];
    }
    const ScanColumn& column = columns[c];
    int32_t cx = x + column.dx, cy = y + column.dy;
    // A block starting left of (or below) the raster still overlaps it up to cx + block: the
    // block at 0 covers that overlap (a looser bound, never a smaller one).
    if (cx >= layout.width || cy >= layout.height || cx + block <= 0 || cy + block <= 0) continue;
    cx = std::max(cx, 0);
    cy = std::max(cy, 0);
    const uint64_t occupied = grid.occupancy[static_cast<std::size_t>(cy) * layout.width + cx];
    if (occupied == 0) continue;
    score += __builtin_popcountll(ShiftRight(DilateDown(occupied, w), shift) & column.bins);
  }
  if (columns_scored != nullptr) *columns_scored += columns.size();
  return score;
}

std::vector<BnbCandidate> BranchAndBound(const DiscreteScan& scan, const GlobalMap& map,
                                         const BnbOptions& options, std::size_t* nodes_scored,
                                         std::size_t* columns_scored) {
  Search search(scan, map, options);
  search.Run();
  if (nodes_scored != nullptr) *nodes_scored = search.nodes_scored();
  if (columns_scored != nullptr) *columns_scored = search.columns_scored();
  return search.results();
}

}  // namespace hylo::localization::internal
