// Fence, bay equipment and vegetation of a scenario's site.
#include "scenario_objects.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace hylo::sim::scenario_site {
namespace {

namespace st = structures;
constexpr double kBayClearanceM = 2.5;  // equipment keeps this far from lane centre lines, m
constexpr double kSpurClearM = 30.0;    // nothing grows this close to an empty spur, m

Eigen::Vector3d At(const V2& xy, double z) { return {xy.x(), xy.y(), z}; }

}  // namespace

double Objects::Ground(const V2& xy, double radius) const {
  double z = site_->terrain->BaseHeight(xy.x(), xy.y());
  for (int k = 0; k < 8; ++k) {
    const V2 p = xy + radius * V2(std::cos(k * M_PI / 4), std::sin(k * M_PI / 4));
    z = std::min(z, site_->terrain->BaseHeight(p.x(), p.y()));
  }
  return z - 0.05;  // a little below, so nothing floats
}

st::Parts* Objects::Add(const std::string& kind, bool in_a, bool in_b) {
  site_->objects.push_back(SiteObject{kind, in_a, in_b, {}});
  return &site_->objects.back().parts;
}

Eigen::Vector3d Objects::RandomUnit() {
  Eigen::Vector3d v(rng_->Gaussian(), rng_->Gaussian(), rng_->Gaussian());
  return v.norm() > 1e-9 ? v.normalized() : Eigen::Vector3d::UnitZ();
}

Eigen::Matrix3d Objects::RandomRotation() {
  Eigen::Quaterniond q(rng_->Gaussian(), rng_->Gaussian(), rng_->Gaussian(), rng_->Gaussian());
  return q.normalized().toRotationMatrix();
}

void Objects::Fence(const V2& a, const V2& b) {
  const auto ground = [this](double x, double y) { return site_->terrain->BaseHeight(x, y); };
  st::AddFence(a, b, 3.0, ground, Add("fence"));
}

void Objects::Gantry(const V2& center, const V2& axis, double span_m) {
  st::Parts* parts = Add("gantry");
  const V2 a = center - 0.5 * span_m * axis, b = center + 0.5 * span_m * axis;
  const double top = std::min(Ground(a, 0.6), Ground(b, 0.6)) + rng_->Uniform(8.0, 12.0);
  st::AddLatticeTower(a, Ground(a, 0.6), top - Ground(a, 0.6), 0.8, parts);
  st::AddLatticeTower(b, Ground(b, 0.6), top - Ground(b, 0.6), 0.8, parts);
  st::AddLatticeGirder(At(a + 0.4 * axis, top - 0.4), At(b - 0.4 * axis, top - 0.4), 0.8, parts);
}

