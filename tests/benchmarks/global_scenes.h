#pragma once
// Scenes of the global localization benchmark: start poses spread over the mapped part of a
// simulated site, and the first seconds a vehicle standing (then driving) there records.

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/sim/simulator.h"

namespace hylo::benchmarks {

/// Where a vehicle starts: position on the ground and heading, site frame.
struct StartPose {
  Eigen::Vector2d xy_m = Eigen::Vector2d::Zero();
  double heading_rad = 0.0;
};

/// Where start poses may lie: inside `min_m`..`max_m`, outside the `exclude_*` rectangle
/// (when it is not empty), with a map covering the ground there.
struct StartRegion {
  Eigen::Vector2d min_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d max_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d exclude_min_m = Eigen::Vector2d::Zero();
  Eigen::Vector2d exclude_max_m = Eigen::Vector2d::Zero();
  double spacing_m = 6.0;  ///< one candidate per square of this side, jittered within it
};

/// Start poses on a jittered grid over `region`, uniform random headings, each kept when a
/// vehicle fits there (no structure within 1 m of its footprint up to 2 m high), the terrain
/// is no steeper than a vehicle drives, and `map_site` (the prior map in the site frame; empty:
/// no check) holds ground points within 2 m. At most `count`, in random order (fixed seed).
std::vector<StartPose> SampleStartPoses(const sim::World& world, const PointCloud& map_site,
                                        const StartRegion& region, int count, uint64_t seed);

/// The first `duration_s` seconds of a session of `site` in `session`'s world that starts at
/// rest at `start` and then drives `drive_m` straight ahead (the vehicle stands still for
/// options.trajectory.standstill_s first).
sim::SessionRecording SimulateStart(const sim::SimulationOptions& options, const sim::Site& site,
                                    sim::SessionId session, const StartPose& start,
                                    double duration_s, double drive_m);

/// True when the straight drive of `length_m` from `start` keeps 1 m from every structure.
bool DriveIsClear(const sim::World& world, const StartPose& start, double length_m);

}  // namespace hylo::benchmarks
