// Defaults and validation of IcpInitializerOptions.
#include <cmath>
#include <sstream>

#include "hylo/localization/icp_initializer.h"

namespace hylo::localization {
namespace {

bool Positive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

IcpInitializerOptions::IcpInitializerOptions() {
  // Fine ICP: pairs within 1 m, run to convergence (millimetre / 1e-4 rad increments).
  fine_icp.max_correspondence_distance_m = 1.0;
  fine_icp.max_iterations = 100;
  fine_icp.translation_epsilon_m = 1e-4;
  fine_icp.rotation_epsilon_rad = 1e-5;
  // Coarse ICP: pairs within 3 m so a start 1 m / 10 deg off (half a grid cell) still pulls
  // in, few iterations: it only has to land inside the fine ICP's basin.
  coarse_icp.max_correspondence_distance_m = 3.0;
  coarse_icp.max_iterations = 20;
  coarse_icp.translation_epsilon_m = 1e-3;
  coarse_icp.rotation_epsilon_rad = 1e-4;
}

bool IcpInitializerOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  std::string icp_why;
  if (!Positive(plane_fitness_threshold_m2)) {
    os << "plane_fitness_threshold_m2 = " << plane_fitness_threshold_m2
       << ": must be finite and > 0";
  } else if (!(fitness_threshold_m2 >= 0.0) || !std::isfinite(fitness_threshold_m2)) {
    os << "fitness_threshold_m2 = " << fitness_threshold_m2 << ": must be finite and >= 0";
  } else if (!Positive(fitness_max_range_m)) {
    os << "fitness_max_range_m = " << fitness_max_range_m << ": must be finite and > 0";
  } else if (!Positive(inlier_distance_m)) {
    os << "inlier_distance_m = " << inlier_distance_m << ": must be finite and > 0";
  } else if (!(min_inlier_ratio > 0.0 && min_inlier_ratio <= 1.0)) {
    os << "min_inlier_ratio = " << min_inlier_ratio << ": must be in (0, 1]";
  } else if (!(min_constraint >= 0.0 && min_constraint < 1.0)) {
    os << "min_constraint = " << min_constraint << ": must be in [0, 1)";
  } else if (min_source_points < 3) {
    os << "min_source_points = " << min_source_points << ": must be >= 3";
  } else if (!(fine_voxel_m >= 0.0) || !std::isfinite(fine_voxel_m)) {
    os << "fine_voxel_m = " << fine_voxel_m << ": must be finite and >= 0";
  } else if (fine_max_points < min_source_points) {
    os << "fine_max_points = " << fine_max_points << ": must be >= min_source_points ("
       << min_source_points << ")";
  } else if (coarse_max_points < 3) {
    os << "coarse_max_points = " << coarse_max_points << ": must be >= 3";
  } else if (plane_refine_iterations < 0) {
    os << "plane_refine_iterations = " << plane_refine_iterations << ": must be >= 0";
  } else if (!fine_icp.IsValid(&icp_why)) {
    os << "fine_icp." << icp_why;
  } else if (!(yaw_range_deg >= 0.0 && yaw_range_deg <= 180.0)) {
    os << "yaw_range_deg = " << yaw_range_deg << ": must be in [0, 180]";
  } else if (!Positive(yaw_step_deg)) {
    os << "yaw_step_deg = " << yaw_step_deg << ": must be finite and > 0";
  } else if (!(position_range_m >= 0.0) || !std::isfinite(position_range_m)) {
    os << "position_range_m = " << position_range_m << ": must be finite and >= 0";
  } else if (!Positive(position_step_m)) {
    os << "position_step_m = " << position_step_m << ": must be finite and > 0";
  } else if (!(coarse_voxel_m >= fine_voxel_m) || !std::isfinite(coarse_voxel_m)) {
    os << "coarse_voxel_m = " << coarse_voxel_m << ": must be finite and >= fine_voxel_m ("
       << fine_voxel_m << ")";
  } else if (!coarse_icp.IsValid(&icp_why)) {
    os << "coarse_icp." << icp_why;
  } else if (max_refined_candidates < 1) {
    os << "max_refined_candidates = " << max_refined_candidates << ": must be >= 1";
  } else if (!Positive(distinct_translation_m)) {
    os << "distinct_translation_m = " << distinct_translation_m << ": must be finite and > 0";
  } else if (!Positive(distinct_rotation_deg)) {
    os << "distinct_rotation_deg = " << distinct_rotation_deg << ": must be finite and > 0";
  } else if (max_hypotheses < 1) {
    os << "max_hypotheses = " << max_hypotheses << ": must be >= 1";
  }
  if (why != nullptr) *why = os.str();
  return os.str().empty();
}

}  // namespace hylo::localization