void Objects::Bay(const Box2& bay) {
  const V2 size = bay.max - bay.min, center = 0.5 * (bay.min + bay.max);
  const bool along_x = size.x() >= size.y();
  const V2 axis = along_x ? V2::UnitX() : V2::UnitY();
  const double length = along_x ? size.x() : size.y(), width = along_x ? size.y() : size.x();
  const double yaw = along_x ? 0.0 : 0.5 * M_PI;
  const int kind = std::min(5, static_cast<int>(rng_->Uniform(0.0, 6.0)));
  if (kind == 0) {
    Gantry(center, axis, length - 2.0);
  } else if (kind == 1 && length >= 7.0 && width >= 5.0) {
    st::AddTransformer(center, Ground(center, 3.0), yaw, Add("transformer"));
  } else if (kind <= 2) {  // a row of insulator columns under a busbar
    const int count = std::clamp(static_cast<int>(length / 3.0), 2, 6);
    const double step = (length - 2.0) / (count - 1);
    // By index: the columns' Add calls grow the object list and move the busbar's parts.
    const std::size_t bus = site_->objects.size();
    Add("busbar");
    for (int k = 0; k < count; ++k) {
      const V2 xy = center + (k * step - 0.5 * (length - 2.0)) * axis;
      st::AddInsulatorColumn(xy, Ground(xy, 0.2), Add("insulator_column"));
    }
    const V2 first = center - 0.5 * (length - 2.0) * axis,
             last = center + 0.5 * (length - 2.0) * axis;
    const double z = std::max(Ground(first, 0.2), Ground(last, 0.2)) + 4.4;
    site_->objects[bus].parts.push_back(MakeCylinder(At(first, z), At(last, z), 0.05, st::kSteel));
  } else if (kind == 3) {
    const Eigen::Vector3d box(std::min(size.x(), rng_->Uniform(5.0, 12.0)),
                              std::min(size.y(), rng_->Uniform(4.0, 10.0)),
                              rng_->Uniform(3.0, 5.0));
    const double z = Ground(center, 0.5 * box.head<2>().norm());
    st::Parts* building = Add("building");
    building->push_back(MakeBox(At(center, z + 0.5 * box.z()), box, 0.0, st::kConcrete));
    building->push_back(MakeBox(At(center, z + box.z() + 0.1),
                                box + Eigen::Vector3d(0.6, 0.6, 0.2 - box.z()), 0.0,
                                st::kConcrete));
  } else if (kind == 4) {
    const V2 box = center - 0.25 * length * axis, van = center + 0.25 * length * axis;
    Add("container")
        ->push_back(
            MakeBox(At(box, Ground(box, 3.0) + 1.295), {6.06, 2.44, 2.59}, yaw, st::kContainer));
    if (length >= 12.0) st::AddVehicle(van, Ground(van, 2.0), yaw, Add("parked_vehicle"));
  } else {
    const int poles = 2 + static_cast<int>(rng_->Uniform(0.0, 3.0));
    for (int k = 0; k < poles; ++k) {
      const V2 p(rng_->Uniform(bay.min.x(), bay.max.x()), rng_->Uniform(bay.min.y(), bay.max.y()));
      const double g = Ground(p, 0.2);
      Add("pole")->push_back(MakeCylinder(At(p, g), At(p, g + rng_->Uniform(6.0, 10.0)),
                                          rng_->Uniform(0.1, 0.15), st::kSteel));
    }
    st::AddCableDrum(center, Ground(center, 1.0), yaw, Add("cable_drum"));
  }
}

void Objects::Equipment(const SiteRecipe& recipe, const LaneGrid& lanes) {
  for (int i = 0; i + 1 < lanes.nx(); ++i) {
    for (int j = 0; j + 1 < lanes.ny(); ++j) {
      const bool filled = rng_->Uniform() < recipe.structure_density;
      if (!filled) continue;
      const Box2 bay{lanes.Node(i, j) + V2::Constant(kBayClearanceM),
                     lanes.Node(i + 1, j + 1) - V2::Constant(kBayClearanceM)};
      occupied_.push_back(bay);
      Bay(bay);
    }
  }
}

void Objects::Bush(const V2& xy, bool in_a, bool in_b) {
  st::Parts* parts = Add("bush", in_a, in_b);
  const double radius = rng_->Uniform(0.4, 1.3), height = rng_->Uniform(0.5, 1.8);
  const double base = Ground(xy, radius);
  const float reflectivity = static_cast<float>(rng_->Uniform(0.2, 0.45));
  const int count = 6 + static_cast<int>(rng_->Uniform(0.0, 9.0));
  for (int k = 0; k < count; ++k) {
    const double r = radius * std::sqrt(rng_->Uniform()), a = rng_->Uniform(0.0, 2.0 * M_PI);
    const Eigen::Vector3d p =
        At(xy + r * V2(std::cos(a), std::sin(a)), base + 0.05 + rng_->Uniform(0.05, height));
    if (rng_->Uniform() < 0.6) {  // a clump of leaves
      Primitive leaves =
          MakeBox(p, Eigen::Vector3d::Constant(rng_->Uniform(0.1, 0.4)), 0.0, reflectivity);
      leaves.R_map_box = RandomRotation();
      parts->push_back(leaves);
    } else {  // a twig
      const Eigen::Vector3d dir = RandomUnit();
      parts->push_back(MakeCylinder(p, p + rng_->Uniform(0.3, 1.0) * dir, rng_->Uniform(0.01, 0.03),
                                    reflectivity));
    }
  }
}

