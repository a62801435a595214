// Tiled priors: searches over tiles against one tree over the same points (the same distance
// arithmetic, so results must agree exactly, ties aside), the
// on-demand cache, the background loader (tiles appear and disappear as the position moves,
// waited for deterministically), its failures, and the map manager's use of them.

#include "hylo/tiles/tiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <stdexcept>

#include "hylo/mapping/map_manager.h"
#include "hylo/tiles/tile_streamer.h"
#include "hylo/tiles/tiled_prior.h"

namespace hylo::tiles {
namespace {

using registration::Neighbor;

// Tiles of a cloud held in memory; counts its loads, and fails on one key if asked to.
class MemorySource final : public TileSource {
 public:
  MemorySource(const PointCloud& points, double tile_size_m) : tile_size_m_(tile_size_m) {
    const TileGrid grid(tile_size_m);
    std::map<TileKey, PointCloud> split;
    for (const Eigen::Vector3f& p : points) split[grid.KeyOf(p)].push_back(p);
    for (auto& [key, tile] : split) {
      TileInfo info;
      info.key = key;
      info.points = tile.size();
      info.bounds_local.min = info.bounds_local.max = tile.front();
      for (const Eigen::Vector3f& p : tile) {
        info.bounds_local.min = info.bounds_local.min.cwiseMin(p);
        info.bounds_local.max = info.bounds_local.max.cwiseMax(p);
      }
      infos_.push_back(info);
      points_[key] = tile;
    }
  }
  double tile_size_m() const override { return tile_size_m_; }
  const std::vector<TileInfo>& tiles() const override { return infos_; }
  PointCloud Load(const TileKey& key) const override {
    ++loads;
    if (fail_on && *fail_on == key) throw std::runtime_error("tiles/broken.pcd: corrupt");
    return points_.at(key);
  }
  mutable std::atomic<int> loads{0};
  std::optional<TileKey> fail_on;

 private:
  double tile_size_m_;
  std::vector<TileInfo> infos_;
  std::map<TileKey, PointCloud> points_;
};

// Ground with bumps and poles over [-60, 60) x [-40, 40), a hole of missing tiles, and points
// exactly on tile edges.
PointCloud Scene(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> x(-60.f, 60.f), y(-40.f, 40.f), u(0.f, 1.f);
  PointCloud points;
  for (int i = 0; i < 40000; ++i) {
    const Eigen::Vector3f p(x(rng), y(rng), 0.f);
    if (p.x() > 20.f && p.x() < 40.f && p.y() > 0.f) continue;  // a hole in the map
    points.emplace_back(p.x(), p.y(),
                        0.2f * std::sin(p.x()) + (u(rng) < 0.1f ? 4.f * u(rng) : 0.f));
  }
  for (float e = -60.f; e <= 60.f; e += 10.f) points.emplace_back(e, 10.f * u(rng), 1.f);
  return points;
}

void ExpectSameNeighbours(const registration::NeighborSearch& truth,
                          const registration::NeighborSearch& tiles, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> x(-80.f, 80.f), y(-60.f, 60.f), z(-2.f, 6.f);
  std::vector<Neighbor> want, got;
  const float distances[] = {0.5f, 2.f, 15.f, std::numeric_limits<float>::max()};
  for (int i = 0; i < 3000; ++i) {
    Eigen::Vector3f q(x(rng), y(rng), z(rng));
    if (i % 5 == 0) q.x() = 10.f * std::round(q.x() / 10.f);  // on a tile edge
    const int k = 1 + i % 6;
    const float max_distance = distances[i % 4];
    truth.KNearest(q, k, max_distance, &want);
    tiles.KNearest(q, k, max_distance, &got);
    ASSERT_EQ(got.size(), want.size()) << "query " << q.transpose() << " k " << k;
    for (std::size_t j = 0; j < want.size(); ++j) {
      ASSERT_EQ(got[j].squared_distance, want[j].squared_distance)
          << "query " << i << " rank " << j;
      const bool tie =
          (j > 0 && want[j - 1].squared_distance == want[j].squared_distance) ||
          (j + 1 < want.size() && want[j + 1].squared_distance == want[j].squared_distance);
      if (!tie) {
        ASSERT_EQ(got[j].point, want[j].point) << "query " << i << " rank " << j;
      }
    }
  }
}

TEST(TileSet, FindsTheSameNeighboursAsOneSearchOverAllPoints) {
  const PointCloud points = Scene(1);
  const MemorySource source(points, 10.0);
  std::vector<LoadedTile> loaded;
  for (const TileInfo& info : source.tiles())
    loaded.push_back(BuildTile(info, source.Load(info.key)));
  const TileSet set(10.0, loaded);
  EXPECT_EQ(set.Size(), points.size());
  mapping::IkdTree truth;
  truth.Build(points);
  ExpectSameNeighbours(truth, set, 2);
}

TEST(TileCache, FindsTheSameNeighboursWithinItsBound) {
  const PointCloud points = Scene(3);
  const auto source = std::make_shared<MemorySource>(points, 10.0);
  const std::size_t bound = points.size() / 10;
  const TileCache cache(source, bound);
  EXPECT_EQ(cache.Size(), points.size());
  mapping::IkdTree truth;
  truth.Build(points);
  ExpectSameNeighbours(truth, cache, 4);
  EXPECT_GT(cache.tiles_loaded(), source->tiles().size());  // tiles were dropped and read again
}

class StreamerTest : public ::testing::Test {
 protected:
  StreamerTest() : source_(std::make_shared<MemorySource>(Scene(5), 10.0)) {}

