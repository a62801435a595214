// hylo.inspect: `hylo inspect` from Python, through run::InspectionRun (the code behind the
// command), so the plan is the command's; files are written only when an output folder is given
// (then exactly the command's files).
#include <pybind11/stl.h>

#include <cmath>
#include <optional>

#include "arrays.h"
#include "bindings.h"
#include "config_binding.h"
#include "errors.h"
#include "hylo/run/inspection_run.h"
#include "progress_relay.h"

namespace hylo::python {
namespace {

struct InspectArgs {
  std::string map, costmap, targets;
  ConfigHandle config;
  run::InspectionOverrides overrides;
  std::optional<std::vector<double>> start_xy;  // map frame, m; none: the map frame's origin
  std::string out_dir;
};

Eigen::Vector2d Start(const std::optional<std::vector<double>>& xy) {
  if (!xy) return Eigen::Vector2d::Zero();
  if (xy->size() != 2 || !std::isfinite((*xy)[0]) || !std::isfinite((*xy)[1]))
    throw std::invalid_argument("start: expected two finite numbers (x, y) in the map frame, m");
  return {(*xy)[0], (*xy)[1]};
}

// One dict per target, in the file's order, with plan.csv's fields (map frame).
py::list TargetDicts(const run::InspectionInputs& in, const run::InspectionRun& run) {
  py::list out;
  for (std::size_t i = 0; i < in.targets_local.size(); ++i) {
    const inspection::TargetPlan& t = run.plan.targets[i];
    const bool planned = t.status == inspection::TargetStatus::kPlanned;
    py::dict d;
    d["id"] = in.targets_local[i].id;
    d["status"] = inspection::TargetStatusName(t.status);
    d["reason"] = t.reason;
    d["visible_cells"] = t.visible_cells;
    const Eigen::Vector3d view_map = t.camera + in.origin_world();
    d["view"] = planned ? py::object(py::array_t<double>(3, view_map.data())) : py::none();
    d["order"] = t.order;
    d["path_length_m"] = planned ? py::object(py::float_(t.leg_length_m)) : py::none();
    d["along_route_m"] = planned ? py::object(py::float_(t.along_route_m)) : py::none();
    d["range_m"] = planned ? py::object(py::float_(t.range_m)) : py::none();
    d["view_angle_deg"] = planned ? py::object(py::float_(t.view_angle_deg)) : py::none();
    out.append(d);
  }
  return out;
}

// The route's corners in the map frame, (N, 2), and the ids seen at each (empty between stops).
void AddRoute(const run::InspectionInputs& in, const run::InspectionRun& run, py::dict* out) {
  const std::vector<Eigen::Vector2d> route = run::RouteMapFrame(in, run);
  py::array_t<double> xy({static_cast<py::ssize_t>(route.size()), py::ssize_t{2}});
  auto rows = xy.mutable_unchecked<2>();
  for (std::size_t i = 0; i < route.size(); ++i) {
    rows(i, 0) = route[i].x();
    rows(i, 1) = route[i].y();
  }
  (*out)["route"] = xy;
  py::list stops;
  for (const inspection::Waypoint& w : run.plan.waypoints) {
    py::list ids;
    if (w.stop >= 0) {
      for (const int i : run.plan.stops[w.stop].targets) ids.append(in.targets_local[i].id);
    }
    stops.append(py::tuple(ids));
  }
  (*out)["route_stops"] = stops;
}

py::dict Inspect(const InspectArgs& args, py::object progress) {
  const inspection::InspectionOptions options =
      run::WithOverrides(args.config.config.inspection, args.overrides);
  const Eigen::Vector2d start_map = Start(args.start_xy);
  ProgressRelay relay(std::move(progress));
  std::optional<run::InspectionInputs> inputs;
  run::InspectionRun plan;
  std::vector<std::string> files;
  {
    py::gil_scoped_release release;
    inputs = ReadingFiles({args.map, args.costmap, args.targets}, [&] {
      return run::ReadInspectionInputs(args.map, args.costmap, args.targets);
    });
    // Not a file error: a start off the free space, invalid targets, options (ValueError).
    plan = run::PlanInspectionRun(
        *inputs, start_map, options,
        [&](const std::string&, std::size_t done, std::size_t total) { relay(done, total); });
    relay.Flush();
    if (!args.out_dir.empty()) {
      files =
          ReadingFiles({}, [&] { return run::WriteInspectionRun(args.out_dir, *inputs, plan); });
    }
  }
  py::dict out;
  out["targets"] = TargetDicts(*inputs, plan);
  AddRoute(*inputs, plan, &out);
  out["summary_json"] = plan.summary.dump();
  out["files"] = files;
  return out;
}

}  // namespace

void BindInspect(py::module_& m) {
  m.def(
      "inspect",
      [](const std::string& map, const std::string& costmap, const std::string& targets,
         const ConfigHandle& config, std::optional<double> camera_height_m,
         std::optional<double> min_range_m, std::optional<double> max_range_m,
         std::optional<double> clearance_m, std::optional<double> robot_radius_m,
         std::optional<bool> return_to_start, std::optional<std::vector<double>> start,
         const std::string& out_dir, py::object progress) {
        InspectArgs args{map, costmap, targets, config, {}, std::move(start), out_dir};
        args.overrides.camera_height_m = camera_height_m;
        args.overrides.min_range_m = min_range_m;
        args.overrides.max_range_m = max_range_m;
        args.overrides.clearance_m = clearance_m;
        args.overrides.robot_radius_m = robot_radius_m;
        args.overrides.return_to_start = return_to_start;
        return Inspect(args, std::move(progress));
      },
      py::arg("map"), py::arg("costmap"), py::arg("targets"), py::arg("config"),
      py::arg("camera_height_m"), py::arg("min_range_m"), py::arg("max_range_m"),
      py::arg("clearance_m"), py::arg("robot_radius_m"), py::arg("return_to_start"),
      py::arg("start"), py::arg("out_dir"), py::arg("progress"),
      "Inspection planning from files (hylo.inspect calls this).");
}

}  // namespace hylo::python
