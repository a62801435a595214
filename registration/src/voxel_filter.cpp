#include "hylo/registration/voxel_filter.h"

#include <cstdint>
#include <limits>
#include <numeric>

namespace hylo::registration {
namespace {

// Open-addressing table from voxel key to the kept point of that voxel. It replaces a
// std::unordered_map, whose one heap node per voxel made this the third-largest cost of a
// scan (perf, issue 5): here the slots are one flat array reused from call to call.
class VoxelTable {
 public:
  struct Slot {
    int32_t key[3];
    uint32_t kept;  // position in the caller's `kept` list; kEmpty when unused
    float squared_distance;
  };
  static constexpr uint32_t kEmpty = std::numeric_limits<uint32_t>::max();

  void Reset(std::size_t expected_voxels) {
    std::size_t capacity = 64;
    while (capacity < 2 * expected_voxels) capacity *= 2;
    slots_.assign(capacity, Slot{{0, 0, 0}, kEmpty, 0.f});
    used_ = 0;
  }

  // The slot of `key`, claimed (kept = kEmpty) when the voxel is new.
  Slot* Find(const int32_t* key) {
    if (2 * (used_ + 1) > slots_.size()) Grow();
    Slot* slot = Probe(key);
    if (slot->kept == kEmpty) {
      slot->key[0] = key[0];
      slot->key[1] = key[1];
      slot->key[2] = key[2];
      ++used_;
    }
    return slot;
  }

 private:
  Slot* Probe(const int32_t* key) {
    const std::size_t mask = slots_.size() - 1;
    // Spatial hash primes (Teschner et al. 2003), then a Fibonacci mix so that the low bits
    // used by the mask depend on every coordinate.
    const uint64_t h = (static_cast<uint64_t>(static_cast<uint32_t>(key[0])) * 73856093u) ^
                       (static_cast<uint64_t>(static_cast<uint32_t>(key[1])) * 19349663u) ^
                       (static_cast<uint64_t>(static_cast<uint32_t>(key[2])) * 83492791u);
    std::size_t i = static_cast<std::size_t>((h * 0x9E3779B97F4A7C15ull) >> 32) & mask;
    while (true) {
      Slot& slot = slots_[i];
      if (slot.kept == kEmpty ||
          (slot.key[0] == key[0] && slot.key[1] == key[1] && slot.key[2] == key[2])) {
        return &slot;
      }
      i = (i + 1) & mask;
    }
  }

  void Grow() {
    std::vector<Slot> old;
    old.swap(slots_);
    slots_.assign(2 * old.size(), Slot{{0, 0, 0}, kEmpty, 0.f});
    for (const Slot& s : old) {
      if (s.kept != kEmpty) *Probe(s.key) = s;
    }
  }

  std::vector<Slot> slots_;
  std::size_t used_ = 0;
};

// std::floor for a value in int range, without the library call that x86-64 without SSE4.1
// makes of it (three per point were a visible share of this function's time).
int32_t FloorToInt(float x) {
  const int32_t truncated = static_cast<int32_t>(x);
  return truncated - (x < static_cast<float>(truncated) ? 1 : 0);
}

}  // namespace

std::vector<std::size_t> UniformSampleIndices(const PointCloud& points, float voxel_size_m) {
  std::vector<std::size_t> kept;
  if (voxel_size_m <= 0.f) {
    kept.resize(points.size());
    std::iota(kept.begin(), kept.end(), 0);
    return kept;
  }
  thread_local VoxelTable table;
  // A scan has several points per voxel at the sizes used here; the table grows if not.
  table.Reset(points.size() / 4 + 16);
  const float inv = 1.f / voxel_size_m;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3f scaled = points[i] * inv;
    const int32_t key[3] = {FloorToInt(scaled.x()), FloorToInt(scaled.y()),
                            FloorToInt(scaled.z())};
    const Eigen::Vector3f centre =
        (Eigen::Vector3f(static_cast<float>(key[0]), static_cast<float>(key[1]),
                         static_cast<float>(key[2])) +
         Eigen::Vector3f::Constant(0.5f)) *
        voxel_size_m;
    const float d2 = (points[i] - centre).squaredNorm();
    VoxelTable::Slot* slot = table.Find(key);
    if (slot->kept == VoxelTable::kEmpty) {
      slot->kept = static_cast<uint32_t>(kept.size());
      slot->squared_distance = d2;
      kept.push_back(i);
    } else if (d2 < slot->squared_distance) {
      slot->squared_distance = d2;
      kept[slot->kept] = i;
    }
  }
  return kept;
}

PointCloud UniformSample(const PointCloud& points, float voxel_size_m) {
  PointCloud out;
  const std::vector<std::size_t> kept = UniformSampleIndices(points, voxel_size_m);
  out.reserve(kept.size());
  for (std::size_t i : kept) out.push_back(points[i]);
  return out;
}

}  // namespace hylo::registration
