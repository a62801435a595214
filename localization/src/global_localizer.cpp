// Global localization: the scan as the search sees it, the branch and bound, then refinement
// and judgement by the ICP initializer's gates (global_localizer.h).
#include "hylo/localization/global_localizer.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "global_bnb.h"
#include "hylo/common/check.h"
#include "hylo/common/enum_names.h"
#include "hylo/common/option_checks.h"
#include "hylo/registration/voxel_filter.h"

namespace hylo::localization {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

// The levelled scan relative to the vehicle's ground, filtered for the search. False when no
// ground is seen near the vehicle.
bool PrepareScan(const PointCloud& scan_imu, const Eigen::Matrix3d& R_level_imu,
                 const GlobalLocalizerOptions& options, double cell_m, PointCloud* points_ground,
                 double* sensor_height_m) {
  const Eigen::Matrix3f R = R_level_imu.cast<float>();
  PointCloud levelled;
  levelled.reserve(scan_imu.size());
  for (const Eigen::Vector3f& p : scan_imu) {
    if (!p.allFinite()) continue;
    const Eigen::Vector3f q = R * p;
    const float range = q.norm();
    if (range < options.min_range_m || range > options.max_range_m) continue;
    levelled.push_back(q);
  }
  double ground_z_m = -options.sensor_height_m;
  if (options.sensor_height_m <= 0.0 && !internal::GroundUnderSensor(levelled, &ground_z_m)) {
    return false;
  }
  const float ground_z = static_cast<float>(ground_z_m);
  *sensor_height_m = -ground_z;
  PointCloud kept;
  kept.reserve(levelled.size());
  for (Eigen::Vector3f q : levelled) {
    q.z() -= ground_z;
    if (options.ground_clearance_m < 0.0 || q.z() >= options.ground_clearance_m) kept.push_back(q);
  }
  kept = registration::UniformSample(kept, static_cast<float>(0.5 * cell_m));
  const std::size_t limit = static_cast<std::size_t>(options.max_scan_points);
  points_ground->clear();
  if (kept.size() <= limit) {
    *points_ground = std::move(kept);
    return true;
  }
  for (std::size_t i = 0; i < limit; ++i) points_ground->push_back(kept[i * kept.size() / limit]);
  return true;
}

Eigen::Isometry3d PoseOf(const internal::BnbCandidate& c, double yaw_rad, const GlobalMap& map,
                         const Eigen::Matrix3d& R_level_imu, double sensor_height_m) {
  const GlobalMap::Layout& layout = map.layout();
  const double cell = layout.options.cell_m;
  const std::size_t i = static_cast<std::size_t>(c.y) * layout.width + c.x;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()) * R_level_imu;
  T.translation() = Eigen::Vector3d(layout.origin_x_m + (c.x + 0.5) * cell,
                                    layout.origin_y_m + (c.y + 0.5) * cell,
                                    map.level(0).ground_min_m[i] + sensor_height_m);
  return T;
}

}  // namespace

bool GlobalLocalizerOptions::IsValid(std::string* why) const {
  return CheckNonNegative("min_range_m", min_range_m, why) &&
         (max_range_m > min_range_m ||
          FailOption("max_range_m", max_range_m, "must be > min_range_m", why)) &&
         (std::isfinite(ground_clearance_m) ||
          FailOption("ground_clearance_m", ground_clearance_m, "must be finite", why)) &&
         CheckNonNegative("sensor_height_m", sensor_height_m, why) &&
         CheckNonNegative("z_tolerance_m", z_tolerance_m, why) &&
         CheckInRange("yaw_step_deg", yaw_step_deg, 0.0, 90.0, why) &&
         CheckAtLeast("max_scan_points", max_scan_points, 10, "", why) &&
         CheckAtLeast("max_hypotheses", max_hypotheses, 1, "", why) &&
         ((min_score > 0.0 && min_score <= 1.0) ||
          FailOption("min_score", min_score, "must be in (0, 1]", why)) &&
         CheckPositive("distinct_translation_m", distinct_translation_m, why) &&
         CheckPositive("distinct_yaw_deg", distinct_yaw_deg, why) &&
         ((refine_score_ratio > 0.0 && refine_score_ratio <= 1.0) ||
          FailOption("refine_score_ratio", refine_score_ratio, "must be in (0, 1]", why)) &&
         CheckAtLeast("fine_hypotheses", fine_hypotheses, 1, "", why) &&
         CheckInRange("ambiguity_inlier_margin", ambiguity_inlier_margin, 0.0, 1.0, why) &&
         CheckInRange("min_ground_support", min_ground_support, 0.0, 1.0, why) &&
         CheckAtLeast("judge_max_points", judge_max_points, 50, "", why) &&
         CheckAtLeast("judge_icp_iterations", judge_icp_iterations, 1, "", why);
}

