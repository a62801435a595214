// Point-to-point ICP: alternate nearest-neighbour pairing and the closed-form SVD step.
#include "hylo/registration/icp.h"

#include <cmath>
#include <sstream>

namespace hylo::registration {
namespace {

struct Correspondences {
  std::vector<Eigen::Vector3d> source;  ///< source frame
  std::vector<Eigen::Vector3d> target;  ///< target frame
};

// Pairs each finite source point, moved by T, with its nearest target point within range.
Correspondences FindCorrespondences(const PointCloud& source, const NeighborSearch& target,
                                    const Eigen::Isometry3d& T_target_source, double range_m) {
  Correspondences pairs;
  std::vector<Neighbor> neighbors;
  for (const Eigen::Vector3f& p : source) {
    if (!p.allFinite()) continue;
    const Eigen::Vector3d p_source = p.cast<double>();
    const Eigen::Vector3f q = (T_target_source * p_source).cast<float>();
    target.KNearest(q, 1, static_cast<float>(range_m), &neighbors);
    if (neighbors.empty()) continue;
    pairs.source.push_back(p_source);
    pairs.target.push_back(neighbors.front().point.cast<double>());
  }
  return pairs;
}

bool HasFinitePoint(const PointCloud& cloud) {
  for (const Eigen::Vector3f& p : cloud) {
    if (p.allFinite()) return true;
  }
  return false;
}

IcpSummary Stop(IcpSummary summary, IcpStatus status, const std::string& detail) {
  summary.status = status;
  summary.converged = status == IcpStatus::kConverged;
  std::ostringstream os;
  os << ToString(status) << " after " << summary.iterations << " iterations";
  if (!detail.empty()) os << ": " << detail;
  summary.message = os.str();
  return summary;
}

}  // namespace

const char* ToString(IcpStatus status) {
  switch (status) {
    case IcpStatus::kConverged:
      return "converged";
    case IcpStatus::kMaxIterations:
      return "max iterations reached";
    case IcpStatus::kInvalidOptions:
      return "invalid options";
    case IcpStatus::kEmptyInput:
      return "empty input";
    case IcpStatus::kNonFiniteGuess:
      return "non-finite initial guess";
    case IcpStatus::kTooFewCorrespondences:
      return "too few correspondences";
    case IcpStatus::kDegenerate:
      return "degenerate correspondences";
  }
  return "unknown";
}

bool Icp::Options::IsValid(std::string* why) const {
  std::ostringstream os;
  if (max_iterations < 1) {
    os << "max_iterations = " << max_iterations << " must be >= 1";
  } else if (!(max_correspondence_distance_m > 0.0)) {
    os << "max_correspondence_distance_m = " << max_correspondence_distance_m << " must be > 0";
  } else if (!(translation_epsilon_m > 0.0)) {
    os << "translation_epsilon_m = " << translation_epsilon_m << " must be > 0";
  } else if (!(rotation_epsilon_rad > 0.0)) {
    os << "rotation_epsilon_rad = " << rotation_epsilon_rad << " must be > 0";
  } else if (min_correspondences < 3) {
    os << "min_correspondences = " << min_correspondences << " must be >= 3";
  } else if (!(fitness_max_range_m > 0.0)) {
    os << "fitness_max_range_m = " << fitness_max_range_m << " must be > 0";
  }
  if (why != nullptr) *why = os.str();
  return os.str().empty();
}

IcpSummary Icp::Align(const PointCloud& source, const NeighborSearch& target,
                      const Eigen::Isometry3d& T_target_source_guess) const {
  IcpSummary summary;
  summary.T_target_source = T_target_source_guess;
  std::string why;
  if (!options_.IsValid(&why)) return Stop(summary, IcpStatus::kInvalidOptions, why);
  if (!T_target_source_guess.matrix().allFinite()) {
    return Stop(summary, IcpStatus::kNonFiniteGuess, "");
  }
  if (!HasFinitePoint(source) || target.Size() == 0) {
    return Stop(summary, IcpStatus::kEmptyInput, "source has no finite point or target is empty");
  }
  const double range_m = options_.max_correspondence_distance_m;
  IcpStatus status = IcpStatus::kMaxIterations;
  std::string detail;
  Eigen::Isometry3d T = T_target_source_guess;
  while (summary.iterations < options_.max_iterations) {
    const Correspondences pairs = FindCorrespondences(source, target, T, range_m);
    if (pairs.source.size() < static_cast<std::size_t>(options_.min_correspondences)) {
      status = IcpStatus::kTooFewCorrespondences;
      detail =
          std::to_string(pairs.source.size()) + " pairs within " + std::to_string(range_m) + " m";
      break;
    }
    // Arun/Umeyama: the whole transform in closed form from the current pairs.
    Eigen::Isometry3d T_next;
    if (!UmeyamaAlign(pairs.source, pairs.target, false, &T_next)) {
      status = IcpStatus::kDegenerate;
      break;
    }
    const Eigen::Isometry3d increment = T_next * T.inverse();
    T = T_next;
    ++summary.iterations;
    const double angle = Eigen::AngleAxisd(increment.linear()).angle();
    if (increment.translation().norm() < options_.translation_epsilon_m &&
        angle < options_.rotation_epsilon_rad) {
      status = IcpStatus::kConverged;
      break;
    }
  }
  summary.T_target_source = T;
  const FitnessSummary at_result = FitnessScore(source, target, T, range_m);
  summary.num_correspondences = at_result.num_within;
  summary.inlier_ratio = at_result.inlier_ratio;
  summary.fitness_score =
      options_.fitness_max_range_m == range_m
          ? at_result.fitness_score
          : FitnessScore(source, target, T, options_.fitness_max_range_m).fitness_score;
  return Stop(summary, status, detail);
}

}  // namespace hylo::registration
