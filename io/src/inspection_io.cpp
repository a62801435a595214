#include "hylo/io/inspection_io.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "hylo/io/atomic_file.h"

namespace hylo::io {
namespace {

namespace fs = std::filesystem;
using inspection::InspectionPlan;
using inspection::Target;
using inspection::TargetPlan;
using inspection::TargetStatus;

std::string Number(double v, int decimals = 3) {
  char text[48];
  std::snprintf(text, sizeof(text), "%.*f", decimals, v);
  return text;
}

Json Xyz(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }

Eigen::Vector3d ToMap(const terrain::GridGeometry& g, const Eigen::Vector3d& local) {
  return local + g.origin_world;
}

// A CSV cell that may hold commas or quotes.
std::string Quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

std::string PlanCsv(const InspectionPlan& plan, const std::vector<Target>& targets,
                    const terrain::GridGeometry& g) {
  std::string text =
      "target_id,status,view_x,view_y,view_z,order,path_length_m,along_route_m,range_m,"
      "view_angle_deg,visible_cells,reason\n";
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const TargetPlan& t = plan.targets[i];
    text += targets[i].id + "," + inspection::TargetStatusName(t.status) + ",";
    if (t.status == TargetStatus::kPlanned) {
      const Eigen::Vector3d v = ToMap(g, t.camera);
      text += Number(v.x()) + "," + Number(v.y()) + "," + Number(v.z()) + "," +
              std::to_string(t.order) + "," + Number(t.leg_length_m) + "," +
              Number(t.along_route_m) + "," + Number(t.range_m) + "," + Number(t.view_angle_deg, 1);
    } else {
      text += ",,,,,,,";
    }
    text += "," + std::to_string(t.visible_cells) + "," + Quoted(t.reason) + "\n";
  }
  return text;
}

std::string RouteCsv(const InspectionPlan& plan, const std::vector<Target>& targets,
                     const terrain::GridGeometry& g) {
  std::string text = "x,y,stop\n";
  for (const inspection::Waypoint& w : plan.waypoints) {
    const Eigen::Vector2d xy = w.xy + g.origin_world.head<2>();
    std::string ids;
    if (w.stop >= 0) {
      for (const int i : plan.stops[w.stop].targets) ids += (ids.empty() ? "" : ";") + targets[i].id;
    }
    text += Number(xy.x()) + "," + Number(xy.y()) + "," + ids + "\n";
  }
  return text;
}

// One target's visibility codes on the costmap's cells, cut to the cells it was tested on.
terrain::GridMap VisibilityGrid(const InspectionPlan& plan, std::size_t i,
                                const terrain::GridGeometry& g) {
  const inspection::TargetVisibility& vis = plan.visibility[i];
  int col0 = g.width, row0 = g.height, col1 = -1, row1 = -1;
  for (const inspection::CellView& v : vis.cells) {
    col0 = std::min(col0, g.Col(v.cell));
    col1 = std::max(col1, g.Col(v.cell));
    row0 = std::min(row0, g.Row(v.cell));
    row1 = std::max(row1, g.Row(v.cell));
  }
  if (col1 < 0) col0 = row0 = col1 = row1 = 0;  // no candidate: one NODATA cell
  terrain::GridGeometry cut = g;
  cut.corner_local = g.corner_local + g.resolution_m * Eigen::Vector2d(col0, row0);
  cut.width = col1 - col0 + 1;
  cut.height = row1 - row0 + 1;
  terrain::GridMap grid(cut);
  std::vector<float>& layer = grid.AddLayer("visibility", std::nanf(""));
  const TargetPlan& t = plan.targets[i];
  for (const inspection::CellView& v : vis.cells) {
    const bool reachable = std::isfinite(plan.reach_cost[v.cell]);
    float code = v.visible ? (reachable ? 2.f : 1.f) : 0.f;
    if (t.status == TargetStatus::kPlanned && v.cell == t.view_cell) code = 3.f;
    layer[cut.Index(g.Col(v.cell) - col0, g.Row(v.cell) - row0)] = code;
  }
  return grid;
}

}  // namespace

