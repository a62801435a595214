#include "inspection_service.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "ros_messages.h"

namespace hylo::rosnode {

std::optional<Eigen::Vector2d> ResolveStart(const std::string& frame_id,
                                            const Eigen::Vector2d& requested_xy,
                                            const std::optional<Eigen::Isometry3d>& T_world_imu,
                                            const std::string& map_frame, std::string* why) {
  if (frame_id == map_frame) return requested_xy;
  if (!frame_id.empty()) {
    *why = "start in frame '" + frame_id + "', expected '" + map_frame +
           "' (or an empty frame_id for the current pose)";
    return std::nullopt;
  }
  if (!T_world_imu) {
    *why = "no valid pose yet to start from: give request.start in '" + map_frame + "'";
    return std::nullopt;
  }
  return T_world_imu->translation().head<2>().eval();
}

nav_msgs::Path ToPathMsg(const std::vector<Eigen::Vector2d>& route_map, const std::string& frame_id,
                         const ros::Time& stamp) {
  nav_msgs::Path path;
  path.header.frame_id = frame_id;
  path.header.stamp = stamp;
  double yaw = 0.0;
  for (std::size_t i = 0; i < route_map.size(); ++i) {
    if (i + 1 < route_map.size() && (route_map[i + 1] - route_map[i]).norm() > 1e-9) {
      const Eigen::Vector2d d = route_map[i + 1] - route_map[i];
      yaw = std::atan2(d.y(), d.x());
    }
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() << route_map[i].x(), route_map[i].y(), 0.0;
    T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    geometry_msgs::PoseStamped pose;
    pose.header = path.header;
    pose.pose = ToPoseMsg(T);
    path.poses.push_back(pose);
  }
  return path;
}

InspectionService::InspectionService(const std::string& map, const std::string& costmap,
                                     const std::string& targets,
                                     const inspection::InspectionOptions& options)
    : inputs_(run::ReadInspectionInputs(map, costmap, targets)),
      options_(run::WithOverrides(options, {})) {}

bool InspectionService::Plan(const Eigen::Vector2d& start_map,
                             std::vector<Eigen::Vector2d>* route_map, std::string* summary) const {
  run::InspectionRun run;
  try {
    run = run::PlanInspectionRun(inputs_, start_map, options_);
  } catch (const run::InspectionStartError& e) {
    *summary = e.what();
    return false;
  }
  *route_map = run::RouteMapFrame(inputs_, run);
  const inspection::InspectionSummary& s = run.plan.summary;
  char text[160];
  std::snprintf(text, sizeof(text),
                "%zu of %zu targets planned (%zu occluded, %zu unreachable), route %.1f m, "
                "%zu corners",
                s.planned, inputs_.targets_local.size(), s.occluded, s.unreachable,
                s.route_length_m, route_map->size());
  *summary = text;
  return true;
}

}  // namespace hylo::rosnode
