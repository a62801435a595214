// ICP initializer: the guess first (the paper's step), then a bounded coarse-to-fine search.
#include "hylo/localization/icp_initializer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "hylo/common/check.h"
#include "hylo/registration/voxel_filter.h"
#include "icp_initializer_internal.h"

namespace hylo::localization {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

// One refined pose and its gates.
struct Candidate {
  Eigen::Isometry3d T_map_imu = Eigen::Isometry3d::Identity();
  internal::PoseQuality quality;
  int hypothesis = -1;  // index into the hypothesis list
  bool icp_ok = false;  // the ICP ran to a result (converged or out of iterations)
  bool passes = false;
};

bool IcpRanToResult(const registration::IcpSummary& summary) {
  return summary.status == registration::IcpStatus::kConverged || summary.status == registration::IcpStatus::kMaxIterations;
}

std::string Describe(const internal::PoseQuality& q) {
  std::ostringstream os;
  os << "plane fitness " << q.plane_fitness_m2 << " m^2, fitness " << q.fitness_score_m2
     << " m^2, inlier ratio " << q.inlier_ratio << ", constraint " << q.constraint;
  return os.str();
}

bool PassesGates(const internal::PoseQuality& q, const IcpInitializerOptions& options) {
  return q.plane_fitness_m2 < options.plane_fitness_threshold_m2 &&
         (options.fitness_threshold_m2 <= 0.0 ||
          q.fitness_score_m2 < options.fitness_threshold_m2) &&
         q.inlier_ratio >= options.min_inlier_ratio && q.constraint >= options.min_constraint;
}

class Search {
 public:
  Search(const IcpInitializerOptions& options, const PointCloud& fine_source,
         const registration::NeighborSearch& map, const Eigen::Isometry3d& T_guess)
      : options_(options), fine_source_(fine_source), map_(map), T_guess_(T_guess) {}

  // Fine ICP from `T_start`, then every gate.
  Candidate Refine(const Eigen::Isometry3d& T_start, int hypothesis) {
    ++tried_;
    Candidate c;
    c.hypothesis = hypothesis;
    const registration::IcpSummary icp = registration::Icp(options_.fine_icp).Align(fine_source_, map_, T_start);
    c.icp_ok = IcpRanToResult(icp);
    c.T_map_imu = c.icp_ok ? internal::PlaneRefine(fine_source_, map_, icp.T_target_source,
                                                   options_.inlier_distance_m,
                                                   options_.plane_refine_iterations)
                           : icp.T_target_source;
    c.quality = internal::MeasureQuality(fine_source_, map_, c.T_map_imu, options_);
    c.passes = c.icp_ok && PassesGates(c.quality, options_);
    return c;
  }

  // Coarse ICP from every hypothesis; the best `max_refined_candidates` distinct results
  // (by inlier ratio) go through Refine.
  std::vector<Candidate> CoarseToFine(const std::vector<internal::Hypothesis>& hypotheses) {
    const PointCloud coarse_source =
        internal::Decimate(registration::UniformSample(fine_source_, static_cast<float>(options_.coarse_voxel_m)),
                           options_.coarse_max_points);
    const registration::Icp coarse(options_.coarse_icp);
    std::vector<Candidate> coarse_results;
    for (std::size_t k = 0; k < hypotheses.size(); ++k) {
      ++tried_;
      const registration::IcpSummary icp =
          coarse.Align(coarse_source, map_, internal::ApplyHypothesis(T_guess_, hypotheses[k]));
      if (!IcpRanToResult(icp)) continue;
      Candidate c;
      c.T_map_imu = icp.T_target_source;
      c.hypothesis = static_cast<int>(k);
      c.quality = internal::MeasureOverlap(coarse_source, map_, c.T_map_imu, options_);
      coarse_results.push_back(c);
    }
    std::stable_sort(coarse_results.begin(), coarse_results.end(),
                     [](const Candidate& a, const Candidate& b) {
                       return a.quality.inlier_ratio > b.quality.inlier_ratio;
                     });
    std::vector<Candidate> refined;
    std::vector<Eigen::Isometry3d> seen;
    for (const Candidate& c : coarse_results) {
      if (static_cast<int>(refined.size()) >= options_.max_refined_candidates) break;
      if (!IsNew(c.T_map_imu, &seen)) continue;
      refined.push_back(Refine(c.T_map_imu, c.hypothesis));
    }
    return refined;
  }

  // False when `T` is within the distinct bounds of a pose in `seen`; otherwise adds it.
  bool IsNew(const Eigen::Isometry3d& T, std::vector<Eigen::Isometry3d>* seen) const {
    for (const Eigen::Isometry3d& other : *seen) {
      if (!internal::AreDistinct(T, other, options_.distinct_translation_m,
                                 options_.distinct_rotation_deg * kDegToRad)) {
        return false;
      }
    }
    seen->push_back(T);
    return true;
  }

  int tried() const { return tried_; }

