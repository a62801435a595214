// The robust registration's flow: coarse subset, adaptive threshold, alignment, quality check
// and yaw retries (the ICP itself is in robust_registration_icp.cpp).
#include "hylo/estimation/robust_registration.h"

#include <algorithm>
#include <cmath>

#include "hylo/common/check.h"
#include "hylo/common/option_checks.h"
#include "hylo/registration/voxel_filter.h"

namespace hylo::estimation {
namespace {

double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

// T rotated by `yaw_rad` about the map z axis through its own position.
lie::SE3d YawedAboutMapZ(const lie::SE3d& T, double yaw_rad) {
  return lie::SE3d(lie::SO3d::Exp(Eigen::Vector3d(0.0, 0.0, yaw_rad)) * T.so3(), T.translation());
}

}  // namespace

bool RobustRegistrationOptions::IsValid(std::string* why) const {
  return CheckPositive("coarse_voxel_m", coarse_voxel_m, why) &&
         CheckAtLeast("max_iterations", max_iterations, 1, "", why) &&
         CheckPositive("initial_deviation_m", initial_deviation_m, why) &&
         CheckNonNegative("min_deviation_m", min_deviation_m, why) &&
         CheckPositive("final_kernel_m", final_kernel_m, why) &&
         CheckPositive("settle_fraction", settle_fraction, why) &&
         CheckPositive("inlier_distance_m", inlier_distance_m, why) &&
         CheckInRange("min_inlier_share", min_inlier_share, 0.0, 1.0, why) &&
         CheckAtLeast("inlier_history", inlier_history, 1, "", why) &&
         CheckInRange("retry_yaw_range_deg", retry_yaw_range_deg, 0.0, 180.0, why) &&
         CheckPositive("retry_yaw_step_deg", retry_yaw_step_deg, why);
}

RobustRegistration::RobustRegistration(const RobustRegistrationOptions& options)
    : options_(options) {
  std::string why;
  if (!options_.IsValid(&why)) throw InternalError("invalid robust_registration options: " + why);
}

double RobustRegistration::Deviation() const {
  if (num_deviations_ == 0) return options_.initial_deviation_m;
  return std::sqrt(sum_sq_deviation_ / num_deviations_);
}

RobustAlignment RobustRegistration::Align(const PointCloud& points_lidar,
                                          const lie::SE3d& T_map_lidar_predicted,
                                          const registration::PlaneMatcher& planes) {
  const auto voxel = static_cast<float>(options_.coarse_voxel_m);
  const PointCloud subset = registration::UniformSample(points_lidar, voxel);
  max_range_m_ = 0.0;
  for (const Eigen::Vector3f& p : subset) max_range_m_ = std::max<double>(max_range_m_, p.norm());
  RobustAlignment out;
  out.deviation_m = Deviation();
  out.subset_points = subset.size();
  out.reference_ratio = Median({inlier_history_.begin(), inlier_history_.end()});
  // KISS-ICP: correspondences within 3σ of the model deviation, kernel σ/3.
  PlaneIcpSettings settings;
  settings.gate_m = 3.0 * out.deviation_m;
  settings.kernel_m = out.deviation_m / 3.0;
  settings.final_kernel_m = options_.final_kernel_m;
  settings.max_iterations = options_.max_iterations;
  settings.settle_fraction = options_.settle_fraction;
  settings.inlier_m = options_.inlier_distance_m;
  // One alignment of `points` from `start`; its inlier fraction.
  const auto align = [&](const PointCloud& points, const lie::SE3d& start,
                         lie::SE3d* T) {
    const PlaneIcpResult icp = AlignPointToPlane(points, start, planes, settings);
    out.iterations += icp.iterations;
    ++out.attempts;
    *T = icp.T_map_lidar;
    return static_cast<double>(icp.inliers) / std::max<double>(points.size(), 1);
  };
  out.inlier_ratio = align(subset, T_map_lidar_predicted, &out.T_map_lidar);
  // With no accepted scan to compare with yet (the first alignment of a run, against a map of
  // one scan, from a prediction that knows no velocity) the hypotheses are always tried.
  const bool first = inlier_history_.empty();
  const auto holds = [&] {
    return out.inlier_ratio >= options_.min_inlier_share * out.reference_ratio;
  };
  if (first || !holds()) {
    // Retry wider: every yaw hypothesis aligned on a sparser subset (twice the voxel, about
    // an eighth of the points: which basin, not the last centimetre, is what they decide),
    // then the one with the most inliers refined on the subset.
    const PointCloud sparse = registration::UniformSample(subset, 2.0f * voxel);
    const double step = options_.retry_yaw_step_deg * M_PI / 180.0;
    const double range = options_.retry_yaw_range_deg * M_PI / 180.0;
    double best_ratio = -1.0;
    lie::SE3d best, T;
    for (double yaw = step; yaw <= range + 1e-9; yaw += step) {
      for (double sign : {1.0, -1.0}) {
        const double ratio = align(sparse, YawedAboutMapZ(T_map_lidar_predicted, sign * yaw), &T);
        if (ratio > best_ratio) {
          best_ratio = ratio;
          best = T;
        }
      }
    }
    const double ratio = best_ratio < 0.0 ? 0.0 : align(subset, best, &T);
    if (ratio > out.inlier_ratio) {
      out.inlier_ratio = ratio;
      out.T_map_lidar = T;
    }
  }
  out.passed = first || holds();
  last_ratio_ = out.inlier_ratio;
  return out;
}

void RobustRegistration::Observe(const lie::SE3d& T_map_lidar_predicted,
                                 const lie::SE3d& T_map_lidar_final) {
  const double e =
      ModelDeviation(T_map_lidar_predicted.Inverse() * T_map_lidar_final, max_range_m_);
  if (e > options_.min_deviation_m) {
    sum_sq_deviation_ += e * e;
    ++num_deviations_;
  }
  // The check compares like with like: the inlier fraction of the coarse alignment itself.
  inlier_history_.push_back(last_ratio_);
  while (static_cast<int>(inlier_history_.size()) > options_.inlier_history) {
    inlier_history_.pop_front();
  }
}

}  // namespace hylo::estimation