Json InspectionOptionsJson(const inspection::InspectionOptions& o) {
  Json j = Json::object();
  const inspection::VisibilityOptions& v = o.visibility;
  j["visibility"] = {{"camera_height_m", v.camera_height_m},
                     {"min_range_m", v.min_range_m},
                     {"max_range_m", v.max_range_m},
                     {"target_radius_m", v.target_radius_m},
                     {"min_visible_fraction", v.min_visible_fraction},
                     {"occupancy",
                      {{"voxel_size_m", v.occupancy.voxel_size_m},
                       {"clearance_m", v.occupancy.clearance_m},
                       {"max_voxels_million", v.occupancy.max_voxels_million}}}};
  j["search"] = {{"robot_radius_m", o.search.robot_radius_m},
                 {"cost_weight", o.search.cost_weight}};
  j["viewpoint"] = {{"preferred_range_m", o.viewpoint.preferred_range_m},
                    {"range_weight", o.viewpoint.range_weight},
                    {"angle_weight", o.viewpoint.angle_weight},
                    {"traversal_weight", o.viewpoint.traversal_weight}};
  j["tour"] = {{"return_to_start", o.tour.return_to_start},
               {"exact_max_stops", o.tour.exact_max_stops}};
  j["start_snap_radius_m"] = o.start_snap_radius_m;
  return j;
}

Json InspectionPlanJson(const InspectionPlan& plan, const std::vector<Target>& targets,
                        const terrain::GridGeometry& g,
                        const inspection::InspectionOptions& options) {
  const inspection::InspectionSummary& s = plan.summary;
  Json j = Json::object();
  j["options"] = InspectionOptionsJson(options);
  const Eigen::Vector2d start = g.CentreWorld(g.Col(plan.start_cell), g.Row(plan.start_cell));
  j["start"] = Json::array({start.x(), start.y()});
  j["targets"] = {{"total", targets.size()},
                  {"planned", s.planned},
                  {"occluded", s.occluded},
                  {"unreachable", s.unreachable}};
  j["route"] = {{"length_m", s.route_length_m},
                {"cost", s.route_cost},
                {"stops", plan.stops.size()},
                {"waypoints", plan.waypoints.size()},
                {"tour_method", inspection::TourMethodName(s.tour_method)},
                {"return_to_start", options.tour.return_to_start}};
  j["cells"] = {{"passable", s.passable_cells}, {"reachable", s.reachable_cells}};
  j["occupancy"] = {{"voxels", Json::array({s.occupancy.dims.x(), s.occupancy.dims.y(),
                                            s.occupancy.dims.z()})},
                    {"points_in_box", s.occupancy.points_in_box},
                    {"occupied_voxels", s.occupancy.occupied_voxels},
                    {"blocked_voxels", s.occupancy.blocked_voxels}};
  j["seconds"] = {{"reach", s.seconds_reach},
                  {"occupancy", s.seconds_occupancy},
                  {"visibility", s.seconds_visibility},
                  {"travel_costs", s.seconds_travel_costs},
                  {"tour", s.seconds_tour},
                  {"route", s.seconds_route}};
  Json& per_target = j["per_target"] = Json::array();
  for (std::size_t i = 0; i < targets.size(); ++i) {
    const TargetPlan& t = plan.targets[i];
    Json e = {{"id", targets[i].id},
              {"status", inspection::TargetStatusName(t.status)},
              {"position", Xyz(ToMap(g, targets[i].position))},
              {"candidate_cells", t.candidate_cells},
              {"visible_cells", t.visible_cells},
              {"reachable_visible_cells", t.reachable_visible_cells}};
    if (t.status == TargetStatus::kPlanned) {
      e["order"] = t.order;
      e["view"] = Xyz(ToMap(g, t.camera));
      e["range_m"] = t.range_m;
      e["view_angle_deg"] = t.view_angle_deg;
      e["path_length_m"] = t.leg_length_m;
      e["along_route_m"] = t.along_route_m;
    } else {
      e["reason"] = t.reason;
    }
    per_target.push_back(e);
  }
  return j;
}

std::vector<std::string> WriteInspectionFiles(const std::string& dir, const InspectionPlan& plan,
                                              const std::vector<Target>& targets,
                                              const CostmapLayers& costmap, Json summary) {
  std::error_code error;
  fs::create_directories(fs::path(dir) / "visibility", error);
  if (error) throw std::runtime_error(dir + ": cannot create directory (" + error.message() + ")");
  const terrain::GridGeometry& g = costmap.grid.geometry();
  std::vector<std::string> written;
  const auto path = [&](const std::string& name) {
    written.push_back((fs::path(dir) / name).string());
    return written.back();
  };
  WriteFileAtomically(path("plan.csv"), PlanCsv(plan, targets, g));
  WriteFileAtomically(path("route.csv"), RouteCsv(plan, targets, g));
  for (std::size_t i = 0; i < targets.size(); ++i) {
    WriteAsciiGrid(path("visibility/" + targets[i].id + ".asc"), VisibilityGrid(plan, i, g),
                   "visibility");
  }
  WriteFileAtomically(path("plan.png"), PlanPng(plan, targets, costmap));
  const std::string summary_path = path("summary.json");
  for (const std::string& f : written) summary["outputs"].push_back(f);
  WriteJsonFile(summary_path, summary);
  return written;
}

}  // namespace hylo::io
