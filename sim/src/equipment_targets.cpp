#include "hylo/sim/equipment_targets.h"

#include <map>

namespace hylo::sim {
namespace {

Aabb BoundsOfAll(const std::vector<Primitive>& parts) {
  Aabb box;
  for (const Primitive& p : parts) box.Extend(BoundsOf(p));
  return box;
}

EquipmentTarget Box(const Aabb& box) {
  EquipmentTarget t;
  t.centre_m = 0.5 * (box.min + box.max);
  t.box_size_m = box.max - box.min;
  return t;
}

EquipmentTarget Point(const Eigen::Vector3d& p) {
  EquipmentTarget t;
  t.centre_m = p;
  return t;
}

// The targets of one object (see the header for what each kind gets).
std::vector<EquipmentTarget> TargetsOf(const SiteObject& object) {
  const std::vector<Primitive>& parts = object.parts;
  std::vector<EquipmentTarget> out;
  if (object.kind == "insulator_column") {
    out.push_back(Point(parts.back().center_map));
    out.back().id = "top";
  } else if (object.kind == "transformer") {
    out.push_back(Box(BoundsOf(parts[1])));  // the tank, after the plinth
    out.back().id = "tank";
    int bushing = 0;
    for (const Primitive& p : parts) {
      if (p.shape != Primitive::Shape::kCylinder || p.radius_m > 0.2) continue;  // not the conservator
      out.push_back(Point(p.end_map));
      out.back().id = "bushing_" + std::to_string(++bushing);
    }
  } else if (object.kind == "pole") {
    out.push_back(Point(parts.front().end_map));
    out.back().id = "top";
  } else if (object.kind == "control_building" && parts.size() > 2) {
    out.push_back(Box(BoundsOf(parts[2])));
    out.back().id = "ac_unit";
    out.back().view_azimuth_deg = 0.0;
    out.back().view_tolerance_deg = 60.0;
  } else if (object.kind == "container" || object.kind == "shed" || object.kind == "cable_drum" ||
             object.kind == "parked_vehicle") {
    out.push_back(Box(BoundsOfAll(parts)));
  }
  return out;
}

}  // namespace

std::vector<EquipmentTarget> EquipmentTargets(const Site& site, SessionId session) {
  std::vector<EquipmentTarget> out;
  std::map<std::string, int> count;
  for (std::size_t i = 0; i < site.objects.size(); ++i) {
    const SiteObject& object = site.objects[i];
    if (session == SessionId::kA ? !object.in_a : !object.in_b) continue;
    const std::string name = object.kind + "_" + std::to_string(++count[object.kind]);
    for (EquipmentTarget t : TargetsOf(object)) {
      t.id = t.id.empty() ? name : name + "_" + t.id;
      t.kind = object.kind;
      t.object = static_cast<int>(i);
      out.push_back(t);
    }
  }
  return out;
}

}  // namespace hylo::sim
