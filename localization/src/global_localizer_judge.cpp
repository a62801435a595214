// Global localization, step 2: the search's hypotheses refined by the ICP initializer and
// judged (global_localizer.h): accepted only when one place passes the gates and no other
// comes close.
#include <algorithm>
#include <sstream>

#include "global_bnb.h"
#include "hylo/localization/global_localizer.h"
#include "hylo/registration/icp.h"
#include "hylo/registration/voxel_filter.h"
#include "icp_initializer_internal.h"

namespace hylo::localization {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

bool Distinct(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b,
              const GlobalLocalizerOptions& options) {
  return internal::AreDistinct(a, b, options.distinct_translation_m,
                               options.distinct_yaw_deg * kDegToRad);
}

std::string Describe(const GlobalHypothesis& h) {
  std::ostringstream os;
  const Eigen::Vector3d& t = h.T_refined.translation();
  os << "(" << t.x() << ", " << t.y() << ") score " << h.score << " inliers " << h.inlier_ratio
     << " plane fitness " << h.plane_fitness_m2 << " fitness " << h.fitness_m2 << " ground support "
     << h.ground_support;
  return os.str();
}

// The refined hypothesis with the highest inlier ratio among those distinct from `pose`
// (nullptr when there is none).
const GlobalHypothesis* RunnerUp(const std::vector<GlobalHypothesis>& hypotheses,
                                 const Eigen::Isometry3d& pose,
                                 const GlobalLocalizerOptions& options) {
  const GlobalHypothesis* best = nullptr;
  for (const GlobalHypothesis& h : hypotheses) {
    if (!h.refined || !Distinct(h.T_refined, pose, options)) continue;
    if (best == nullptr || h.inlier_ratio > best->inlier_ratio) best = &h;
  }
  return best;
}

// The vehicle's own ground returns in `scan_imu`: within kGroundRadiusM horizontally, no
// higher than the search's clearance above the ground under the sensor (`sensor_height_m`
// below it). Slopes and ditches around the vehicle keep their downhill part; that is enough
// to tell whether the vehicle stands on mapped ground.
PointCloud GroundReturns(const PointCloud& scan_imu, const Eigen::Matrix3d& R_level_imu,
                         double sensor_height_m, const GlobalLocalizerOptions& options) {
  constexpr float kGroundRadiusM = 10.0f;  // as the ground estimate under the sensor
  const float band_m =
      static_cast<float>(options.ground_clearance_m > 0.0 ? options.ground_clearance_m : 0.3);
  const float top_z = static_cast<float>(-sensor_height_m) + band_m;
  const Eigen::Matrix3f R = R_level_imu.cast<float>();
  PointCloud ground;
  for (const Eigen::Vector3f& p : scan_imu) {
    const Eigen::Vector3f q = R * p;
    const float r = q.head<2>().norm();
    if (q.allFinite() && r >= options.min_range_m && r <= kGroundRadiusM && q.z() <= top_z) {
      ground.push_back(p);
    }
  }
  return ground;
}

}  // namespace

