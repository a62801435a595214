// Point cloud files and the ground filter: `hylo.read_cloud`, `hylo.write_cloud` and
// `hylo.ground_mask` / `hylo.extract_ground` (the Python side adds defaults and the bar).
#include <pybind11/stl.h>

#include <cmath>
#include <cstring>

#include "arrays.h"
#include "bindings.h"
#include "errors.h"
#include "hylo/config/run_config.h"
#include "hylo/io/cloud_io.h"
#include "hylo/terrain/ground_filter.h"
#include "progress_relay.h"

namespace hylo::python {
namespace {

py::array_t<double> ReadCloud(const std::string& path) {
  io::CloudFile cloud;
  {
    py::gil_scoped_release release;
    cloud = ReadingFiles({path}, [&] { return io::ReadCloud(path); });
  }
  return ArrayFromPoints(std::move(cloud.positions));
}

void WriteCloud(const std::string& path, const py::handle& points, const py::handle& intensity) {
  io::CloudFile cloud;
  cloud.positions = PointsFromArray(points, "points");
  if (!intensity.is_none()) {
    const auto values = py::array_t<float, py::array::forcecast>::ensure(intensity);
    if (!values || values.ndim() != 1 ||
        values.shape(0) != static_cast<py::ssize_t>(cloud.positions.size())) {
      PyErr_Clear();
      throw std::invalid_argument("intensity: expected one value per point");
    }
    const auto v = values.unchecked<1>();
    for (py::ssize_t i = 0; i < v.shape(0); ++i) cloud.intensity.push_back(v(i));
  }
  py::gil_scoped_release release;
  ReadingFiles({}, [&] { io::WriteCloud(path, cloud); });
}

// `hylo ground`'s options: the library's defaults (the command's) with `method`, then the
// keys of a `ground:` section given as YAML.
terrain::GroundFilterOptions GroundOptions(const std::string& method,
                                           const std::string& options_yaml,
                                           const std::string& source) {
  terrain::GroundFilterOptions options;
  if (!terrain::ParseGroundMethod(method, &options.method)) {
    throw std::invalid_argument("method: '" + method + "' is not one of smrf, csf");
  }
  if (!options_yaml.empty()) {
    options = config::ParseGroundOptions(options_yaml, source, options);
  }
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  return options;
}

py::array LabelsAsMask(const std::vector<terrain::GroundLabel>& labels) {
  py::array_t<bool> mask(static_cast<py::ssize_t>(labels.size()));
  bool* out = mask.mutable_data();
  for (std::size_t i = 0; i < labels.size(); ++i) {
    out[i] = labels[i] == terrain::GroundLabel::kGround;
  }
  return mask;
}

py::dict ExtractGround(const py::handle& points, const std::string& method,
                       const std::string& options_yaml, const std::string& source,
                       py::object progress) {
  const terrain::GroundFilterOptions options = GroundOptions(method, options_yaml, source);
  const std::vector<Eigen::Vector3d> points_world = PointsFromArray(points, "points");
  ProgressRelay relay(std::move(progress));
  terrain::GroundFilterResult result;
  {
    py::gil_scoped_release release;
    result = terrain::ExtractGround(points_world, options, [&relay](int step, int total) {
      relay(static_cast<std::size_t>(step), static_cast<std::size_t>(total), step == total);
    });
  }
  if (!result.ok) throw std::invalid_argument("points: " + result.message);
  py::dict out;
  out["mask"] = LabelsAsMask(result.labels);
  out["height_above_ground_m"] = ArrayFromVector(std::move(result.height_above_ground_m));
  out["method"] = terrain::ToString(result.method);
  out["message"] = result.message;
  out["num_ground"] = result.num_ground;
  out["num_objects"] = result.num_objects;
  out["num_invalid"] = result.num_invalid;
  out["origin_world"] = std::vector<double>(result.origin_world.data(),
                                            result.origin_world.data() + 3);
  return out;
}

}  // namespace

void BindClouds(py::module_& m) {
  m.def("read_cloud", &ReadCloud, py::arg("path"),
        "Reads a cloud file (PCD, PLY, KITTI .bin, LAS) as an (N, 3) float64 array in the file's "
        "frame; non-finite points are dropped as `hylo` drops them.");
  m.def("write_cloud", &WriteCloud, py::arg("path"), py::arg("points"),
        py::arg("intensity") = py::none(),
        "Writes an (N, 3) array as PCD/PLY/KITTI .bin/LAS (by extension), whole or not at all.");
  m.def("extract_ground", &ExtractGround, py::arg("points"), py::arg("method"),
        py::arg("options_yaml"), py::arg("source"), py::arg("progress"));
}

}  // namespace hylo::python
