#include "hylo/registration/plane_matcher.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "hylo/common/check.h"
#include "hylo/registration/covariance_eigen.h"

namespace hylo::registration {

bool PlaneMatcherOptions::IsValid(std::string* why) const {
  std::ostringstream os;
  if (num_neighbors < 3) {
    os << "num_neighbors = " << num_neighbors << ": must be >= 3 (a plane needs 3 points)";
  } else if (line_like_neighbors < 0) {
    os << "line_like_neighbors = " << line_like_neighbors << ": must be >= 0";
  } else if (!(line_like_ratio > 0.0 && line_like_ratio <= 1.0)) {
    os << "line_like_ratio = " << line_like_ratio << ": must be in (0, 1]";
  } else if (!(max_neighbor_distance_m > 0.0) || !std::isfinite(max_neighbor_distance_m)) {
    os << "max_neighbor_distance_m = " << max_neighbor_distance_m << ": must be finite and > 0";
  } else if (!(planarity_threshold_m > 0.0) || !std::isfinite(planarity_threshold_m)) {
    os << "planarity_threshold_m = " << planarity_threshold_m << ": must be finite and > 0";
  } else if (!(range_gate_factor > 0.0) || !std::isfinite(range_gate_factor)) {
    os << "range_gate_factor = " << range_gate_factor << ": must be finite and > 0";
  } else {
    return true;
  }
  if (why != nullptr) *why = os.str();
  return false;
}

bool FitPlane(const std::vector<Neighbor>& points, double planarity_threshold_m, Plane* plane,
              NeighborSpread* spread) {
  if (spread != nullptr) *spread = NeighborSpread{};
  if (points.size() < 3) return false;
  // Centre on the first point before accumulating so that large map coordinates do not
  // cancel in the covariance.
  const Eigen::Vector3d ref = points.front().point.cast<double>();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d outer = Eigen::Matrix3d::Zero();
  for (const Neighbor& n : points) {
    const Eigen::Vector3d q = n.point.cast<double>() - ref;
    sum += q;
    outer += q * q.transpose();
  }
  const double count = static_cast<double>(points.size());
  const Eigen::Vector3d mean = sum / count;
  const Eigen::Matrix3d cov = outer / count - mean * mean.transpose();
  Eigen::Vector3d normal, eigenvalues;
  CovarianceEigen(cov, &normal, &eigenvalues);
  if (spread != nullptr) {
    spread->across_m = std::sqrt(std::max(eigenvalues(1), 0.0));
    spread->along_m = std::sqrt(std::max(eigenvalues(2), 0.0));
  }
  // A line (two small eigenvalues) has no defined normal.
  if (!(eigenvalues(1) > 1e-8) || !normal.allFinite()) return false;
  const Eigen::Vector3d centroid = ref + mean;
  const double offset = -normal.dot(centroid);
  for (const Neighbor& n : points) {
    if (std::abs(normal.dot(n.point.cast<double>()) + offset) > planarity_threshold_m) {
      return false;
    }
  }
  plane->normal = normal;
  plane->offset = offset;
  return true;
}

PlaneMatcher::PlaneMatcher(const NeighborSearch& map, const PlaneMatcherOptions& options)
    : map_(map), options_(options) {
  std::string why;
  if (!options_.IsValid(&why)) throw InternalError("invalid options: " + why);
}

bool PlaneMatcher::Match(const Eigen::Vector3d& point_map, Plane* plane) const {
  thread_local std::vector<Neighbor> neighbors;
  const Eigen::Vector3f query = point_map.cast<float>();
  const auto reach_m = static_cast<float>(options_.max_neighbor_distance_m);
  map_.KNearest(query, options_.num_neighbors, reach_m, &neighbors);
  if (static_cast<int>(neighbors.size()) < options_.num_neighbors) return false;
  if (options_.line_like_neighbors <= options_.num_neighbors) {
    return FitPlane(neighbors, options_.planarity_threshold_m, plane);
  }
  NeighborSpread spread;
  const bool fitted = FitPlane(neighbors, options_.planarity_threshold_m, plane, &spread);
  const bool line_like = spread.across_m < options_.planarity_threshold_m &&
                         spread.across_m < options_.line_like_ratio * spread.along_m;
  if (!line_like) return fitted;
  // Along a line: reach across it (see PlaneMatcherOptions::line_like_neighbors).
  map_.KNearest(query, options_.line_like_neighbors, reach_m, &neighbors);
  if (static_cast<int>(neighbors.size()) < options_.line_like_neighbors) return false;
  return FitPlane(neighbors, options_.planarity_threshold_m, plane);
}

bool PlaneMatcher::PassesGate(double residual_m, double range_m) const {
  return std::abs(residual_m) < options_.range_gate_factor * std::sqrt(std::max(range_m, 1e-3));
}

}  // namespace hylo::registration
