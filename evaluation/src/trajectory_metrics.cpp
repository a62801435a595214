// Time association and alignment of trajectories (errors: trajectory_metrics_error.cpp).
#include "hylo/evaluation/trajectory_metrics.h"

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "hylo/registration/icp.h"

namespace hylo::evaluation {
namespace {

std::vector<TimedPose> SortedByTime(std::vector<TimedPose> poses) {
  std::stable_sort(poses.begin(), poses.end(),
                   [](const TimedPose& a, const TimedPose& b) { return a.t_ns < b.t_ns; });
  return poses;
}

// First reference pose with t >= t_ns.
std::vector<TimedPose>::const_iterator LowerBound(const std::vector<TimedPose>& poses,
                                                  int64_t t_ns) {
  return std::lower_bound(poses.begin(), poses.end(), t_ns,
                          [](const TimedPose& p, int64_t t) { return p.t_ns < t; });
}

bool FindNearest(const std::vector<TimedPose>& reference, int64_t t_ns, int64_t max_dt_ns,
                 Eigen::Isometry3d* pose) {
  if (reference.empty()) return false;
  const auto hi = LowerBound(reference, t_ns);
  auto best = hi == reference.end() ? hi - 1 : hi;
  if (hi != reference.begin() && hi != reference.end() && t_ns - (hi - 1)->t_ns < hi->t_ns - t_ns) {
    best = hi - 1;
  }
  if (std::llabs(best->t_ns - t_ns) > max_dt_ns) return false;
  *pose = best->T_world_body;
  return true;
}

bool FindInterpolated(const std::vector<TimedPose>& reference, int64_t t_ns,
                      const AssociationOptions& options, Eigen::Isometry3d* pose) {
  if (FindNearest(reference, t_ns, 0, pose)) return true;  // an exact stamp
  const auto hi = LowerBound(reference, t_ns);
  if (hi == reference.begin() || hi == reference.end()) return false;
  const int64_t gap_ns = hi->t_ns - (hi - 1)->t_ns;
  const int64_t nearest_ns = std::min(t_ns - (hi - 1)->t_ns, hi->t_ns - t_ns);
  if (gap_ns > options.max_gap_ns && nearest_ns > options.max_dt_ns) return false;
  return InterpolatePose(reference, t_ns, pose);
}

}  // namespace

bool InterpolatePose(const std::vector<TimedPose>& trajectory, int64_t t_ns,
                     Eigen::Isometry3d* pose) {
  if (trajectory.empty() || t_ns < trajectory.front().t_ns || t_ns > trajectory.back().t_ns) {
    return false;
  }
  const auto hi = LowerBound(trajectory, t_ns);
  if (hi->t_ns == t_ns || hi == trajectory.begin()) {
    *pose = hi->T_world_body;
    return true;
  }
  const TimedPose& a = *(hi - 1);
  const TimedPose& b = *hi;
  const double w = static_cast<double>(t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
  const Eigen::Quaterniond qa(a.T_world_body.linear()), qb(b.T_world_body.linear());
  pose->setIdentity();
  pose->linear() = qa.slerp(w, qb).toRotationMatrix();
  pose->translation() = (1.0 - w) * a.T_world_body.translation() + w * b.T_world_body.translation();
  return true;
}

bool AssociationOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  if (max_dt_ns < 0) {
    os << "max_dt_ns = " << max_dt_ns << " must be >= 0";
  } else if (max_gap_ns <= 0) {
    os << "max_gap_ns = " << max_gap_ns << " must be > 0";
  }
  if (why != nullptr) *why = os.str();
  return os.str().empty();
}

AssociatedPoses Associate(const std::vector<TimedPose>& estimate,
                          const std::vector<TimedPose>& reference,
                          const AssociationOptions& options) {
  const std::vector<TimedPose> est = SortedByTime(estimate);
  const std::vector<TimedPose> ref = SortedByTime(reference);
  AssociatedPoses pairs;
  for (std::size_t i = 0; i < est.size(); ++i) {
    if (i > 0 && est[i].t_ns == est[i - 1].t_ns) continue;
    Eigen::Isometry3d T_ref;
    const bool found = options.method == Association::kNearest
                           ? FindNearest(ref, est[i].t_ns, options.max_dt_ns, &T_ref)
                           : FindInterpolated(ref, est[i].t_ns, options, &T_ref);
    if (!found) {
      ++pairs.num_unmatched;
      continue;
    }
    pairs.t_ns.push_back(est[i].t_ns);
    pairs.estimate.push_back(est[i].T_world_body);
    pairs.reference.push_back(T_ref);
  }
  return pairs;
}

AlignmentResult AlignTrajectories(const std::vector<Eigen::Isometry3d>& estimate,
                                  const std::vector<Eigen::Isometry3d>& reference,
                                  Alignment alignment) {
  AlignmentResult result;
  if (estimate.size() != reference.size() || estimate.empty()) {
    result.message = "no associated poses to align";
    return result;
  }
  if (alignment == Alignment::kNone) {
    result.ok = true;
  } else if (alignment == Alignment::kFirstPose) {
    result.T_reference_estimate = reference.front() * estimate.front().inverse();
    result.ok = true;
  } else {
    std::vector<Eigen::Vector3d> source, target;
    for (std::size_t i = 0; i < estimate.size(); ++i) {
      source.push_back(estimate[i].translation());
      target.push_back(reference[i].translation());
    }
    const bool with_scale = alignment == Alignment::kSim3;
    result.ok = registration::UmeyamaAlign(source, target, with_scale, &result.T_reference_estimate,
                                           &result.scale);
    if (!result.ok) {
      result.message = std::string(ToString(alignment)) +
                       " alignment needs >= 3 non-collinear positions (got " +
                       std::to_string(estimate.size()) + " poses); try --align first";
    }
  }
  return result;
}

Eigen::Isometry3d ApplyAlignment(const AlignmentResult& alignment, const Eigen::Isometry3d& pose) {
  Eigen::Isometry3d aligned = Eigen::Isometry3d::Identity();
  const Eigen::Matrix3d& R = alignment.T_reference_estimate.linear();
  aligned.linear() = R * pose.linear();
  aligned.translation() =
      alignment.scale * (R * pose.translation()) + alignment.T_reference_estimate.translation();
  return aligned;
}

const char* ToString(Alignment alignment) {
  switch (alignment) {
    case Alignment::kNone:
      return "none";
    case Alignment::kFirstPose:
      return "first";
    case Alignment::kSE3:
      return "se3";
    case Alignment::kSim3:
      return "sim3";
  }
  return "unknown";
}

}  // namespace hylo::evaluation
