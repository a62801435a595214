#pragma once
// The `inspection:` section: where the robot stands to see each target, and the route there
// (hylo inspect).

#include "config_sections.h"

namespace hylo::config {

template <class V>
void VisitFields(V& v, inspection::OccupancyOptions& o) {
  v("voxel_size_m", o.voxel_size_m, "edge of the voxels sight lines are cast through, m (> 0)");
  v("clearance_m", o.clearance_m,
    "sight lines keep at least this from every map point: the map's noise plus the camera's "
    "pose uncertainty on the spot, m (>= 0)");
  v("max_voxels_million", o.max_voxels_million,
    "larger grids are refused (memory: 1000 M voxels = 125 MB), millions of voxels (> 0)");
}

template <class V>
void VisitFields(V& v, inspection::VisibilityOptions& o) {
  v("camera_height_m", o.camera_height_m, "camera above the ground of the robot's cell, m");
  v("min_range_m", o.min_range_m, "camera-to-target range, least, m (a target may set its own)");
  v("max_range_m", o.max_range_m, "camera-to-target range, most, m (a target may set its own)");
  v("target_radius_m", o.target_radius_m,
    "a point target's own surroundings (the part it is on), where sight lines may end, m");
  v("min_visible_fraction", o.min_visible_fraction,
    "a box target is seen when this share of its nine sight lines is clear, (0, 1]");
  v.Section("occupancy", o.occupancy, "the map's voxels that block sight lines");
}

template <class V>
void VisitFields(V& v, inspection::SearchOptions& o) {
  v("robot_radius_m", o.robot_radius_m, "the robot's centre keeps this far from lethal cells, m");
  v("cost_weight", o.cost_weight,
    "extra cost of a step per unit of cell cost: a cell just below lethal counts "
    "1 + cost_weight times its length (>= 0)");
}

template <class V>
void VisitFields(V& v, inspection::ViewpointOptions& o) {
  v("preferred_range_m", o.preferred_range_m, "range the camera is best at, m");
  v("range_weight", o.range_weight, "weight of the range term of a viewpoint's score (>= 0)");
  v("angle_weight", o.angle_weight, "weight of the view-angle term (>= 0)");
  v("traversal_weight", o.traversal_weight, "weight of the standing cell's cost (>= 0)");
}

template <class V>
void VisitFields(V& v, inspection::TourOptions& o) {
  v("return_to_start", o.return_to_start,
    "a closed tour back to the start; false: it ends at the last viewpoint");
  v("exact_max_stops", o.exact_max_stops,
    "the tour is solved exactly (Held-Karp) up to this many stops besides the start, else "
    "heuristically ([0, 16]: memory is 2^n n doubles)");
}

template <class V>
void VisitFields(V& v, inspection::InspectionOptions& o) {
  v.Section("visibility", o.visibility, "the camera, its ranges and what blocks its view");
  v.Section("search", o.search, "paths over the traversability costmap");
  v.Section("viewpoint", o.viewpoint, "how the place to stand is chosen among those that see");
  v.Section("tour", o.tour, "the order of the visits");
  v("start_snap_radius_m", o.start_snap_radius_m,
    "a start off the passable cells moves to the nearest one within this distance, m");
}

}  // namespace hylo::config
