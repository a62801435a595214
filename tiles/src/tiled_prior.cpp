#include "hylo/tiles/tiled_prior.h"

#include <utility>

#include "hylo/common/check.h"

namespace hylo::tiles {
namespace {

std::shared_ptr<TileStreamer> NotNull(std::shared_ptr<TileStreamer> streamer) {
  HYLO_CHECK(streamer != nullptr);
  return streamer;
}

}  // namespace

TiledPrior::TiledPrior(std::shared_ptr<TileStreamer> streamer, std::size_t cache_max_points)
    : streamer_(NotNull(std::move(streamer))),
      held_(std::make_shared<const TileSet>()),
      cache_(streamer_->shared_source(), cache_max_points) {
  streamer_->TakeUpdate(&held_);
}

void TiledPrior::Follow(const Eigen::Vector3f& position_map) {
  streamer_->SetPosition(position_map);
  streamer_->TakeUpdate(&held_);
}

void TiledPrior::SetOnDemand(bool on_demand) {
  // Tiles read on demand are for the start and a lost vehicle: once tracking again, the
  // memory goes back to the tiles around the vehicle.
  if (on_demand_ && !on_demand) cache_.Clear();
  on_demand_ = on_demand;
  streamer_->TakeUpdate(&held_);
}

bool TiledPrior::OnMap(const Eigen::Vector3f& position_map) const {
  return streamer_->OnMap(position_map);
}

std::string TiledPrior::error() const { return streamer_->error(); }

void TiledPrior::KNearest(const Eigen::Vector3f& query, int k, float max_distance,
                          std::vector<registration::Neighbor>* neighbors) const {
  if (on_demand_) {
    cache_.KNearestPreferring(held_.get(), query, k, max_distance, neighbors);
  } else {
    held_->KNearest(query, k, max_distance, neighbors);
  }
}

std::size_t TiledPrior::Size() const { return on_demand_ ? cache_.Size() : held_->Size(); }

}  // namespace hylo::tiles
