#include "arrays.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace hylo::python {
namespace {

std::string ShapeText(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < array.ndim(); ++d) {
    text += (d > 0 ? ", " : "") + std::to_string(array.shape(d));
  }
  return text + (array.ndim() == 1 ? ",)" : ")");
}

}  // namespace

py::array FloatArray(const py::handle& object, const std::string& what) {
  if (py::isinstance<py::array_t<double>>(object) || py::isinstance<py::array_t<float>>(object)) {
    return py::reinterpret_borrow<py::array>(object);
  }
  py::array converted = py::array_t<double, py::array::forcecast>::ensure(object);
  if (!converted) {
    PyErr_Clear();
    throw std::invalid_argument(what + ": expected a numeric array, got " +
                                std::string(py::str(py::type::of(object).attr("__name__"))));
  }
  return converted;
}

void RequireShape(const py::array& array, std::initializer_list<py::ssize_t> shape,
                  const std::string& what) {
  bool ok = array.ndim() == static_cast<py::ssize_t>(shape.size());
  py::ssize_t d = 0;
  std::string wanted = "(";
  for (const py::ssize_t extent : shape) {
    if (ok && extent >= 0 && array.shape(d) != extent) ok = false;
    wanted += (d > 0 ? ", " : "") + (extent < 0 ? std::string("N") : std::to_string(extent));
    ++d;
  }
  wanted += shape.size() == 1 ? ",)" : ")";
  if (!ok) {
    throw std::invalid_argument(what + ": expected shape " + wanted + ", got " +
                                ShapeText(array));
  }
}

std::vector<Eigen::Vector3d> PointsFromArray(const py::handle& object, const std::string& what) {
  const py::array array = FloatArray(object, what);
  RequireShape(array, {-1, 3}, what);
  std::vector<Eigen::Vector3d> points(static_cast<std::size_t>(array.shape(0)));
  ForEachRow3(array, [&](py::ssize_t i, double x, double y, double z) {
    points[static_cast<std::size_t>(i)] = Eigen::Vector3d(x, y, z);
  });
  return points;
}

py::array_t<double> ArrayFromPoints(std::vector<Eigen::Vector3d>&& points) {
  static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double), "Vector3d must be 3 packed doubles");
  auto* owned = new std::vector<Eigen::Vector3d>(std::move(points));
  py::capsule free(owned, [](void* p) { delete static_cast<std::vector<Eigen::Vector3d>*>(p); });
  return py::array_t<double>({static_cast<py::ssize_t>(owned->size()), py::ssize_t{3}},
                             owned->empty() ? nullptr : owned->front().data(), free);
}

py::array_t<double> WorldArray(const PointCloud& points_map, const Eigen::Vector3d& origin_world) {
  py::array_t<double> out({static_cast<py::ssize_t>(points_map.size()), py::ssize_t{3}});
  auto view = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < points_map.size(); ++i) {
    const Eigen::Vector3d p = points_map[i].cast<double>() + origin_world;
    for (int k = 0; k < 3; ++k) view(static_cast<py::ssize_t>(i), k) = p[k];
  }
  return out;
}

int64_t SecondsToNs(double t_s, const std::string& what) {
  // 9.2e9 s: the int64 ns range, with room for the rounding.
  if (!std::isfinite(t_s) || std::abs(t_s) > 9.2e9) {
    throw std::invalid_argument(what + " = " + std::to_string(t_s) +
                                ": must be a finite time in seconds");
  }
  return std::llround(t_s * 1e9);
}

py::array_t<double> TrajectoryArray(const std::vector<io::StampedPose>& poses) {
  py::array_t<double> out({static_cast<py::ssize_t>(poses.size()), py::ssize_t{8}});
  auto view = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const io::StampedPose& p = poses[i];
    const auto r = static_cast<py::ssize_t>(i);
    // Divided, not multiplied by 1e-9: the double nearest the TUM file's decimal stamp.
    view(r, 0) = static_cast<double>(p.t_ns) / 1e9;
    for (int k = 0; k < 3; ++k) view(r, 1 + k) = p.position[k];
    view(r, 4) = p.orientation.x();
    view(r, 5) = p.orientation.y();
    view(r, 6) = p.orientation.z();
    view(r, 7) = p.orientation.w();
  }
  return out;
}

py::array_t<int64_t> StampsArray(const std::vector<io::StampedPose>& poses) {
  std::vector<int64_t> t_ns;
  t_ns.reserve(poses.size());
  for (const io::StampedPose& p : poses) t_ns.push_back(p.t_ns);
  return ArrayFromVector(std::move(t_ns));
}

std::vector<io::StampedPose> PosesFromArray(const py::handle& object, const py::handle& t_ns,
                                            const std::string& what) {
  const py::array array = py::array_t<double, py::array::forcecast>::ensure(object);
  if (!array) {
    PyErr_Clear();
    throw std::invalid_argument(what + ": expected an (N, 8) array t_s x y z qx qy qz qw");
  }
  RequireShape(array, {-1, 8}, what + " (t_s x y z qx qy qz qw)");
  const auto view = py::reinterpret_borrow<py::array_t<double>>(array).unchecked<2>();
  std::vector<int64_t> stamps;
  if (!t_ns.is_none()) {
    const auto given = py::array_t<int64_t, py::array::forcecast>::ensure(t_ns);
    if (!given || given.ndim() != 1 || given.shape(0) != array.shape(0)) {
      PyErr_Clear();
      throw std::invalid_argument(what + ": t_ns must hold one stamp per pose");
    }
    const auto s = given.unchecked<1>();
    for (py::ssize_t i = 0; i < s.shape(0); ++i) stamps.push_back(s(i));
  }
  std::vector<io::StampedPose> poses(static_cast<std::size_t>(array.shape(0)));
  for (py::ssize_t i = 0; i < view.shape(0); ++i) {
    io::StampedPose& p = poses[static_cast<std::size_t>(i)];
    const std::string row = what + " row " + std::to_string(i);
    p.t_ns = stamps.empty() ? SecondsToNs(view(i, 0), row + " t_s") : stamps[i];
    p.position = Eigen::Vector3d(view(i, 1), view(i, 2), view(i, 3));
    const Eigen::Quaterniond q(view(i, 7), view(i, 4), view(i, 5), view(i, 6));
    if (!p.position.allFinite() || !q.coeffs().allFinite() || std::abs(q.norm() - 1.0) > 1e-3) {
      throw std::invalid_argument(row + ": position and quaternion must be finite, the "
                                  "quaternion of unit norm (within 1e-3)");
    }
    p.orientation = q;  // as given, so a trajectory written back keeps its digits
  }
  return poses;
}

py::array_t<double> MatrixArray(const Eigen::Isometry3d& T) {
  py::array_t<double> out({py::ssize_t{4}, py::ssize_t{4}});
  auto view = out.mutable_unchecked<2>();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) view(r, c) = T.matrix()(r, c);
  }
  return out;
}

}  // namespace hylo::python
