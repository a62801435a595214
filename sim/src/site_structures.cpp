// Substation structures assembled from boxes and cylinders.
#include "site_structures.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace hylo::sim::structures {
namespace {

Eigen::Vector3d At(const Eigen::Vector2d& xy, double z) { return {xy.x(), xy.y(), z}; }

void Beam(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double radius, Parts* out) {
  out->push_back(MakeCylinder(a, b, radius, kSteel));
}

}  // namespace

void AddLatticeTower(const Eigen::Vector2d& center, double base_z_m, double height_m,
                     double width_m, Parts* out) {
  const double h = 0.5 * width_m;
  const Eigen::Vector2d corners[4] = {
      center + Eigen::Vector2d(-h, -h), center + Eigen::Vector2d(h, -h),
      center + Eigen::Vector2d(h, h), center + Eigen::Vector2d(-h, h)};
  for (const auto& c : corners) Beam(At(c, base_z_m), At(c, base_z_m + height_m), 0.06, out);
  const int panels = std::max(1, static_cast<int>(std::round(height_m / 1.5)));
  const double panel_h = height_m / panels;
  for (int p = 0; p < panels; ++p) {
    const double z0 = base_z_m + p * panel_h, z1 = z0 + panel_h;
    for (int f = 0; f < 4; ++f) {
      const Eigen::Vector2d& a = corners[f];
      const Eigen::Vector2d& b = corners[(f + 1) % 4];
      Beam(At(a, z1), At(b, z1), 0.035, out);  // ring at the panel top
      // Alternating diagonals give the familiar zig-zag of lattice towers.
      if (p % 2 == 0)
        Beam(At(a, z0), At(b, z1), 0.03, out);
      else
        Beam(At(b, z0), At(a, z1), 0.03, out);
    }
  }
}

void AddLatticeGirder(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double width_m,
                      Parts* out) {
  const Eigen::Vector3d along = (to - from).normalized();
  const Eigen::Vector3d side = along.cross(Eigen::Vector3d::UnitZ()).normalized() * 0.5 * width_m;
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ() * 0.5 * width_m;
  const Eigen::Vector3d offsets[4] = {-side - up, side - up, side + up, -side + up};
  for (const auto& o : offsets) Beam(from + o, to + o, 0.05, out);
  const int panels = std::max(1, static_cast<int>(std::round((to - from).norm() / 1.5)));
  for (int p = 0; p < panels; ++p) {
    const Eigen::Vector3d a = from + (to - from) * (double(p) / panels);
    const Eigen::Vector3d b = from + (to - from) * (double(p + 1) / panels);
    for (const double s : {-1.0, 1.0}) {  // the two vertical faces
      const Eigen::Vector3d low = s * side - up, high = s * side + up;
      Beam(p % 2 == 0 ? a + low : a + high, p % 2 == 0 ? b + high : b + low, 0.03, out);
    }
    Beam(b - side - up, b + side - up, 0.03, out);  // bottom cross member
  }
}

void AddSaggingCable(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double sag_m,
                     double radius_m, int segments, Parts* out) {
  const auto point = [&](double s) {  // parabola through both ends, lowest by sag at s=0.5
    Eigen::Vector3d p = from + s * (to - from);
    p.z() -= 4.0 * sag_m * s * (1.0 - s);
    return p;
  };
  for (int i = 0; i < segments; ++i) {
    out->push_back(MakeCylinder(point(double(i) / segments), point(double(i + 1) / segments),
                                radius_m, kCable));
  }
}

void AddInsulatorColumn(const Eigen::Vector2d& xy, double base_z_m, Parts* out) {
  out->push_back(MakeCylinder(At(xy, base_z_m), At(xy, base_z_m + 2.5), 0.15, kSteel));
  const double z0 = base_z_m + 2.5, z1 = z0 + 1.5;
  out->push_back(MakeCylinder(At(xy, z0), At(xy, z1), 0.07, kPorcelain));
  for (double z = z0 + 0.1; z < z1 - 0.05; z += 0.12) {
    out->push_back(MakeCylinder(At(xy, z), At(xy, z + 0.025), 0.14, kPorcelain));
  }
  out->push_back(MakeBox(At(xy, z1 + 0.15), Eigen::Vector3d(0.6, 0.3, 0.3), 0.0, kSteel));
}

