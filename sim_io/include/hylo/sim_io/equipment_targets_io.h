#pragma once
// The simulator's equipment (sim/equipment_targets.h) as the inspection planner's targets, in
// any frame placed by a rigid transform from the site frame: the tests' local grid frame (a
// translation) or a SLAM map's frame (`hylo demo`, through session A's alignment to the truth).
// A box stays axis-aligned in the new frame: it becomes the axis-aligned box around the
// rotated one (the same box under a translation or a quarter-turn about z, larger otherwise).

#include <Eigen/Geometry>
#include <vector>

#include "hylo/inspection/target.h"
#include "hylo/sim/equipment_targets.h"

namespace hylo::sim {

/// The targets in frame f, with T_f_site mapping site-frame points into it; view azimuths
/// turn with the transform's yaw.
std::vector<inspection::Target> EquipmentAsTargets(const std::vector<EquipmentTarget>& equipment,
                                                   const Eigen::Isometry3d& T_f_site);

}  // namespace hylo::sim
