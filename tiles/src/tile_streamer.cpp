// The background loader of a tiled prior (tile_streamer.h).
#include "hylo/tiles/tile_streamer.h"

#include <time.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "hylo/common/check.h"
#include "hylo/common/option_checks.h"

namespace hylo::tiles {
namespace {

double ThreadCpuS() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

}  // namespace

bool TileStreamerOptions::IsValid(std::string* why) const {
  return CheckPositive("load_radius_m", load_radius_m, why) &&
         CheckNonNegative("unload_margin_m", unload_margin_m, why);
}

TileStreamer::TileStreamer(std::shared_ptr<const TileSource> source,
                           const TileStreamerOptions& options)
    : source_(std::move(source)),
      options_(options),
      grid_(source_->tile_size_m()),
      lookup_(source_->tiles()) {
  std::string why;
  if (!options_.IsValid(&why)) throw InternalError("TileStreamerOptions: " + why);
  thread_ = std::thread(&TileStreamer::Run, this);
}

TileStreamer::~TileStreamer() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  progress_.notify_all();
  thread_.join();
}

void TileStreamer::SetPosition(const Eigen::Vector3f& position_local) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    position_ = position_local;
    ++requested_;
  }
  wake_.notify_one();
}

bool TileStreamer::TakeUpdate(std::shared_ptr<const TileSet>* current) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (published_ == nullptr) return false;
    if (*current != nullptr) retired_.push_back(std::move(*current));
    *current = std::move(published_);
    published_.reset();
  }
  wake_.notify_one();  // the loader frees what only the retired set held
  return true;
}

void TileStreamer::WaitUntilCurrent() {
  std::unique_lock<std::mutex> lock(mutex_);
  const uint64_t target = requested_;
  progress_.wait(lock, [&] { return done_ >= target || !error_.empty() || stop_; });
}

std::string TileStreamer::error() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return error_;
}

TileStreamerStats TileStreamer::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stats_;
}

bool TileStreamer::OnMap(const Eigen::Vector3f& position_local) const {
  return lookup_.Find(grid_.KeyOf(position_local)) >= 0;
}

bool TileStreamer::Stopping() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stop_;
}

void TileStreamer::Run() {
  uint64_t seen = 0;
  for (;;) {
    Eigen::Vector3f position;
    uint64_t generation = 0;
    std::vector<std::shared_ptr<const TileSet>> retired;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || requested_ != seen || !retired_.empty(); });
      if (stop_) return;
      retired.swap(retired_);
      position = position_;
      generation = requested_;
    }
    retired.clear();  // frees, here, the trees only the retired sets held
    if (generation == seen) continue;
    seen = generation;
    const bool failed = !error().empty();
    if (!failed && !Update(position) && Stopping()) return;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_ = std::max(done_, generation);
    }
    progress_.notify_all();
  }
}

bool TileStreamer::Update(const Eigen::Vector3f& p) {
  const double load2 = options_.load_radius_m * options_.load_radius_m;
  const double keep = options_.load_radius_m + options_.unload_margin_m;
  std::vector<LoadedTile> kept;
  for (LoadedTile& t : held_) {
    if (grid_.SquaredDistanceTo(t.info.key, p) <= keep * keep) kept.push_back(std::move(t));
  }
  const std::size_t unloaded = held_.size() - kept.size();
  held_.swap(kept);
  kept.clear();
  // Wanted tiles not held, nearest first (only the keys around the vehicle are looked at).
  std::vector<std::pair<double, int>> wanted;
  const TileKey lo = grid_.KeyOf(p - Eigen::Vector3f::Constant(options_.load_radius_m));
  const TileKey hi = grid_.KeyOf(p + Eigen::Vector3f::Constant(options_.load_radius_m));
  for (int64_t y = lo.iy; y <= hi.iy; ++y) {
    for (int64_t x = lo.ix; x <= hi.ix; ++x) {
      const TileKey key{static_cast<int32_t>(x), static_cast<int32_t>(y)};
      const int i = lookup_.Find(key);
      if (i < 0) continue;
      const double d2 = grid_.SquaredDistanceTo(key, p);
      const bool held = std::any_of(held_.begin(), held_.end(),
                                    [&](const LoadedTile& t) { return t.info.key == key; });
      if (d2 <= load2 && !held) wanted.emplace_back(d2, i);
    }
  }
  std::sort(wanted.begin(), wanted.end());
  if (unloaded > 0) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stats_.tiles_unloaded += unloaded;
    }
    Publish();
  }
  for (const auto& [d2, i] : wanted) {
    if (Stopping()) return false;
    const TileInfo& info = source_->tiles()[static_cast<std::size_t>(i)];
    const double cpu_start = ThreadCpuS();
    LoadedTile tile;
    try {
      tile = BuildTile(info, source_->Load(info.key));
    } catch (const std::exception& e) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        error_ = e.what();
      }
      progress_.notify_all();
      return false;
    }
    const std::size_t points = tile.tree->Size();
    held_.push_back(std::move(tile));
    {
      std::lock_guard<std::mutex> lock(mutex_);
      ++stats_.tiles_loaded;
      stats_.points_loaded += points;
      stats_.load_cpu_s += ThreadCpuS() - cpu_start;
    }
    Publish();
  }
  return true;
}

void TileStreamer::Publish() {
  auto set = std::make_shared<const TileSet>(grid_.tile_size_m(), held_);
  std::shared_ptr<const TileSet> untaken;  // a set the scan path never took: freed unlocked
  {
    std::lock_guard<std::mutex> lock(mutex_);
    untaken = std::move(published_);
    published_ = std::move(set);
    stats_.max_tiles_held = std::max(stats_.max_tiles_held, published_->tiles().size());
    stats_.max_points_held = std::max(stats_.max_points_held, published_->Size());
  }
}

}  // namespace hylo::tiles