void AddTransformer(const Eigen::Vector2d& xy, double base_z_m, double yaw_rad, Parts* out) {
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(yaw_rad).toRotationMatrix();
  const auto local = [&](double x, double y, double z) {
    return At(xy + R * Eigen::Vector2d(x, y), z);
  };
  out->push_back(MakeBox(local(0, 0, base_z_m + 0.15), {6.0, 4.2, 0.3}, yaw_rad, kConcrete));
  const double tank_z0 = base_z_m + 0.3, tank_h = 3.0;
  out->push_back(MakeBox(local(0, 0, tank_z0 + 0.5 * tank_h), {5.0, 3.0, tank_h}, yaw_rad, kPaint));
  for (const double side : {-1.0, 1.0}) {  // radiator fins, 0.3 m pitch along the tank
    for (double x = -2.2; x <= 2.2 + 1e-9; x += 0.3) {
      out->push_back(
          MakeBox(local(x, side * 1.7, tank_z0 + 1.5), {0.04, 0.4, 2.4}, yaw_rad, kPaint));
    }
  }
  const double top = tank_z0 + tank_h;
  for (const double x : {-1.5, 0.0, 1.5}) {
    out->push_back(MakeCylinder(local(x, -0.6, top), local(x, -0.6, top + 1.4), 0.12, kPorcelain));
  }
  out->push_back(
      MakeCylinder(local(-1.6, 0.9, top + 0.9), local(1.0, 0.9, top + 0.9), 0.4, kPaint));
  out->push_back(MakeBox(local(-0.3, 0.9, top + 0.25), {0.2, 0.2, 0.5}, yaw_rad, kSteel));
}

void AddFence(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double post_spacing_m,
              const std::function<double(double, double)>& ground_z_m, Parts* out) {
  const double length = (b - a).norm();
  const int spans = std::max(1, static_cast<int>(std::ceil(length / post_spacing_m)));
  const Eigen::Vector2d dir = (b - a) / length;
  const double yaw = std::atan2(dir.y(), dir.x());
  for (int i = 0; i <= spans; ++i) {
    const Eigen::Vector2d p = a + (b - a) * (double(i) / spans);
    const double z = ground_z_m(p.x(), p.y());
    out->push_back(MakeCylinder(At(p, z - 0.3), At(p, z + 2.2), 0.04, kSteel));
    if (i == spans) break;
    const Eigen::Vector2d q = a + (b - a) * (double(i + 1) / spans);
    const Eigen::Vector2d mid = 0.5 * (p + q);
    const double z_mid = std::min(z, ground_z_m(q.x(), q.y()));
    const double span_len = (q - p).norm() - 0.1;
    // Chain-link mesh: a thin dark panel (returns are sparse and weak on real mesh).
    out->push_back(MakeBox(At(mid, z_mid + 1.05), {span_len, 0.02, 2.0}, yaw, kFenceMesh));
  }
}

void AddVehicle(const Eigen::Vector2d& xy, double base_z_m, double yaw_rad, Parts* out) {
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(yaw_rad).toRotationMatrix();
  const auto local = [&](double x, double y, double z) {
    return At(xy + R * Eigen::Vector2d(x, y), z);
  };
  out->push_back(MakeBox(local(0, 0, base_z_m + 1.05), {4.6, 1.9, 1.3}, yaw_rad, kVehiclePaint));
  out->push_back(MakeBox(local(-0.6, 0, base_z_m + 2.1), {3.0, 1.8, 0.8}, yaw_rad, kVehiclePaint));
  for (const double x : {-1.5, 1.5}) {
    for (const double y : {-0.85, 0.85}) {
      out->push_back(MakeCylinder(local(x, y - 0.12, base_z_m + 0.36),
                                  local(x, y + 0.12, base_z_m + 0.36), 0.36, 0.1f));
    }
  }
}

void AddCableDrum(const Eigen::Vector2d& xy, double base_z_m, double yaw_rad, Parts* out) {
  const Eigen::Vector2d axis = Eigen::Rotation2Dd(yaw_rad) * Eigen::Vector2d(0.6, 0.0);
  out->push_back(
      MakeCylinder(At(xy - axis, base_z_m + 0.9), At(xy + axis, base_z_m + 0.9), 0.9, 0.45f));
}

}  // namespace hylo::sim::structures
