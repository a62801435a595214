#include "hylo/registration/voxel_filter.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <string>

#include "hylo/common/check.h"
#include "hylo/common/voxel_key.h"
#include "hylo/registration/parallel.h"

namespace hylo::registration {
namespace {

// Open-addressing table from voxel key to the kept point of that voxel. It replaces a
// std::unordered_map, whose one heap node per voxel made this the third-largest cost of a
// scan (a profile of `hylo map`): here the slots are one flat array reused from call to call.
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

  // Asks the memory system for the slot where `key`'s probe starts (a large table misses
  // the cache on almost every voxel).
  void Prefetch(const int32_t* key) const { __builtin_prefetch(&slots_[Home(key)]); }

  std::size_t MemoryBytes() const { return slots_.capacity() * sizeof(Slot); }

 private:
  // Spatial hash primes (Teschner et al. 2003), then a Fibonacci mix so that the low bits
  // used by the mask depend on every coordinate.
  std::size_t Home(const int32_t* key) const {
    const uint64_t h = (static_cast<uint64_t>(static_cast<uint32_t>(key[0])) * 73856093u) ^
                       (static_cast<uint64_t>(static_cast<uint32_t>(key[1])) * 19349663u) ^
                       (static_cast<uint64_t>(static_cast<uint32_t>(key[2])) * 83492791u);
    return static_cast<std::size_t>((h * 0x9E3779B97F4A7C15ull) >> 32) & (slots_.size() - 1);
  }

  Slot* Probe(const int32_t* key) {
    const std::size_t mask = slots_.size() - 1;
    std::size_t i = Home(key);
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

// The voxel table keys voxels by int32 indices (half the probe traffic of int64 keys); callers
// keep points within that range (see UniformSampler::Add).
void VoxelKeyOf(const Eigen::Vector3f& point, float voxel_size_m, int32_t* key) {
  const VoxelKey voxel = VoxelOf(point, voxel_size_m);
  key[0] = static_cast<int32_t>(voxel.x());
  key[1] = static_cast<int32_t>(voxel.y());
  key[2] = static_cast<int32_t>(voxel.z());
}

// Which of `parts` a voxel belongs to: the top bits of a mix of its key, independent of the
// bits VoxelTable::Home takes (a part's voxels spread over all of its table's slots).
int PartOf(const int32_t* key, int parts) {
  const uint64_t h = (static_cast<uint64_t>(static_cast<uint32_t>(key[0])) * 73856093u) ^
                     (static_cast<uint64_t>(static_cast<uint32_t>(key[1])) * 19349663u) ^
                     (static_cast<uint64_t>(static_cast<uint32_t>(key[2])) * 83492791u);
  return static_cast<int>(((h * 0x9E3779B97F4A7C15ull) >> 56) % static_cast<uint64_t>(parts));
}

enum class Offer { kNewVoxel, kReplaces, kRejected };

// Offers `point` to its voxel in `table`. A new voxel records `next_position` (the caller
// appends the point there); a point nearer the centre than the voxel's takes its place
// (returned through `replaced_position`); otherwise the voxel keeps its point.
Offer OfferPoint(const Eigen::Vector3f& point, float voxel_size_m, uint32_t next_position,
                 VoxelTable* table, uint32_t* replaced_position) {
  int32_t key[3];
  VoxelKeyOf(point, voxel_size_m, key);
  const Eigen::Vector3f centre = VoxelCentre(VoxelKey(key[0], key[1], key[2]), voxel_size_m);
  const float d2 = (point - centre).squaredNorm();
  VoxelTable::Slot* slot = table->Find(key);
  if (slot->kept == VoxelTable::kEmpty) {
    slot->kept = next_position;
    slot->squared_distance = d2;
    return Offer::kNewVoxel;
  }
  if (!(d2 < slot->squared_distance)) return Offer::kRejected;
  slot->squared_distance = d2;
  *replaced_position = slot->kept;
  return Offer::kReplaces;
}

std::vector<std::size_t> UniformSampleIndicesInParts(const PointCloud& points, float voxel_size_m,
                                                     int parts);

// Sized for half the points as voxels: a 0.5 m scan voxel keeps ~10 % of a 16-beam scan,
// a 0.1 m dense copy ~60 %, and growing (rehashing) mid-scan cost more than a larger
// clear. Map-sized clouds start at 1M voxels (40 MiB) and grow only if they need to.
std::size_t ExpectedVoxels(std::size_t points) {
  constexpr std::size_t kMaxInitialVoxels = std::size_t{1} << 20;
  return std::min(points / 2, kMaxInitialVoxels) + 16;
}

}  // namespace

std::vector<std::size_t> UniformSampleIndices(const PointCloud& points, float voxel_size_m) {
  std::vector<std::size_t> kept;
  if (voxel_size_m <= 0.f) {
    kept.resize(points.size());
    std::iota(kept.begin(), kept.end(), 0);
    return kept;
  }
  // Below a few thousand points the parts cost more than they save; each part reads every
  // point's part number, so more parts than a few dozen would cost more than they save too.
  constexpr std::size_t kMinPointsInParts = 4096;
  constexpr int kMaxParts = 32;
  const int threads = ParallelThreads();
  if (threads > 1 && points.size() >= kMinPointsInParts) {
    return UniformSampleIndicesInParts(points, voxel_size_m, std::min(threads, kMaxParts));
  }
  thread_local VoxelTable table;
  table.Reset(ExpectedVoxels(points.size()));
  for (std::size_t i = 0; i < points.size(); ++i) {
    uint32_t position = 0;
    switch (OfferPoint(points[i], voxel_size_m, static_cast<uint32_t>(kept.size()), &table,
                       &position)) {
      case Offer::kNewVoxel: kept.push_back(i); break;
      case Offer::kReplaces: kept[position] = i; break;
      case Offer::kRejected: break;
    }
  }
  return kept;
}

namespace {

// UniformSampleIndices with the voxels split into `parts` (<= 255) by PartOf, each part sampled on
// its own table (in parallel), and the same result: the kept list holds each voxel's point nearest
// its centre (the earliest on a tie) at the place of the voxel's first point, so the parts'
// voxels, written at their first points' indices, merge in that order.
std::vector<std::size_t> UniformSampleIndicesInParts(const PointCloud& points, float voxel_size_m,
                                                     int parts) {
  const std::size_t n = points.size();
  std::vector<uint8_t> part_of(n);
  ParallelFor(n, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      int32_t key[3];
      VoxelKeyOf(points[i], voxel_size_m, key);
      part_of[i] = static_cast<uint8_t>(PartOf(key, parts));
    }
  });
  // kept_at_first[i]: 1 + the kept index of the voxel whose first point is i; 0 for none.
  std::vector<uint32_t> kept_at_first(n, 0);
  ParallelTasks(parts, [&](int part) {
    thread_local VoxelTable table;
    table.Reset(ExpectedVoxels(n) / static_cast<std::size_t>(parts) + 16);
    std::vector<uint32_t> first, best;  // per voxel of this part, in order of appearance
    for (std::size_t i = 0; i < n; ++i) {
      if (part_of[i] != part) continue;
      uint32_t position = 0;
      switch (OfferPoint(points[i], voxel_size_m, static_cast<uint32_t>(first.size()), &table,
                         &position)) {
        case Offer::kNewVoxel:
          first.push_back(static_cast<uint32_t>(i));
          best.push_back(static_cast<uint32_t>(i));
          break;
        case Offer::kReplaces:
          best[position] = static_cast<uint32_t>(i);
          break;
        case Offer::kRejected:
          break;
      }
    }
    for (std::size_t v = 0; v < first.size(); ++v) kept_at_first[first[v]] = best[v] + 1;
  });
  std::vector<std::size_t> kept;
  for (std::size_t i = 0; i < n; ++i) {
    if (kept_at_first[i] != 0) kept.push_back(kept_at_first[i] - 1);
  }
  return kept;
}

}  // namespace