 private:
  const IcpInitializerOptions& options_;
  const PointCloud& fine_source_;
  const registration::NeighborSearch& map_;
  Eigen::Isometry3d T_guess_;
  int tried_ = 0;
};

void SetBest(const std::vector<Candidate>& candidates, IcpInitializerResult* result) {
  for (const Candidate& c : candidates) {
    if (c.quality.inlier_ratio > result->best_inlier_ratio ||
        (c.quality.inlier_ratio == result->best_inlier_ratio &&
         c.quality.plane_fitness_m2 < result->best_plane_fitness_m2)) {
      result->best_fitness_score_m2 = c.quality.fitness_score_m2;
      result->best_plane_fitness_m2 = c.quality.plane_fitness_m2;
      result->best_inlier_ratio = c.quality.inlier_ratio;
      result->best_constraint = c.quality.constraint;
      result->best_T_map_imu = c.T_map_imu;
    }
  }
}

void Accept(const Candidate& c, const std::vector<internal::Hypothesis>& hypotheses,
            IcpInitializerResult* result) {
  result->accepted = true;
  result->T_map_imu = c.T_map_imu;
  result->fitness_score_m2 = c.quality.fitness_score_m2;
  result->plane_fitness_m2 = c.quality.plane_fitness_m2;
  result->inlier_ratio = c.quality.inlier_ratio;
  result->constraint = c.quality.constraint;
  result->accepted_hypothesis = c.hypothesis;
  if (c.hypothesis > 0) {
    const internal::Hypothesis& h = hypotheses[c.hypothesis];
    result->hypothesis_dx_m = h.dx_m;
    result->hypothesis_dy_m = h.dy_m;
    result->hypothesis_dyaw_deg = h.dyaw_rad / kDegToRad;
  }
}

// The search's verdict: the lowest-plane-fitness passing candidate, unless another distinct one
// passes too (then the view is ambiguous and neither is trusted).
void Decide(const std::vector<Candidate>& refined, const IcpInitializerOptions& options,
            const std::vector<internal::Hypothesis>& hypotheses, IcpInitializerResult* result) {
  std::vector<const Candidate*> passing;
  for (const Candidate& c : refined) {
    if (c.passes) passing.push_back(&c);
  }
  std::sort(passing.begin(), passing.end(), [](const Candidate* a, const Candidate* b) {
    return a->quality.plane_fitness_m2 < b->quality.plane_fitness_m2;
  });
  int distinct = 0;
  for (const Candidate* c : passing) {
    bool is_new = true;
    for (const Candidate* earlier : passing) {
      if (earlier == c) break;
      is_new = is_new && internal::AreDistinct(c->T_map_imu, earlier->T_map_imu,
                                               options.distinct_translation_m,
                                               options.distinct_rotation_deg * kDegToRad);
    }
    distinct += is_new ? 1 : 0;
  }
  result->num_accepted_distinct = distinct;
  std::ostringstream os;
  if (passing.empty()) {
    os << "rejected: no hypothesis passed the gates (best: plane fitness "
       << result->best_plane_fitness_m2 << " m^2, fitness " << result->best_fitness_score_m2
       << " m^2, inlier ratio " << result->best_inlier_ratio << ", constraint "
       << result->best_constraint << ")";
  } else if (distinct > 1 && options.reject_ambiguous) {
    os << "rejected: " << distinct << " distinct poses pass the gates (ambiguous view)";
  } else {
    Accept(*passing.front(), hypotheses, result);
    os << "accepted after search: " << Describe(passing.front()->quality);
  }
  result->message = os.str();
}

// Input checks; an empty string when the input can be registered.
std::string CheckInput(const PointCloud& fine_source, const registration::NeighborSearch& map,
                       const Eigen::Isometry3d& T_guess, const IcpInitializerOptions& options) {
  std::ostringstream os;
  if (!T_guess.matrix().allFinite()) {
    os << "rejected: the initial guess is not finite";
  } else if (map.Size() == 0) {
    os << "rejected: the prior map is empty";
  } else if (static_cast<int>(fine_source.size()) < options.min_source_points) {
    os << "rejected: " << fine_source.size() << " finite scan points after downsampling, "
       << options.min_source_points << " needed";
  }
  return os.str();
}

}  // namespace

IcpInitializer::IcpInitializer(const IcpInitializerOptions& options) : options_(options) {
  std::string why;
  HYLO_CHECK(options_.IsValid(&why), "IcpInitializerOptions: " + why);
}

IcpInitializerResult IcpInitializer::Initialize(const PointCloud& scan_imu,
                                                const registration::NeighborSearch& map,
                                                const Eigen::Isometry3d& T_map_imu_guess) const {
  const auto start = std::chrono::steady_clock::now();
  IcpInitializerResult result;
  result.T_map_imu = T_map_imu_guess;
  result.best_T_map_imu = T_map_imu_guess;
  const PointCloud fine_source = internal::Decimate(
      registration::UniformSample(FinitePoints(scan_imu), static_cast<float>(options_.fine_voxel_m)),
      options_.fine_max_points);
  result.num_source_points = fine_source.size();
  const auto finish = [&]() {
    result.elapsed_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
  };
  result.message = CheckInput(fine_source, map, T_map_imu_guess, options_);
  if (!result.message.empty()) return finish();

  Search search(options_, fine_source, map, T_map_imu_guess);
  const std::vector<internal::Hypothesis> hypotheses = internal::MakeHypotheses(options_);
  // The paper's step: fine ICP from the guess.
  const Candidate direct = search.Refine(T_map_imu_guess, 0);
  result.hypotheses_tried = search.tried();
  if (direct.passes) {
    Accept(direct, hypotheses, &result);
    result.num_accepted_distinct = 1;
    result.message = "accepted from the guess: " + Describe(direct.quality);
    return finish();
  }
  SetBest({direct}, &result);
  if (!options_.search_enabled) {
    result.message =
        "rejected: the guess failed (" + Describe(direct.quality) + ") and the search is disabled";
    return finish();
  }
  std::vector<Candidate> refined = search.CoarseToFine(hypotheses);
  result.hypotheses_tried = search.tried();
  SetBest(refined, &result);
  Decide(refined, options_, hypotheses, &result);
  return finish();
}

}  // namespace hylo::localization
