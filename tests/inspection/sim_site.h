#pragma once
// The simulated substation as the inspection planner sees it, for the tests and the
// benchmark: session A's lidar returns at the TRUE poses (every n-th scan along its whole
// route) as the map, the returns that hit the ground and the rest as the traversability
// chain's ground and objects (the truth's labels, so a ground filter's errors stay out of the
// planner's figures), the equipment targets of sim/equipment_targets.h, and the checks of a
// plan against the simulator's true geometry (ray casting and distances to the true surfaces,
// never the map).

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "hylo/inspection/planner.h"
#include "hylo/sim/equipment_targets.h"
#include "hylo/sim/simulator.h"
#include "hylo/sim/surface_distance.h"
#include "hylo/terrain/traversability.h"

namespace hylo::inspection_sim {

struct SimSiteOptions {
  uint64_t seed = 1;                   ///< the site's seed
  double duration_s = 180.0;           ///< session A, s (180: its whole route)
  int scan_stride = 10;                ///< every n-th scan of session A goes into the map
  double column_deg = 0.5;             ///< lidar column spacing, deg
  double terrain_resolution_m = 0.4;   ///< the simulator's ground grid, m
  double map_voxel_m = 0.05;           ///< one return per voxel in the map, m
  terrain::TraversabilityOptions traversability;  ///< `hylo traversability` defaults
};

struct SimSite {
  sim::SimulationOptions sim;
  sim::Site site;
  std::unique_ptr<sim::World> world;   ///< session A's world: the truth the map was made of
  std::unique_ptr<sim::SurfaceDistanceField> field;  ///< distances to its surfaces
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< the grid's origin_world (site frame)
  PointCloud map_local;                ///< the map, local frame (site frame - origin)
  terrain::TraversabilityMap costmap;
  double seconds = 0.0;                ///< wall time to build all this, s
};

SimSite BuildSimSite(const SimSiteOptions& options);

/// The equipment targets in the grid's local frame.
std::vector<inspection::Target> LocalTargets(const std::vector<sim::EquipmentTarget>& equipment,
                                             const Eigen::Vector3d& origin);

/// The camera on `cell` as the robot would hold it: the cell centre, camera_height_m above
/// the true ground the vehicle rides on (Terrain::BaseHeight); local frame.
Eigen::Vector3d TrueCamera(const SimSite& s, std::size_t cell, double camera_height_m);

/// How many of the target's sight lines from `camera_local` are clear in the truth: nothing
/// of the true world within `margin_m` of the line (0: the line itself hits nothing) up to
/// where it enters the target's own region (visibility.h).
int ClearLinesInTruth(const SimSite& s, const inspection::TargetShape& shape,
                      const Eigen::Vector3d& camera_local, double margin_m);

/// What the first blocked sight line hits in the truth (for failure messages).
std::string DescribeFirstHit(const SimSite& s, const inspection::TargetShape& shape,
                             const Eigen::Vector3d& camera_local);

}  // namespace hylo::inspection_sim