GlobalLocalizationResult GlobalLocalizer::Localize(const PointCloud& scan_imu,
                                                   const Eigen::Matrix3d& R_level_imu,
                                                   const GlobalMap& global_map,
                                                   const registration::NeighborSearch& map) const {
  const double start_s = internal::ThreadCpuSeconds();
  GlobalLocalizationResult result;
  result.hypotheses = Search(scan_imu, R_level_imu, global_map, &result.stats);
  double refine_start_s = -1.0;  // set when the refinements begin
  const auto finish = [&](GlobalStatus status, const std::string& message) {
    if (refine_start_s >= 0.0) result.refine_s = internal::ThreadCpuSeconds() - refine_start_s;
    result.status = status;
    result.message = ToString(status) + ": " + message;
    result.elapsed_s = internal::ThreadCpuSeconds() - start_s;
    return result;
  };
  if (global_map.empty() || map.Size() == 0) return finish(GlobalStatus::kBadInput, "empty map");
  if (result.stats.scan_points == 0) {
    return finish(GlobalStatus::kBadInput, "no ground seen near the vehicle, or too few points");
  }
  if (result.hypotheses.empty()) {
    return finish(GlobalStatus::kNotFound, "no place explains the scan");
  }

  refine_start_s = internal::ThreadCpuSeconds();
  const IcpInitializer judge(icp_judge_);
  // Every hypothesis refines the same cloud: thin it once, not once per hypothesis (the
  // initializer's own voxel filter then finds it already thinned).
  const PointCloud scan_fine = icp_.fine_voxel_m > 0.0
                                   ? registration::UniformSample(scan_imu, static_cast<float>(icp_.fine_voxel_m))
                                   : scan_imu;
  // Coarse stage: each hypothesis scoring at least refine_score_ratio x the best is pulled in
  // by the initializer's coarse ICP on a sparse cloud and ranked by the share of its points
  // near the map; the best fine_hypotheses distinct ones are refined and gated.
  const PointCloud scan_coarse = internal::Decimate(
      registration::UniformSample(scan_fine, static_cast<float>(icp_.coarse_voxel_m)), icp_.coarse_max_points);
  const registration::Icp coarse(icp_.coarse_icp);
  const PointCloud ground_fine =
      GroundReturns(scan_fine, R_level_imu, result.stats.sensor_height_m, options_);
  std::vector<std::size_t> order;
  const double best_score = result.hypotheses.front().score;
  for (std::size_t i = 0; i < result.hypotheses.size(); ++i) {
    GlobalHypothesis& h = result.hypotheses[i];
    if (h.score < options_.refine_score_ratio * best_score) break;
    const registration::IcpSummary s = coarse.Align(scan_coarse, map, h.T_map_imu);
    if (s.status != registration::IcpStatus::kConverged && s.status != registration::IcpStatus::kMaxIterations) continue;
    h.T_coarse = s.T_target_source;
    h.coarse_inlier_ratio =
        internal::MeasureOverlap(scan_coarse, map, h.T_coarse, icp_).inlier_ratio;
    order.push_back(i);
  }
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return result.hypotheses[a].coarse_inlier_ratio > result.hypotheses[b].coarse_inlier_ratio;
  });
  std::vector<IcpInitializerResult> refinements(result.hypotheses.size());
  std::vector<Eigen::Isometry3d> seen;
  int refined = 0;
  for (const std::size_t i : order) {
    if (refined >= options_.fine_hypotheses) break;
    GlobalHypothesis& h = result.hypotheses[i];
    if (std::any_of(seen.begin(), seen.end(), [&](const Eigen::Isometry3d& T) {
          return !Distinct(h.T_coarse, T, options_);
        })) {
      continue;
    }
    seen.push_back(h.T_coarse);
    ++refined;
    refinements[i] = judge.Initialize(scan_fine, map, h.T_coarse);
    const IcpInitializerResult& r = refinements[i];
    h.refined = true;
    h.passes = r.accepted;
    h.T_refined = r.accepted ? r.T_map_imu : r.best_T_map_imu;
    h.fitness_m2 = r.accepted ? r.fitness_score_m2 : r.best_fitness_score_m2;
    h.plane_fitness_m2 = r.accepted ? r.plane_fitness_m2 : r.best_plane_fitness_m2;
    h.inlier_ratio = r.accepted ? r.inlier_ratio : r.best_inlier_ratio;
    h.ground_support = internal::MeasureOverlap(ground_fine, map, h.T_refined, icp_).inlier_ratio;
    if (h.ground_support < options_.min_ground_support) h.passes = false;
  }

  // The passing poses, best inlier ratio first; distinct ones counted.
  std::vector<std::size_t> passing;
  for (std::size_t i = 0; i < result.hypotheses.size(); ++i) {
    if (result.hypotheses[i].passes) passing.push_back(i);
  }
  if (passing.empty()) {
    const GlobalHypothesis* top = nullptr;
    for (const GlobalHypothesis& h : result.hypotheses) {
      if (h.refined && (top == nullptr || h.inlier_ratio > top->inlier_ratio)) top = &h;
    }
    return finish(GlobalStatus::kNotFound,
                  top == nullptr
                      ? "no hypothesis survived the coarse ICP"
                      : "no place passed the ICP gates (best refined " + Describe(*top) + ")");
  }
  std::stable_sort(passing.begin(), passing.end(), [&](std::size_t a, std::size_t b) {
    return result.hypotheses[a].inlier_ratio > result.hypotheses[b].inlier_ratio;
  });
  const GlobalHypothesis& best = result.hypotheses[passing.front()];
  std::vector<Eigen::Isometry3d> distinct;
  for (const std::size_t i : passing) {
    const Eigen::Isometry3d& T = result.hypotheses[i].T_refined;
    if (std::none_of(distinct.begin(), distinct.end(),
                     [&](const Eigen::Isometry3d& d) { return !Distinct(T, d, options_); })) {
      distinct.push_back(T);
    }
  }
  result.num_passing = static_cast<int>(distinct.size());
  // Uniqueness: another place that explains nearly as much of the scan (passing the gates or
  // not) makes the view ambiguous. A place that passes the gates but explains clearly less
  // does not: on open gravel a wrong place's ground alone fits (and passes) wherever the
  // structures leave a quarter of the scan unexplained.
  const GlobalHypothesis* runner_up = RunnerUp(result.hypotheses, best.T_refined, options_);
  if (runner_up != nullptr &&
      runner_up->inlier_ratio >= best.inlier_ratio - options_.ambiguity_inlier_margin) {
    return finish(GlobalStatus::kAmbiguous, "two places fit nearly equally: " + Describe(best) +
                                                " vs " + Describe(*runner_up));
  }
  result.refinement = refinements[passing.front()];
  result.T_map_imu = result.refinement.T_map_imu;
  return finish(GlobalStatus::kAccepted, Describe(best));
}

}  // namespace hylo::localization