class UniformSampler::Table : public VoxelTable {};

UniformSampler::UniformSampler(float voxel_size_m)
    : table_(std::make_unique<Table>()), voxel_size_m_(voxel_size_m) {
  if (!(voxel_size_m > 0.f) || !std::isfinite(voxel_size_m)) {
    throw InternalError("UniformSampler: voxel_size_m = " + std::to_string(voxel_size_m) +
                        " must be finite and > 0");
  }
  table_->Reset(1024);
}

UniformSampler::~UniformSampler() = default;
UniformSampler::UniformSampler(UniformSampler&&) noexcept = default;
UniformSampler& UniformSampler::operator=(UniformSampler&&) noexcept = default;

std::size_t UniformSampler::Add(const PointCloud& points) {
  const float inverse_voxel = 1.f / voxel_size_m_;
  // Keys are int32 voxel indices: a finite point beyond their range is as unusable as NaN.
  auto usable = [inverse_voxel](const Eigen::Vector3f& p) {
    return p.allFinite() && (p.cwiseAbs() * inverse_voxel).maxCoeff() <= 2.0e9f;
  };
  // A map-sized table misses the cache on nearly every point: the slot of the point a few
  // places ahead is requested early (dense map of hylo map: ~2x faster inserts).
  constexpr std::size_t kPrefetchAhead = 8;
  std::size_t non_finite = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (i + kPrefetchAhead < points.size() && usable(points[i + kPrefetchAhead])) {
      int32_t key[3];
      VoxelKeyOf(points[i + kPrefetchAhead], voxel_size_m_, key);
      table_->Prefetch(key);
    }
    const Eigen::Vector3f& p = points[i];
    if (!usable(p)) {
      ++non_finite;
      continue;
    }
    uint32_t position = 0;
    switch (OfferPoint(p, voxel_size_m_, static_cast<uint32_t>(points_.size()), table_.get(),
                       &position)) {
      case Offer::kNewVoxel: points_.push_back(p); break;
      case Offer::kReplaces: points_[position] = p; break;
      case Offer::kRejected: break;
    }
  }
  return non_finite;
}

std::size_t UniformSampler::MemoryBytes() const {
  return table_->MemoryBytes() + points_.capacity() * sizeof(Eigen::Vector3f);
}

PointCloud UniformSample(const PointCloud& points, float voxel_size_m) {
  PointCloud out;
  const std::vector<std::size_t> kept = UniformSampleIndices(points, voxel_size_m);
  out.reserve(kept.size());
  for (std::size_t i : kept) out.push_back(points[i]);
  return out;
}

}  // namespace hylo::registration
