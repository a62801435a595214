#pragma once
// numpy arrays in and out. Inputs are read in place through their strides, float64 or float32
// (other numeric types are converted first: one copy, documented in docs/python.md); outputs
// take over the library's vector where its layout is numpy's, without a copy.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/io/trajectory_io.h"

namespace hylo::python {

namespace py = pybind11;

/// `object` as a numpy array of float64 or float32 (in place), or of another numeric type
/// converted to float64 (a copy). Throws std::invalid_argument naming `what` otherwise.
py::array FloatArray(const py::handle& object, const std::string& what);

/// Throws std::invalid_argument "`what`: expected shape (N, 3), got (a, b)" unless `array`
/// has `ndim` dimensions and, where `shape` is not -1, that extent.
void RequireShape(const py::array& array, std::initializer_list<py::ssize_t> shape,
                  const std::string& what);

/// Calls `f(i, x, y, z)` for every row of an (N, 3) float array, in place.
template <class F>
void ForEachRow3(const py::array& array, F&& f) {
  const auto rows = [&](auto typed) {
    const auto view = typed.template unchecked<2>();
    for (py::ssize_t i = 0; i < view.shape(0); ++i) f(i, view(i, 0), view(i, 1), view(i, 2));
  };
  if (py::isinstance<py::array_t<float>>(array)) {
    rows(py::reinterpret_borrow<py::array_t<float>>(array));
  } else {
    rows(py::reinterpret_borrow<py::array_t<double>>(array));
  }
}

/// The (N, 3) points of `object` (any numeric array or nested sequence).
std::vector<Eigen::Vector3d> PointsFromArray(const py::handle& object, const std::string& what);

/// An (N, 3) float64 array owning `points` (moved in, no copy).
py::array_t<double> ArrayFromPoints(std::vector<Eigen::Vector3d>&& points);
/// Map-frame points (float, near zero) as (N, 3) float64 in the world frame.
py::array_t<double> WorldArray(const PointCloud& points_map, const Eigen::Vector3d& origin_world);
/// A 1-D array owning `values` (moved in, no copy).
template <class T>
py::array_t<T> ArrayFromVector(std::vector<T>&& values) {
  auto* owned = new std::vector<T>(std::move(values));
  py::capsule free(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>({static_cast<py::ssize_t>(owned->size())}, owned->data(), free);
}

/// Seconds to ns, rounded; throws std::invalid_argument naming `what` when not finite or
/// beyond int64.
int64_t SecondsToNs(double t_s, const std::string& what);

/// Poses as an (N, 8) array of rows `t_s x y z qx qy qz qw` (TUM's columns).
py::array_t<double> TrajectoryArray(const std::vector<io::StampedPose>& poses);
/// Their stamps, ns (exact, where t_s is rounded to a double).
py::array_t<int64_t> StampsArray(const std::vector<io::StampedPose>& poses);
/// Poses from an (N, 8) array `t_s x y z qx qy qz qw`; `t_ns` (N stamps, ns) when given
/// replaces the first column. Throws std::invalid_argument naming `what`: wrong shape,
/// non-finite values, a quaternion far from unit norm.
std::vector<io::StampedPose> PosesFromArray(const py::handle& object, const py::handle& t_ns,
                                            const std::string& what);

/// A 4×4 array (row-major) of `T`.
py::array_t<double> MatrixArray(const Eigen::Isometry3d& T);

}  // namespace hylo::python