void Objects::Tree(const V2& xy, bool in_a, bool in_b) {
  st::Parts* parts = Add("tree", in_a, in_b);
  const double trunk_r = rng_->Uniform(0.08, 0.25), trunk_h = rng_->Uniform(1.5, 4.0);
  const double crown_r = rng_->Uniform(1.0, 2.5);
  const double base = Ground(xy, trunk_r);
  const float reflectivity = static_cast<float>(rng_->Uniform(0.2, 0.45));
  const Eigen::Vector3d top = At(xy, base + trunk_h);
  parts->push_back(MakeCylinder(At(xy, base), top, trunk_r, 0.3f));
  const Eigen::Vector3d crown = top + Eigen::Vector3d(0.0, 0.0, 0.5 * crown_r);
  const int count = 10 + static_cast<int>(rng_->Uniform(0.0, 15.0));
  for (int k = 0; k < count; ++k) {
    const Eigen::Vector3d p = crown + crown_r * std::cbrt(rng_->Uniform()) * RandomUnit();
    if (k % 4 == 0) {  // a branch from the trunk's top
      parts->push_back(MakeCylinder(top, p, rng_->Uniform(0.03, 0.06), 0.3f));
    } else {
      Primitive leaves =
          MakeBox(p, Eigen::Vector3d::Constant(rng_->Uniform(0.2, 0.6)), 0.0, reflectivity);
      leaves.R_map_box = RandomRotation();
      parts->push_back(leaves);
    }
  }
}

bool Objects::ClearOfEverything(const V2& p, const LaneGrid& lanes, const Drives& drives,
                                bool spur) const {
  for (const double x : lanes.xs) {
    if (DistanceToSegment(p, V2(x, lanes.ys.front()), V2(x, lanes.ys.back())) < 3.0) return false;
  }
  for (const double y : lanes.ys) {
    if (DistanceToSegment(p, V2(lanes.xs.front(), y), V2(lanes.xs.back(), y)) < 3.0) return false;
  }
  for (std::size_t k = 0; k < drives.roads.size(); ++k) {
    const double clear = spur && k > 0 ? kSpurClearM : 3.5;  // road 0 is the approach
    if (DistanceToSegment(p, drives.roads[k].first, drives.roads[k].second) < clear) return false;
  }
  for (const Box2& box : occupied_) {
    if ((p.array() > box.min.array() - 1.5).all() && (p.array() < box.max.array() + 1.5).all()) {
      return false;
    }
  }
  const V2 size = site_->site_max_m;
  const bool near_fence = (std::abs(p.x()) < 1.5 || std::abs(p.x() - size.x()) < 1.5) ||
                          (std::abs(p.y()) < 1.5 || std::abs(p.y() - size.y()) < 1.5);
  return !near_fence;
}

void Objects::Clutter(const SiteRecipe& recipe, const LaneGrid& lanes, const Drives& drives) {
  const V2 lo = V2::Constant(-20.0), hi = recipe.yard_size_m + V2::Constant(20.0);
  const double area = (hi - lo).prod();
  const int wanted = static_cast<int>(std::lround(recipe.clutter_per_100m2 * area / 100.0));
  const bool spur = recipe.featureless_m > 0.0;
  int placed = 0;
  for (int attempt = 0; attempt < 20 * wanted && placed < wanted; ++attempt) {
    const V2 p(rng_->Uniform(lo.x(), hi.x()), rng_->Uniform(lo.y(), hi.y()));
    const double kind = rng_->Uniform(), change = rng_->Uniform();
    if (!ClearOfEverything(p, lanes, drives, spur)) continue;
    const bool in_a = change >= 0.5 * recipe.changed_fraction;
    const bool in_b = change < 0.5 * recipe.changed_fraction || change >= recipe.changed_fraction;
    if (kind < 0.2) {
      Tree(p, in_a, in_b);
    } else {
      Bush(p, in_a, in_b);
    }
    ++placed;
  }
}

}  // namespace hylo::sim::scenario_site
