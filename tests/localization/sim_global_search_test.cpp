// Searching while moving on a small symmetric site, whole pipeline (simulated lidar + IMU):
// two identical walled bays 40 m apart, the lidar's range kept short so a vehicle standing in
// one sees nothing of the other. Its static view fits both bays equally, so the global start
// must say "ambiguous" and search while it drives. With a building beside the first bay only,
// the drive out of the bay sees it and the start is accepted at the true bay; without it the
// two drives look the same all the way, and no pose may ever be reported.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "estimation/sim_localization_util.h"
#include "hylo/sim/simulator.h"

namespace hylo::testing {
namespace {

using localization::LocalizationEvent;
using odometry::OdometryPipeline;

constexpr double kBaySpacingM = 40.0;  // bay B is bay A moved by this along x
constexpr double kLidarRangeM = 12.0;

struct Block {
  Eigen::Vector3d center;  // of the footprint, on the ground
  Eigen::Vector3d size;
};

// A bay at x = `x0`: walls on three sides (open towards +x) and four boxes of different sizes,
// none symmetric to another, so a view inside it fixes yaw and position within the bay. The
// walls are 1.2 m thick: the prior holds every face, and a thin wall's far face would offer
// the ICP a second basin a wall's thickness away.
std::vector<Block> Bay(double x0) {
  return {{{x0 - 8.4, 0.0, 0.0}, {1.2, 17.6, 3.0}}, {{x0, 8.4, 0.0}, {16.0, 1.2, 2.5}},
          {{x0, -8.4, 0.0}, {16.0, 1.2, 2.5}},      {{x0 - 4.0, 4.0, 0.0}, {1.0, 2.0, 1.5}},
          {{x0 - 3.0, -5.0, 0.0}, {2.0, 1.0, 2.2}}, {{x0 + 3.0, 5.0, 0.0}, {1.5, 1.5, 1.0}},
          {{x0 + 4.0, -3.5, 0.0}, {1.0, 1.0, 2.0}}};
}

// Beside bay A only: a building past its opening and a wall along the lane, out of a standing
// vehicle's range in the bay, in view once it drives out.
std::vector<Block> Landmarks() {
  return {{{18.0, 0.0, 0.0}, {6.0, 12.0, 4.0}}, {{16.0, 11.0, 0.0}, {20.0, 0.4, 3.0}}};
}

std::vector<Block> Blocks(bool with_landmarks) {
  std::vector<Block> blocks = Bay(0.0);
  for (const Block& b : Bay(kBaySpacingM)) blocks.push_back(b);
  if (with_landmarks) {
    for (const Block& b : Landmarks()) blocks.push_back(b);
  }
  return blocks;
}

sim::TerrainOptions FlatTerrainOptions() {
  sim::TerrainOptions options;
  options.min_m = Eigen::Vector2d(-20.0, -25.0);
  options.max_m = Eigen::Vector2d(75.0, 25.0);
  options.resolution_m = 0.4;
  return options;
}

// The site: flat ground, the blocks, session B starting at rest in bay A facing its opening and
// driving 16 m straight out.
sim::Site SymmetricSite(bool with_landmarks) {
  sim::Site site;
  sim::TerrainShape flat;
  flat.undulation_m = 0.0;
  site.terrain = std::make_shared<const sim::Terrain>(flat, FlatTerrainOptions(), 7);
  for (const Block& b : Blocks(with_landmarks)) {
    sim::SiteObject object;
    object.kind = "block";
    object.parts.push_back(
        sim::MakeBox(b.center + Eigen::Vector3d(0, 0, 0.5 * b.size.z()), b.size, 0.0, 0.4f));
    site.objects.push_back(object);
  }
  site.route_a = site.route_b = {Eigen::Vector2d(-3.0, 0.5), Eigen::Vector2d(13.0, 0.5)};
  site.site_min_m = FlatTerrainOptions().min_m;
  site.site_max_m = FlatTerrainOptions().max_m;
  return site;
}

// The prior map: the ground and every face of every block at random, about one point per
// 10 cm x 10 cm (a regular grid would pull the ICP towards its nodes).
PointCloud PriorMap(const sim::Site& site, bool with_landmarks) {
  PointCloud points;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const sim::TerrainOptions t = FlatTerrainOptions();
  const Eigen::Vector2d size = t.max_m - t.min_m - Eigen::Vector2d(1.0, 1.0);
  for (int i = 0; i < static_cast<int>(size.prod() / 0.01); ++i) {
    const double x = t.min_m.x() + 0.5 + unit(rng) * size.x();
    const double y = t.min_m.y() + 0.5 + unit(rng) * size.y();
    points.emplace_back(x, y, site.terrain->Height(x, y));
  }
  const auto face = [&](const Eigen::Vector3d& corner, const Eigen::Vector3d& u,
                        const Eigen::Vector3d& v) {
    const int n = static_cast<int>(u.norm() * v.norm() / 0.01);
    for (int i = 0; i < n; ++i) {
      points.push_back((corner + unit(rng) * u + unit(rng) * v).cast<float>());
    }
  };
  for (const Block& b : Blocks(with_landmarks)) {
    const Eigen::Vector3d lo = b.center - 0.5 * Eigen::Vector3d(b.size.x(), b.size.y(), 0.0);
    const Eigen::Vector3d x(b.size.x(), 0, 0), y(0, b.size.y(), 0), z(0, 0, b.size.z());
    face(lo, x, z);
    face(lo + y, x, z);
    face(lo, y, z);
    face(lo + x, y, z);
    face(lo + z, x, y);
  }
  return points;
}

struct SearchRun {
  std::unique_ptr<LocalizationSink> sink;
};

SearchRun RunSymmetricSite(bool with_landmarks) {
  const sim::Site site = SymmetricSite(with_landmarks);
  sim::SimulationOptions sim_options;
  sim_options.duration_b_s = 22.0;
  sim_options.lidar.max_range_m = kLidarRangeM;
  sim_options.lidar.column_deg = 0.4;
  odometry::OdometryPipelineOptions options = PipelineOptionsFor(sim_options);
  SearchRun run;
  run.sink = std::make_unique<LocalizationSink>(options);
  run.sink->pipeline.SetPriorMap(PriorMap(site, with_landmarks));
  run.sink->pipeline.SetInitialGuess(std::nullopt);
  sim::SessionSimulator(sim_options, site, sim::SessionId::kB).Run(run.sink.get());
  run.sink->Finish();
  return run;
}

std::string EventList(const OdometryPipeline& pipeline) {
  std::string all;
  for (const LocalizationEvent& e : pipeline.events()) {
    all += "\n  " + localization::ToString(e.kind) + ": " + e.message;
  }
  return all;
}

TEST(SimGlobalSearch, AnAmbiguousStartIsResolvedByDrivingOut) {
  const SearchRun run = RunSymmetricSite(/*with_landmarks=*/true);
  const OdometryPipeline& pipeline = run.sink->pipeline;
  const std::string events = EventList(pipeline);
  ASSERT_NE(pipeline.status(), OdometryPipeline::Status::kFailed) << pipeline.message() << events;
  ASSERT_GE(pipeline.events().size(), 2u) << events;
  // The static view: both bays fit, nothing is picked.
  const LocalizationEvent& first = pipeline.events().front();
  EXPECT_EQ(first.kind, LocalizationEvent::Kind::kSearching) << events;
  EXPECT_NE(first.message.find("ambiguous"), std::string::npos) << events;
  // Later, once the building is in view: accepted, at the true bay.
  const LocalizationEvent* start = nullptr;
  for (const LocalizationEvent& e : pipeline.events()) {
    if (e.kind == LocalizationEvent::Kind::kInitialized) start = &e;
  }
  ASSERT_NE(start, nullptr) << events;
  Eigen::Isometry3d truth;
  ASSERT_TRUE(evaluation::InterpolatePose(run.sink->truth, start->t_ns, &truth));
  const Eigen::Isometry3d error = truth.inverse() * start->T_map_imu;
  const Eigen::Vector3d dp = start->T_map_imu.translation() - truth.translation();
  std::printf(
      "accepted %.2f s into the run, %.3f m (%.3f, %.3f, %.3f) / %.3f deg from the "
      "truth%s\n",
      (start->t_ns - run.sink->truth.front().t_ns) * 1e-9, error.translation().norm(), dp.x(),
      dp.y(), dp.z(), Eigen::AngleAxisd(error.linear()).angle() * 180.0 / M_PI, events.c_str());
  EXPECT_LT(error.translation().norm(), 0.1) << events;
  EXPECT_LT(Eigen::AngleAxisd(error.linear()).angle(), 1.0 * M_PI / 180.0) << events;
  // No pose before the start was accepted; the poses after it follow the truth.
  ASSERT_FALSE(run.sink->results().empty());
  EXPECT_GE(run.sink->results().front().t_ns, start->t_ns);
  double worst_m = 0.0;
  for (const odometry::ScanResult& r : run.sink->results()) {
    Eigen::Isometry3d T_true;
    if (!evaluation::InterpolatePose(run.sink->truth, r.t_ns, &T_true)) continue;
    worst_m = std::max(worst_m, (Eigen::Isometry3d(r.state.T_map_imu().Matrix()).translation() -
                                 T_true.translation())
                                    .norm());
  }
  std::printf("tracking after the start: worst %.3f m\n", worst_m);
  EXPECT_LT(worst_m, 0.1);
}

TEST(SimGlobalSearch, ATrulySymmetricDriveStaysAmbiguousAndReportsNoPose) {
  const SearchRun run = RunSymmetricSite(/*with_landmarks=*/false);
  const OdometryPipeline& pipeline = run.sink->pipeline;
  const std::string events = EventList(pipeline);
  EXPECT_EQ(pipeline.status(), OdometryPipeline::Status::kFailed) << events;
  EXPECT_NE(pipeline.message().find("searching"), std::string::npos) << pipeline.message();
  EXPECT_TRUE(run.sink->results().empty()) << "a pose was reported on a symmetric site" << events;
  int attempts = 0;
  for (const LocalizationEvent& e : pipeline.events()) {
    EXPECT_NE(e.kind, LocalizationEvent::Kind::kInitialized) << events;
    if (e.kind == LocalizationEvent::Kind::kSearching) ++attempts;
  }
  EXPECT_GE(attempts, 3) << "the drive must have been searched several times" << events;
  std::printf("%d searching events, none accepted%s\n", attempts, events.c_str());
}

}  // namespace
}  // namespace hylo::testing
