// The closed-form alignment step shared by ICP and trajectory alignment, and the fitness score.
#include <Eigen/SVD>
#include <cmath>

#include "hylo/registration/icp.h"

namespace hylo::registration {
namespace {

// Relative size below which a singular value of the cross-covariance counts as zero: a rank-1
// covariance (collinear points) leaves the rotation about the line free.
constexpr double kRankTolerance = 1e-9;

bool AllFinite(const std::vector<Eigen::Vector3d>& points) {
  for (const Eigen::Vector3d& p : points) {
    if (!p.allFinite()) return false;
  }
  return true;
}

Eigen::Vector3d Mean(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) sum += p;
  return sum / static_cast<double>(points.size());
}

}  // namespace

bool UmeyamaAlign(const std::vector<Eigen::Vector3d>& source,
                  const std::vector<Eigen::Vector3d>& target, bool with_scale, Eigen::Isometry3d* T,
                  double* scale) {
  if (source.size() != target.size() || source.size() < 3) return false;
  if (!AllFinite(source) || !AllFinite(target)) return false;
  const double n = static_cast<double>(source.size());
  const Eigen::Vector3d mean_source = Mean(source);
  const Eigen::Vector3d mean_target = Mean(target);
  // Umeyama Eq. (38): cross-covariance of the centred sets, and Eq. (36): source variance.
  Eigen::Matrix3d sigma = Eigen::Matrix3d::Zero();
  double variance_source = 0.0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const Eigen::Vector3d s = source[i] - mean_source;
    sigma += (target[i] - mean_target) * s.transpose();
    variance_source += s.squaredNorm();
  }
  sigma /= n;
  variance_source /= n;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sigma, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d d = svd.singularValues();
  if (!(d(0) > 0.0) || d(1) <= kRankTolerance * d(0)) return false;
  // Eq. (39)/(43): flip the smallest axis when U V^T would be a reflection.
  Eigen::Vector3d s_diag = Eigen::Vector3d::Ones();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) s_diag(2) = -1.0;
  const Eigen::Matrix3d R = svd.matrixU() * s_diag.asDiagonal() * svd.matrixV().transpose();
  double c = 1.0;
  if (with_scale) {
    if (!(variance_source > 0.0)) return false;
    c = d.dot(s_diag) / variance_source;  // Eq. (42)
  }
  T->setIdentity();
  T->linear() = R;
  T->translation() = mean_target - c * R * mean_source;  // Eq. (41)
  if (scale != nullptr) *scale = c;
  return true;
}

FitnessSummary FitnessScore(const PointCloud& source, const NeighborSearch& target,
                            const Eigen::Isometry3d& T_target_source, double max_range_m) {
  FitnessSummary summary;
  const float search_range = std::isfinite(max_range_m) ? static_cast<float>(max_range_m)
                                                        : std::numeric_limits<float>::max();
  std::vector<Neighbor> neighbors;
  double sum_sq = 0.0;
  for (const Eigen::Vector3f& p : source) {
    if (!p.allFinite()) continue;
    ++summary.num_source;
    const Eigen::Vector3d q = T_target_source * p.cast<double>();
    target.KNearest(q.cast<float>(), 1, search_range, &neighbors);
    if (neighbors.empty()) continue;
    const double d2 = (neighbors.front().point.cast<double>() - q).squaredNorm();
    if (d2 > max_range_m * max_range_m) continue;
    sum_sq += d2;
    ++summary.num_within;
  }
  if (summary.num_within > 0) summary.fitness_score = sum_sq / summary.num_within;
  if (summary.num_source > 0) {
    summary.inlier_ratio = static_cast<double>(summary.num_within) / summary.num_source;
  }
  return summary;
}

}  // namespace hylo::registration
