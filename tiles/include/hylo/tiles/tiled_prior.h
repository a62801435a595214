#pragma once
// A tiled prior as the map manager's streamed prior (mapping/streamed_prior.h): the tiles a
// TileStreamer keeps around the vehicle, searched between two swaps as one TileSet, and on
// demand every other tile through a TileCache.

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "hylo/mapping/streamed_prior.h"
#include "hylo/tiles/tile_streamer.h"
#include "hylo/tiles/tiles.h"

namespace hylo::tiles {

class TiledPrior final : public mapping::StreamedPrior {
 public:
  /// `cache_max_points` bounds the tiles read on demand. Takes whatever set `streamer` (not
  /// null) already finished.
  TiledPrior(std::shared_ptr<TileStreamer> streamer, std::size_t cache_max_points);

  void Follow(const Eigen::Vector3f& position_map) override;
  void SetOnDemand(bool on_demand) override;
  bool OnMap(const Eigen::Vector3f& position_map) const override;
  std::string error() const override;
  void KNearest(const Eigen::Vector3f& query, int k, float max_distance,
                std::vector<registration::Neighbor>* neighbors) const override;
  std::size_t Size() const override;
  std::size_t HeldSize() const override { return held_->Size(); }
  PointCloud FlattenHeld() const override { return held_->Flatten(); }
  std::size_t MemoryBytes() const override { return held_->MemoryBytes(); }

  const TileStreamer& streamer() const { return *streamer_; }
  const TileCache& cache() const { return cache_; }

 private:
  std::shared_ptr<TileStreamer> streamer_;
  std::shared_ptr<const TileSet> held_;  // the tiles held now (the scan thread's copy)
  TileCache cache_;                      // on-demand reads of the other tiles
  bool on_demand_ = false;
};

}  // namespace hylo::tiles
