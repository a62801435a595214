#pragma once
// Keeps the tiles of a tiled prior (tiles.h) that lie around the vehicle, loading and unloading
// them in a background thread. The scan path only posts the vehicle's position and picks up
// the newest finished TileSet (a pointer swap under a mutex): reading files, thinning and
// building trees all happen on the loader thread, and the trees of unloaded tiles are freed
// there too.
//
// A tile is wanted when its square comes within load_radius_m of the vehicle (horizontally),
// and kept until it is farther than load_radius_m + unload_margin_m, so a vehicle going back
// and forth along a tile edge does not make the loader read the same files again and again.
// Wanted tiles load nearest first, and each finished tile is published at once.

#include <Eigen/Core>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "hylo/tiles/tiles.h"

namespace hylo::tiles {

struct TileStreamerOptions {
  double load_radius_m = 110.0;   ///< tiles within this of the vehicle are loaded, m (> 0)
  double unload_margin_m = 25.0;  ///< ... and unloaded beyond load_radius_m + this, m (>= 0)
  bool IsValid(std::string* why) const;
};

/// What the loader did so far.
struct TileStreamerStats {
  std::size_t tiles_loaded = 0;  ///< loads (a tile loaded twice counts twice)
  std::size_t tiles_unloaded = 0;
  std::size_t points_loaded = 0;    ///< points of those loads
  std::size_t max_tiles_held = 0;   ///< most tiles held at once
  std::size_t max_points_held = 0;  ///< most points held at once
  double load_cpu_s = 0.0;          ///< CPU time of the loader thread (read, thin, build), s
};

class TileStreamer {
 public:
  /// Starts the loader thread (idle until the first position). Throws hylo::InternalError
  /// when `options` is not valid.
  TileStreamer(std::shared_ptr<const TileSource> source, const TileStreamerOptions& options);
  /// Stops and joins the loader (a load in progress finishes first).
  ~TileStreamer();
  TileStreamer(const TileStreamer&) = delete;
  TileStreamer& operator=(const TileStreamer&) = delete;

  /// Where the vehicle is (local frame). Cheap; any thread.
  void SetPosition(const Eigen::Vector3f& position_local);
  /// Replaces `*current` by the newest finished tile set when there is one (true); the set it
  /// replaces goes back to the loader, so unloaded trees are freed off the calling thread.
  /// One consumer thread.
  bool TakeUpdate(std::shared_ptr<const TileSet>* current);
  /// Blocks until every tile wanted at the last posted position is loaded, or a load failed
  /// (then error() says why). For the start and for tests: a deterministic wait.
  void WaitUntilCurrent();
  /// The first load failure ("" while none): the file and what is wrong with it. The loader
  /// stops loading after one.
  std::string error() const;
  TileStreamerStats stats() const;
  const TileSource& source() const { return *source_; }
  const std::shared_ptr<const TileSource>& shared_source() const { return source_; }
  const TileStreamerOptions& options() const { return options_; }
  /// True when `position_local` lies on a tile of the map (its square holds map points).
  bool OnMap(const Eigen::Vector3f& position_local) const;

 private:
  void Run();
  // One pass of the loader for `position` (without the lock); false when stopped or failed.
  bool Update(const Eigen::Vector3f& position);
  bool Stopping() const;
  void Publish();  // held_ as the newest set

  std::shared_ptr<const TileSource> source_;
  TileStreamerOptions options_;
  TileGrid grid_;
  TileLookup lookup_;  // over source_->tiles()

  mutable std::mutex mutex_;
  std::condition_variable wake_;      // the loader: new position, retired sets, stop
  std::condition_variable progress_;  // WaitUntilCurrent: a pass finished, or an error
  Eigen::Vector3f position_ = Eigen::Vector3f::Zero();
  uint64_t requested_ = 0;  // generation of the last posted position
  uint64_t done_ = 0;       // generation whose pass finished
  bool stop_ = false;
  std::shared_ptr<const TileSet> published_;  // newest set, not yet taken
  std::vector<std::shared_ptr<const TileSet>> retired_;
  std::string error_;
  TileStreamerStats stats_;

  std::vector<LoadedTile> held_;  // loader thread only: what the newest set holds
  std::thread thread_;            // last: starts after every member above exists
};

}  // namespace hylo::tiles
