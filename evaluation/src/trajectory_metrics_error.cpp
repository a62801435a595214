// ATE and RPE over associated poses (association and alignment: trajectory_metrics.cpp).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "hylo/evaluation/trajectory_metrics.h"

namespace hylo::evaluation {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

double AngleDeg(const Eigen::Matrix3d& R) { return Eigen::AngleAxisd(R).angle() * kRadToDeg; }

// Copies one statistics block into a result's flat fields (ATE and RPE share the layout).
template <typename Result>
void FillTranslation(const ErrorStatistics& s, Result* r) {
  r->rmse_m = s.rmse;
  r->mean_m = s.mean;
  r->median_m = s.median;
  r->std_m = s.std;
  r->max_m = s.max;
}
template <typename Result>
void FillRotation(const ErrorStatistics& s, Result* r) {
  r->rotation_rmse_deg = s.rmse;
  r->rotation_mean_deg = s.mean;
  r->rotation_median_deg = s.median;
  r->rotation_max_deg = s.max;
}

double PathLength(const std::vector<Eigen::Isometry3d>& poses) {
  double length = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    length += (poses[i].translation() - poses[i - 1].translation()).norm();
  }
  return length;
}

void FillEndDrift(const AssociatedPoses& pairs, AteResult* ate) {
  ate->path_length_m = PathLength(pairs.reference);
  const Eigen::Isometry3d T_first = pairs.reference.front() * pairs.estimate.front().inverse();
  ate->end_drift_m =
      ((T_first * pairs.estimate.back()).translation() - pairs.reference.back().translation())
          .norm();
  ate->end_drift_percent =
      ate->path_length_m > 0.0 ? 100.0 * ate->end_drift_m / ate->path_length_m : 0.0;
}

// Index pairs (i, j) at the requested delta.
std::vector<std::pair<std::size_t, std::size_t>> DeltaPairs(const AssociatedPoses& poses,
                                                            const RpeOptions& options) {
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  const std::size_t n = poses.reference.size();
  if (options.unit == DeltaUnit::kFrames) {
    const std::size_t step = static_cast<std::size_t>(std::llround(options.delta));
    for (std::size_t i = 0; i + step < n; ++i) pairs.emplace_back(i, i + step);
    return pairs;
  }
  // Cumulative reference distance; for each i the first j that is delta metres further on.
  std::vector<double> distance(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    distance[i] = distance[i - 1] +
                  (poses.reference[i].translation() - poses.reference[i - 1].translation()).norm();
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto j =
        std::lower_bound(distance.begin() + i, distance.end(), distance[i] + options.delta);
    if (j == distance.end()) break;
    pairs.emplace_back(i, static_cast<std::size_t>(j - distance.begin()));
  }
  return pairs;
}

}  // namespace

ErrorStatistics ComputeStatistics(std::vector<double> values) {
  ErrorStatistics s;
  s.count = values.size();
  if (values.empty()) return s;
  const double n = static_cast<double>(values.size());
  double sum = 0.0, sum_sq = 0.0;
  for (double v : values) {
    sum += v;
    sum_sq += v * v;
    s.max = std::max(s.max, v);
  }
  s.mean = sum / n;
  s.rmse = std::sqrt(sum_sq / n);
  double sum_dev = 0.0;
  for (double v : values) sum_dev += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(sum_dev / n);
  std::sort(values.begin(), values.end());
  const std::size_t mid = values.size() / 2;
  s.median = values.size() % 2 == 1 ? values[mid] : 0.5 * (values[mid - 1] + values[mid]);
  return s;
}

bool AteOptions::IsValid(std::string* why) const { return association.IsValid(why); }

bool RpeOptions::IsValid(std::string* why) const {
  if (!association.IsValid(why)) return false;
  std::ostringstream os;
  if (unit == DeltaUnit::kFrames && !(delta >= 1.0 && std::floor(delta) == delta)) {
    os << "delta = " << delta << " must be an integer >= 1 (frames)";
  } else if (unit == DeltaUnit::kMeters && !(delta > 0.0 && std::isfinite(delta))) {
    os << "delta = " << delta << " must be finite and > 0 (m)";
  }
  if (why != nullptr) *why = os.str();
  return os.str().empty();
}

AteResult ComputeAte(const std::vector<TimedPose>& estimate,
                     const std::vector<TimedPose>& reference, const AteOptions& options) {
  AteResult ate;
  if (!options.IsValid(&ate.message)) return ate;
  const AssociatedPoses pairs = Associate(estimate, reference, options.association);
  ate.num_poses = pairs.t_ns.size();
  ate.num_unmatched = pairs.num_unmatched;
  if (pairs.t_ns.empty()) {
    ate.message = "no estimated pose has a reference pose within the time tolerance";
    return ate;
  }
  const AlignmentResult alignment =
      AlignTrajectories(pairs.estimate, pairs.reference, options.alignment);
  if (!alignment.ok) {
    ate.message = alignment.message;
    return ate;
  }
  ate.T_reference_estimate = alignment.T_reference_estimate;
  ate.scale = alignment.scale;
  std::vector<double> rotation_deg;
  for (std::size_t i = 0; i < pairs.t_ns.size(); ++i) {
    const Eigen::Isometry3d aligned = ApplyAlignment(alignment, pairs.estimate[i]);
    ate.translation_errors_m.push_back(
        (aligned.translation() - pairs.reference[i].translation()).norm());
    rotation_deg.push_back(AngleDeg(pairs.reference[i].linear().transpose() * aligned.linear()));
  }
  ate.t_ns = pairs.t_ns;
  FillTranslation(ComputeStatistics(ate.translation_errors_m), &ate);
  FillRotation(ComputeStatistics(rotation_deg), &ate);
  FillEndDrift(pairs, &ate);
  ate.ok = true;
  return ate;
}

RpeResult ComputeRpe(const std::vector<TimedPose>& estimate,
                     const std::vector<TimedPose>& reference, const RpeOptions& options) {
  RpeResult rpe;
  if (!options.IsValid(&rpe.message)) return rpe;
  const AssociatedPoses poses = Associate(estimate, reference, options.association);
  rpe.num_poses = poses.t_ns.size();
  std::vector<double> translation_m, rotation_deg;
  for (const auto& [i, j] : DeltaPairs(poses, options)) {
    const Eigen::Isometry3d delta_ref = poses.reference[i].inverse() * poses.reference[j];
    const Eigen::Isometry3d delta_est = poses.estimate[i].inverse() * poses.estimate[j];
    const Eigen::Isometry3d error = delta_ref.inverse() * delta_est;  // Sturm et al. Eq. (5)
    translation_m.push_back(error.translation().norm());
    rotation_deg.push_back(AngleDeg(error.linear()));
  }
  rpe.num_pairs = translation_m.size();
  if (translation_m.empty()) {
    std::ostringstream os;
    os << "no pose pair " << options.delta
       << (options.unit == DeltaUnit::kFrames ? " frames" : " m") << " apart among "
       << rpe.num_poses << " associated poses";
    rpe.message = os.str();
    return rpe;
  }
  FillTranslation(ComputeStatistics(translation_m), &rpe);
  FillRotation(ComputeStatistics(rotation_deg), &rpe);
  rpe.ok = true;
  return rpe;
}

}  // namespace hylo::evaluation
