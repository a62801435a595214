#include "hylo/run/inspection_run.h"

#include <cstdio>
#include <stdexcept>

#include "hylo/common/local_origin.h"
#include "hylo/io/cloud_io.h"
#include "hylo/io/inspection_io.h"
#include "hylo/io/targets_io.h"

namespace hylo::run {

inspection::InspectionOptions WithOverrides(inspection::InspectionOptions o,
                                            const InspectionOverrides& given) {
  inspection::VisibilityOptions& v = o.visibility;
  if (given.camera_height_m) v.camera_height_m = *given.camera_height_m;
  if (given.min_range_m) v.min_range_m = *given.min_range_m;
  if (given.max_range_m) v.max_range_m = *given.max_range_m;
  if (given.clearance_m) v.occupancy.clearance_m = *given.clearance_m;
  if (given.voxel_m) v.occupancy.voxel_size_m = *given.voxel_m;
  if (given.robot_radius_m) o.search.robot_radius_m = *given.robot_radius_m;
  if (given.return_to_start) o.tour.return_to_start = *given.return_to_start;
  std::string why;
  if (!o.IsValid(&why)) throw std::invalid_argument("inspection options: " + why);
  return o;
}

InspectionInputs ReadInspectionInputs(const std::string& map_path, const std::string& costmap_dir,
                                      const std::string& targets_path) {
  InspectionInputs in{map_path,     costmap_dir,
                      targets_path, io::ReadCostmapLayers(costmap_dir),
                      {},           io::ReadTargets(targets_path)};
  for (inspection::Target& t : in.targets_local) t.position -= in.origin_world();
  const io::CloudFile map = io::ReadCloud(map_path);
  if (map.positions.empty()) throw std::runtime_error(map_path + ": the map has no point");
  in.map_local = ToLocal(map.positions, in.origin_world());
  return in;
}

InspectionRun PlanInspectionRun(const InspectionInputs& in, const Eigen::Vector2d& start_map,
                                const inspection::InspectionOptions& options,
                                const inspection::InspectionProgress& progress) {
  InspectionRun run;
  try {
    run.plan = inspection::PlanInspection(in.map_local, in.costmap.grid, in.costmap.classes,
                                          in.targets_local, start_map - in.origin_world().head<2>(),
                                          options, progress);
  } catch (const inspection::StartNotPassable& e) {
    char where[96];
    std::snprintf(where, sizeof(where), "start (%.3f, %.3f) in the map frame: ", start_map.x(),
                  start_map.y());
    throw InspectionStartError(where + std::string(e.what()));
  }
  run.summary =
      io::InspectionPlanJson(run.plan, in.targets_local, in.costmap.grid.geometry(), options);
  run.summary["map"] = in.map_path;
  run.summary["costmap"] = in.costmap_dir;
  run.summary["targets_file"] = in.targets_path;
  return run;
}

std::vector<std::string> WriteInspectionRun(const std::string& dir, const InspectionInputs& in,
                                            const InspectionRun& run) {
  return io::WriteInspectionFiles(dir, run.plan, in.targets_local, in.costmap, run.summary);
}

std::vector<Eigen::Vector2d> RouteMapFrame(const InspectionInputs& in, const InspectionRun& run) {
  std::vector<Eigen::Vector2d> route;
  route.reserve(run.plan.waypoints.size());
  for (const inspection::Waypoint& w : run.plan.waypoints)
    route.push_back(w.xy + in.origin_world().head<2>());
  return route;
}

}  // namespace hylo::run
