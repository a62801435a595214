#pragma once
// Builders for the substation's structures, each a list of analytic primitives placed on
// the ground at `base_z_m` (the lowest ground point under the footprint, so nothing floats).
// Sizes follow typical 150 kV outdoor switchyards (gantries ~11 m, transformers ~5 x 3 m).

#include <Eigen/Core>
#include <functional>
#include <vector>

#include "hylo/sim/primitives.h"

namespace hylo::sim::structures {

using Parts = std::vector<Primitive>;

/// Reflectivities of the site's materials (diffuse, 0..1).
constexpr float kSteel = 0.35f, kPorcelain = 0.6f, kConcrete = 0.5f, kFenceMesh = 0.15f,
                kPaint = 0.3f, kVehiclePaint = 0.7f, kContainer = 0.4f, kCable = 0.25f;

/// A lattice tower of four legs with horizontal rings and alternating face diagonals.
void AddLatticeTower(const Eigen::Vector2d& center, double base_z_m, double height_m,
                     double width_m, Parts* out);
/// A lattice girder between two points (4 chords, braced on its vertical faces).
void AddLatticeGirder(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double width_m,
                      Parts* out);
/// A cable sagging between two points as a parabola of `sag_m`, in `segments` cylinders.
void AddSaggingCable(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double sag_m,
                     double radius_m, int segments, Parts* out);
/// A post insulator on a steel pedestal, with sheds (discs) every 12 cm.
void AddInsulatorColumn(const Eigen::Vector2d& xy, double base_z_m, Parts* out);
/// A power transformer: plinth, tank, cooling fins on both long sides, bushings, conservator.
void AddTransformer(const Eigen::Vector2d& xy, double base_z_m, double yaw_rad, Parts* out);
/// A fence run from a to b: posts every `post_spacing_m` and mesh panels between them.
/// `ground_z_m(x, y)` gives the ground under each post (panels follow the terrain).
void AddFence(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double post_spacing_m,
              const std::function<double(double, double)>& ground_z_m, Parts* out);
/// A parked van: body, cab and four wheels.
void AddVehicle(const Eigen::Vector2d& xy, double base_z_m, double yaw_rad, Parts* out);
/// A cable drum lying on its side (axis horizontal at `yaw_rad`).
void AddCableDrum(const Eigen::Vector2d& xy, double base_z_m, double yaw_rad, Parts* out);

}  // namespace hylo::sim::structures
