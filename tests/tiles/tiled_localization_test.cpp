// Localization in a tiled prior on the simulator: session A mapped by SLAM, written as a map
// file and cut into 20 m tiles (hylo tile's code), then session B localized in both through
// the run layer (run::LoadPriorMap, what `hylo localize` and the ROS node call). The tiles
// stream around the vehicle; the ATE must be the untiled map's. Then the tiled map's own
// behaviours: a hole in the tiles (odometry only, said in events), hybrid additions written
// back as tiles and loaded by the next session.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "estimation/sim_localization_util.h"
#include "hylo/io/cloud_io.h"
#include "hylo/run/prior_map_io.h"
#include "hylo/tiles/map_tiler.h"
#include "hylo/tiles/tiled_map.h"
#include "hylo/tiles/tiled_prior.h"
#include "hylo/tiles/tiled_prior_map.h"
#include "test_data.h"

namespace hylo::testing {
namespace {

using estimation::Estimator;
using localization::LocalizationEvent;

constexpr double kDegToRad = M_PI / 180.0;

sim::SimulationOptions SimOptions() { return sim::SimulationOptions(); }  // seed 1, as the demo

const sim::Site& SharedSite() {
  static const sim::Site site = sim::BuildSite(SimOptions().seed, SimOptions().terrain);
  return site;
}

// SLAM on session A, cached per build of this test (as tests/estimation/sim_localization_test).
const SimPrior& SharedPrior() {
  static const SimPrior prior = [] {
    return CachedSimPriorForThisBuild(SimOptions(), SharedSite(), "sim_prior_seed1_tiled");
  }();
  return prior;
}

// The prior as a map file (A's map frame is the "world") and cut into tiles, once.
struct PriorFiles {
  std::string pcd, tiled;
};
const PriorFiles& SharedFiles() {
  static const PriorFiles files = [] {
    PriorFiles f;
    const std::string dir = ScratchDir("tiled_localization");
    f.pcd = dir + "/prior.pcd";
    f.tiled = dir + "/prior_tiles";
    io::CloudFile cloud;
    for (const Eigen::Vector3f& p : SharedPrior().points_map)
      cloud.positions.push_back(p.cast<double>());
    io::WriteCloud(f.pcd, cloud);
    tiles::TileMapOptions options;
    options.tile_size_m = 20.0;  // ~40 tiles over the site: they stream during the drive
    tiles::TileMapFile(f.pcd, f.tiled, options);
    return f;
  }();
  return files;
}

// The true start of session B in the prior's frame, moved by (dx, dy) m and dyaw deg.
Eigen::Isometry3d PerturbedStart(const sim::SimulationOptions& options, double dx, double dy,
                                 double dyaw_deg) {
  struct FirstTruth : sim::SessionSink {
    void OnImu(const ImuSample&) override {}
    void OnScan(const LidarScan&) override {}
    void OnTruth(const sim::TruthSample& t) override {
      if (!have) T_site_imu = t.T_map_imu;
      have = true;
    }
    bool have = false;
    Eigen::Isometry3d T_site_imu = Eigen::Isometry3d::Identity();
  } sink;
  sim::SimulationOptions first = options;
  first.duration_b_s = 0.2;
  sim::SessionSimulator(first, SharedSite(), sim::SessionId::kB).Run(&sink);
  Eigen::Isometry3d guess = SharedPrior().T_site_map.inverse() * sink.T_site_imu;
  guess.translation() += Eigen::Vector3d(dx, dy, 0.0);
  guess.linear() =
      Eigen::AngleAxisd(dyaw_deg * kDegToRad, Eigen::Vector3d::UnitZ()) * guess.linear();
  return guess;
}

struct SessionRun {
  std::unique_ptr<LocalizationSink> sink;
  mapping::PriorMap prior;
  evaluation::AteResult ate;
};

// Session B localized in the map at `map_path` (file or tiled directory) from `guess`.
SessionRun RunSessionB(const std::string& map_path, const sim::SimulationOptions& sim_options,
                       Estimator::Backend backend, double update_after_s,
                       const Eigen::Isometry3d& guess,
                       const mapping::PriorMapOptions& prior_options = {}) {
  odometry::OdometryPipelineOptions options = PipelineOptionsFor(sim_options);
  options.estimator.backend = backend;
  options.localization.update_after_s = update_after_s;
  SessionRun run;
  run.sink = std::make_unique<LocalizationSink>(options);
  run.prior = run::LoadPriorMap(map_path, prior_options, guess, &run.sink->pipeline);
  sim::SessionSimulator(sim_options, SharedSite(), sim::SessionId::kB).Run(run.sink.get());
  run.sink->Finish();
  if (!run.sink->session.finalized().empty()) {
    run.ate = evaluation::ComputeAte(run.sink->Estimate(), run.sink->truth);
  }
  return run;
}

class TiledLocalization : public ::testing::TestWithParam<Estimator::Backend> {};

TEST_P(TiledLocalization, GivesTheUntiledMapsTrajectory) {
  const sim::SimulationOptions sim_options = SimOptions();
  const Eigen::Isometry3d guess = PerturbedStart(sim_options, 1.4, -1.4, 20.0);
  const SessionRun whole = RunSessionB(SharedFiles().pcd, sim_options, GetParam(), -1.0, guess);
  // The default radius (the scan's reach, 102 m) holds this small site whole (the same ATE to
  // 0.01 mm); 60 m makes the tiles come and go along the drive, and leaves the farthest scan
  // points without a map.
  mapping::PriorMapOptions window;
  window.tile_load_radius_m = 60.0;
  window.tile_unload_margin_m = 10.0;
  const SessionRun tiled =
      RunSessionB(SharedFiles().tiled, sim_options, GetParam(), -1.0, guess, window);
  for (const SessionRun* run : {&whole, &tiled}) {
    ASSERT_NE(run->sink->pipeline.status(), odometry::OdometryPipeline::Status::kFailed)
        << run->sink->pipeline.message();
    ASSERT_TRUE(run->ate.ok) << run->ate.message;
  }
  // The same map: the tiler thins as the whole-map load does, with the same origin.
  EXPECT_EQ(tiled.prior.num_kept, whole.prior.num_kept);
  EXPECT_EQ(tiled.prior.origin_world, whole.prior.origin_world);
  const auto& streamer =
      dynamic_cast<const tiles::TiledPrior&>(*tiled.sink->pipeline.map().streamed_prior())
          .streamer();
  const auto stats = streamer.stats();
  std::printf(
      "[%s] ATE whole map %.5f m, tiled %.5f m (rotation %.4f / %.4f deg); %zu scans / "
      "%zu; tiles loaded %zu, unloaded %zu, at most %zu tiles (%zu of %zu points) held\n",
      estimation::ToString(GetParam()).c_str(), whole.ate.rmse_m, tiled.ate.rmse_m,
      whole.ate.rotation_rmse_deg, tiled.ate.rotation_rmse_deg, tiled.sink->results().size(),
      whole.sink->results().size(), stats.tiles_loaded, stats.tiles_unloaded, stats.max_tiles_held,
      stats.max_points_held, whole.prior.num_kept);
  EXPECT_GT(tiled.ate.path_length_m, 100.0);
  EXPECT_EQ(tiled.sink->results().size(), whole.sink->results().size());
  // The tiles hold the same points and the search over them is exact; what differs is the
  // map beyond 60 m, and tiles arriving a scan later than the whole map had them: within 1 mm.
  EXPECT_NEAR(tiled.ate.rmse_m, whole.ate.rmse_m, 1e-3);
  // This site is small for the window (70 m around the vehicle covers most of it at times):
  // what must show is tiles leaving and coming back as the vehicle moves.
  EXPECT_GT(stats.tiles_unloaded, 0u);
  EXPECT_GT(stats.tiles_loaded, streamer.source().tiles().size());
}

INSTANTIATE_TEST_SUITE_P(Backends, TiledLocalization,
                         ::testing::Values(Estimator::Backend::kIeskf,
                                           Estimator::Backend::kSlidingWindow),
                         [](const auto& info) { return estimation::ToString(info.param); });

// Session B's first 70 s drive east along y = 47 from x = 40 to x = 90 (site frame).
sim::SimulationOptions EastwardB() {
  sim::SimulationOptions o = SimOptions();
  o.duration_b_s = 70.0;
  return o;
}

TEST(TiledLocalizationOffMap, AHoleInTheTilesIsCrossedInOdometryModeAndSaidSo) {
  // The tiled map without the tiles the route crosses between x = 62 and 78 m (site frame).
  const std::string dir = ScratchDir("tiled_hole") + "/holed";
  std::filesystem::copy(SharedFiles().tiled, dir, std::filesystem::copy_options::recursive);
  tiles::TiledMapIndex index = tiles::ReadTiledMapIndex(dir);
  const tiles::TileGrid grid(index.tile_size_m);
  std::vector<tiles::TileKey> hole;
  for (double x = 62.0; x <= 78.0; x += 0.5) {
    const Eigen::Vector3d p_map =
        SharedPrior().T_site_map.inverse() * Eigen::Vector3d(x, 47.0, 0.0);
    hole.push_back(grid.KeyOf((p_map - index.origin_world).cast<float>()));
  }
  std::vector<tiles::TiledMapTile> kept;
  index.points = 0;
  for (const tiles::TiledMapTile& t : index.tiles) {
    if (std::count(hole.begin(), hole.end(), tiles::TileKey{t.ix, t.iy}) > 0) continue;
    kept.push_back(t);
    index.points += t.points;
  }
  ASSERT_LT(kept.size(), index.tiles.size());
  index.tiles = kept;
  tiles::WriteTiledMapIndex(dir, index);
  const SessionRun run = RunSessionB(dir, EastwardB(), Estimator::Backend::kIeskf, -1.0,
                                     PerturbedStart(EastwardB(), 0.5, -0.5, 5.0));
  const auto& pipeline = run.sink->pipeline;
  ASSERT_NE(pipeline.status(), odometry::OdometryPipeline::Status::kFailed) << pipeline.message();
  std::vector<LocalizationEvent::Kind> kinds;
  for (const auto& e : pipeline.events()) {
    kinds.push_back(e.kind);
    std::printf("event %s at %.1f s: %s\n", localization::ToString(e.kind).c_str(),
                1e-9 * static_cast<double>(e.t_ns - run.sink->truth.front().t_ns),
                e.message.c_str());
  }
  const std::vector<LocalizationEvent::Kind> expected = {LocalizationEvent::Kind::kInitialized,
                                                         LocalizationEvent::Kind::kLeftMap,
                                                         LocalizationEvent::Kind::kReenteredMap};
  EXPECT_EQ(kinds, expected);
  EXPECT_GT(pipeline.map().run_size(), 0u) << "odometry mode extends the run's map";
  ASSERT_TRUE(run.ate.ok) << run.ate.message;
  std::printf("ATE across the hole %.4f m over %.1f m\n", run.ate.rmse_m, run.ate.path_length_m);
  EXPECT_LE(run.ate.rmse_m, 0.05);
}

TEST(TiledLocalizationHybrid, AddedPointsAreWrittenAsTilesAndLoadedByTheNextSession) {
  const std::string dir = ScratchDir("tiled_hybrid");
  const std::string map_dir = dir + "/map";
  std::filesystem::copy(SharedFiles().tiled, map_dir, std::filesystem::copy_options::recursive);
  sim::SimulationOptions options = SimOptions();
  options.duration_b_s = 40.0;
  const Eigen::Isometry3d guess = PerturbedStart(options, 0.5, -0.5, 5.0);
  const SessionRun first = RunSessionB(map_dir, options, Estimator::Backend::kIeskf, 5.0, guess);
  ASSERT_NE(first.sink->pipeline.status(), odometry::OdometryPipeline::Status::kFailed);
  const mapping::MapManager& map = first.sink->pipeline.map();
  const std::size_t added = map.run_size() + map.windowed_out().size();
  ASSERT_GT(added, 100u);
  const std::size_t written =
      tiles::WriteAddedTiles(dir + "/out/map_added", first.prior, first.sink->pipeline, 0.5);
  EXPECT_EQ(written, added);  // already thinned at the map voxel on the run's tree
  const tiles::TiledMapIndex layer = tiles::ReadTiledMapIndex(dir + "/out/map_added");
  const tiles::TiledMapIndex base = tiles::ReadTiledMapIndex(map_dir);
  EXPECT_EQ(layer.origin_world, base.origin_world);
  EXPECT_EQ(layer.tile_size_m, base.tile_size_m);
  // The next session starts from the grown map: the layer moved into the map directory.
  std::filesystem::rename(dir + "/out/map_added", map_dir + "/map_added");
  const SessionRun second = RunSessionB(map_dir, options, Estimator::Backend::kIeskf, -1.0, guess);
  ASSERT_NE(second.sink->pipeline.status(), odometry::OdometryPipeline::Status::kFailed);
  EXPECT_EQ(second.prior.num_kept, base.points + layer.points);
  ASSERT_TRUE(second.ate.ok);
  EXPECT_LE(second.ate.rmse_m, 0.03);
  // Its own additions (none: localization only) leave the earlier layer as it was written.
  EXPECT_EQ(tiles::WriteAddedTiles(dir + "/again", second.prior, second.sink->pipeline, 0.5),
            layer.points);
}

}  // namespace
}  // namespace hylo::testing