std::string ToString(GlobalStatus status) {
  static constexpr std::pair<GlobalStatus, const char*> kNames[] = {
      {GlobalStatus::kAccepted, "accepted"},
      {GlobalStatus::kAmbiguous, "ambiguous"},
      {GlobalStatus::kNotFound, "not_found"},
      {GlobalStatus::kBadInput, "bad_input"}};
  return NameOf(kNames, status);
}

Eigen::Matrix3d LevellingRotation(const Eigen::Matrix3d& R_map_imu) {
  const double yaw = std::atan2(R_map_imu(1, 0), R_map_imu(0, 0));
  return Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R_map_imu;
}

GlobalLocalizer::GlobalLocalizer(const GlobalLocalizerOptions& options,
                                 const IcpInitializerOptions& icp)
    : options_(options), icp_(icp) {
  std::string why;
  HYLO_CHECK(options_.IsValid(&why), "GlobalLocalizerOptions: " + why);
  HYLO_CHECK(icp_.IsValid(&why), "IcpInitializerOptions: " + why);
  icp_.search_enabled = false;
  icp_judge_ = icp_;
  icp_judge_.fine_max_points = std::min(icp_.fine_max_points, options_.judge_max_points);
  // The judge's fine ICP starts from the coarse ICP's result and hands over to the
  // point-to-plane steps: it only has to settle into their basin, not converge to 0.1 mm.
  icp_judge_.fine_icp.max_iterations =
      std::min(icp_.fine_icp.max_iterations, options_.judge_icp_iterations);
  icp_judge_.min_source_points = std::min(icp_judge_.min_source_points, icp_judge_.fine_max_points);
}

std::vector<GlobalHypothesis> GlobalLocalizer::Search(const PointCloud& scan_imu,
                                                      const Eigen::Matrix3d& R_level_imu,
                                                      const GlobalMap& global_map,
                                                      GlobalSearchStats* stats) const {
  const double start_s = internal::ThreadCpuSeconds();
  GlobalSearchStats local;
  GlobalSearchStats& s = stats != nullptr ? *stats : local;
  s = GlobalSearchStats();
  std::vector<GlobalHypothesis> hypotheses;
  if (global_map.empty()) return hypotheses;
  const GlobalMapOptions& map_options = global_map.options();
  PointCloud points;
  if (!PrepareScan(scan_imu, R_level_imu, options_, map_options.cell_m, &points,
                   &s.sensor_height_m) ||
      points.size() < 10) {
    s.search_s = internal::ThreadCpuSeconds() - start_s;
    return hypotheses;
  }
  const double yaw_step = options_.yaw_step_deg > 0.0 ? options_.yaw_step_deg * kDegToRad
                                                      : map_options.cell_m / options_.max_range_m;
  const internal::DiscreteScan scan = internal::Discretize(points, map_options, yaw_step);
  s.scan_points = points.size();
  s.scan_voxels = static_cast<std::size_t>(scan.total_voxels);
  s.yaws = static_cast<int>(scan.yaws_rad.size());
  internal::BnbOptions bnb;
  bnb.max_candidates = options_.max_hypotheses;
  bnb.min_score = std::max(1, static_cast<int>(std::ceil(options_.min_score * scan.total_voxels)));
  bnb.z_tolerance_m = options_.z_tolerance_m;
  bnb.distinct_cells = options_.distinct_translation_m / map_options.cell_m;
  bnb.distinct_yaw_rad = options_.distinct_yaw_deg * kDegToRad;
  for (const internal::BnbCandidate& c :
       internal::BranchAndBound(scan, global_map, bnb, &s.nodes_scored, &s.columns_scored)) {
    GlobalHypothesis h;
    h.T_map_imu = PoseOf(c, scan.yaws_rad[static_cast<std::size_t>(c.yaw_index)], global_map,
                         R_level_imu, s.sensor_height_m);
    h.score = static_cast<double>(c.score) / scan.total_voxels;
    hypotheses.push_back(h);
  }
  s.search_s = internal::ThreadCpuSeconds() - start_s;
  return hypotheses;
}

}  // namespace hylo::localization
