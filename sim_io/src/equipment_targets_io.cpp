#include "hylo/sim_io/equipment_targets_io.h"

#include <cmath>

namespace hylo::sim {

std::vector<inspection::Target> EquipmentAsTargets(const std::vector<EquipmentTarget>& equipment,
                                                   const Eigen::Isometry3d& T_f_site) {
  const Eigen::Matrix3d R = T_f_site.linear();
  // The yaw of the site's x axis seen in frame f: azimuths are measured from +x.
  const double yaw_deg = std::atan2(R(1, 0), R(0, 0)) * 180.0 / M_PI;
  std::vector<inspection::Target> out;
  out.reserve(equipment.size());
  for (const EquipmentTarget& e : equipment) {
    inspection::Target t;
    t.id = e.id;
    t.position = T_f_site * e.centre_m;
    // Half-extents of the rotated box along f's axes: |R| times the site half-extents.
    t.box_size_m = R.cwiseAbs() * e.box_size_m;
    if (std::isfinite(e.view_azimuth_deg)) {
      t.view_azimuth_deg = std::remainder(e.view_azimuth_deg + yaw_deg, 360.0);
      if (t.view_azimuth_deg < 0.0) t.view_azimuth_deg += 360.0;
      t.view_tolerance_deg = e.view_tolerance_deg;
    }
    out.push_back(t);
  }
  return out;
}

}  // namespace hylo::sim
