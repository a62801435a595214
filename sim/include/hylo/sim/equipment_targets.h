#pragma once
// Points of interest on the fixed site's equipment, where an inspection robot would point
// its cameras: what the inspection tests and benchmark plan for. Taken from the site's own
// primitives, so each lies exactly on (or around) the simulated equipment:
//   insulator_column  the fitting on top of the porcelain (a point);
//   transformer       the tank (a box) and each bushing's top (points);
//   pole              the top (a point);
//   control_building  the air-conditioning unit on its east wall (a box), to be seen from the
//                     east (azimuth 0 +- 60 deg);
//   container, shed, cable_drum, parked_vehicle   the whole object (a box).
// Ids are "<kind>_<n>[_<part>]", n counting objects of that kind from 1.

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "hylo/sim/site_layout.h"

namespace hylo::sim {

struct EquipmentTarget {
  std::string id;
  std::string kind;                                       ///< SiteObject::kind
  int object = -1;                                        ///< index into Site::objects
  Eigen::Vector3d centre_m = Eigen::Vector3d::Zero();     ///< site frame, m
  Eigen::Vector3d box_size_m = Eigen::Vector3d::Zero();   ///< axis-aligned box; zero: a point
  double view_azimuth_deg = std::nan("");                 ///< NaN: any direction
  double view_tolerance_deg = std::nan("");
};

/// The targets on the objects present in `session`.
std::vector<EquipmentTarget> EquipmentTargets(const Site& site, SessionId session);

}  // namespace hylo::sim