  // Keys of the tiles whose square comes within `radius` of `p`.
  std::vector<TileKey> Within(const Eigen::Vector3f& p, double radius) const {
    std::vector<TileKey> keys;
    const TileGrid grid(10.0);
    for (const TileInfo& t : source_->tiles()) {
      if (grid.SquaredDistanceTo(t.key, p) <= radius * radius) keys.push_back(t.key);
    }
    return keys;
  }
  static std::vector<TileKey> Keys(const TileSet& set) {
    std::vector<TileKey> keys;
    for (const LoadedTile& t : set.tiles()) keys.push_back(t.info.key);
    return keys;
  }
  std::shared_ptr<MemorySource> source_;
};

TEST_F(StreamerTest, TilesAppearAndDisappearAsThePositionMoves) {
  TileStreamerOptions options;
  options.load_radius_m = 15.0;
  options.unload_margin_m = 5.0;
  TileStreamer streamer(source_, options);
  std::shared_ptr<const TileSet> current;
  EXPECT_FALSE(streamer.TakeUpdate(&current));  // nothing before a position
  const Eigen::Vector3f a(-45.f, -25.f, 0.f);
  streamer.SetPosition(a);
  streamer.WaitUntilCurrent();
  ASSERT_TRUE(streamer.TakeUpdate(&current));
  EXPECT_EQ(Keys(*current), Within(a, 15.0));
  EXPECT_FALSE(streamer.TakeUpdate(&current));  // no news since

  // Moving 30 m east: the tiles now within 15 m load; those held before stay up to 20 m away.
  const Eigen::Vector3f b(-15.f, -25.f, 0.f);
  streamer.SetPosition(b);
  streamer.WaitUntilCurrent();
  ASSERT_TRUE(streamer.TakeUpdate(&current));
  const std::vector<TileKey> held_at_a = Within(a, 15.0);
  const TileGrid grid(10.0);
  std::vector<TileKey> expected;
  std::size_t dropped = 0;
  for (const TileInfo& t : source_->tiles()) {
    const double d2 = grid.SquaredDistanceTo(t.key, b);
    const bool held = std::count(held_at_a.begin(), held_at_a.end(), t.key) > 0;
    if (d2 <= 15.0 * 15.0 || (held && d2 <= 20.0 * 20.0)) expected.push_back(t.key);
    dropped += held && d2 > 20.0 * 20.0 ? 1 : 0;
  }
  EXPECT_EQ(Keys(*current), expected);
  EXPECT_GT(dropped, 0u);
  const TileStreamerStats stats = streamer.stats();
  EXPECT_EQ(stats.tiles_loaded, static_cast<std::size_t>(source_->loads.load()));
  EXPECT_EQ(stats.tiles_unloaded, dropped);
  EXPECT_TRUE(streamer.error().empty());
  // Where the map has tiles, and where it has none.
  EXPECT_TRUE(streamer.OnMap(b));
  EXPECT_FALSE(streamer.OnMap(Eigen::Vector3f(30.f, 20.f, 0.f)));  // the hole
  EXPECT_FALSE(streamer.OnMap(Eigen::Vector3f(500.f, 0.f, 0.f)));  // far outside
}

TEST_F(StreamerTest, AFailedLoadIsReportedAndStopsTheLoader) {
  source_->fail_on = TileKey{-5, -3};
  TileStreamerOptions options;
  options.load_radius_m = 12.0;
  TileStreamer streamer(source_, options);
  streamer.SetPosition(Eigen::Vector3f(-45.f, -25.f, 0.f));
  streamer.WaitUntilCurrent();  // returns on the error, it does not hang
  EXPECT_NE(streamer.error().find("tiles/broken.pcd: corrupt"), std::string::npos);
  const int loads = source_->loads;
  streamer.SetPosition(Eigen::Vector3f(0.f, 0.f, 0.f));
  streamer.WaitUntilCurrent();
  EXPECT_EQ(source_->loads, loads);  // no more loads after a failure
}

TEST_F(StreamerTest, TheMapManagerSearchesRunPointsAndTheTilesItHolds) {
  mapping::MapManagerOptions map_options;
  map_options.window_size_m = 0.0;
  mapping::MapManager map(map_options);
  TileStreamerOptions options;
  options.load_radius_m = 25.0;
  auto streamer = std::make_shared<TileStreamer>(source_, options);
  auto tiled = std::make_shared<TiledPrior>(streamer, 1000000);
  map.SetStreamedPrior(tiled);
  EXPECT_TRUE(map.streamed());
  EXPECT_EQ(map.prior_size(), 0u);
  const Eigen::Vector3f p(-40.f, -20.f, 0.f);
  map.BeginScan(p);
  streamer->WaitUntilCurrent();
  map.BeginScan(p);  // picks up the finished set
  PointCloud held;
  for (const TileKey& key : Within(p, 25.0)) {
    const PointCloud tile = source_->Load(key);
    held.insert(held.end(), tile.begin(), tile.end());
  }
  EXPECT_EQ(map.prior_size(), held.size());
  const PointCloud run = {{-40.f, -20.f, 0.05f}, {-39.9f, -20.f, 0.05f}};
  map.AddScan(run, p);
  const PointCloud kept = map.FlattenRun();  // downsampled on the tree
  ASSERT_FALSE(kept.empty());
  held.insert(held.end(), kept.begin(), kept.end());
  mapping::IkdTree truth;
  truth.Build(held);
  std::vector<Neighbor> want, got;
  for (float dx = -5.f; dx <= 5.f; dx += 0.7f) {
    const Eigen::Vector3f q = p + Eigen::Vector3f(dx, 0.3f * dx, 0.1f);
    truth.KNearest(q, 5, 2.f, &want);
    map.KNearest(q, 5, 2.f, &got);
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t j = 0; j < want.size(); ++j) {
      EXPECT_EQ(got[j].squared_distance, want[j].squared_distance);
    }
  }
  // On demand, a query far from the held tiles reads them through the cache.
  const Eigen::Vector3f far(50.f, -30.f, 0.f);
  map.KNearest(far, 1, 1.f, &got);
  EXPECT_TRUE(got.empty());
  map.SetOnDemand(true);
  EXPECT_EQ(map.Size(), map.run_size() + tiled->cache().Size());  // every tile searchable
  map.KNearest(far, 1, 1.f, &got);
  EXPECT_EQ(got.size(), 1u);
  EXPECT_TRUE(map.OnPriorMap(p));
  EXPECT_FALSE(map.OnPriorMap(Eigen::Vector3f(30.f, 20.f, 0.f)));
}

}  // namespace
}  // namespace hylo::tiles
