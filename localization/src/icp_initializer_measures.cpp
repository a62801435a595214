// The ICP initializer's hypothesis grid and acceptance measures (see icp_initializer.h).
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "hylo/common/check.h"
#include "hylo/registration/plane_matcher.h"
#include "icp_initializer_internal.h"

namespace hylo::localization {
namespace internal {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

// Offsets {0, +-step, +-2 step, ...} within +-range (0 alone when range is 0).
std::vector<double> SymmetricSteps(double range, double step) {
  std::vector<double> steps{0.0};
  for (int k = 1; k * step <= range + 1e-9; ++k) {
    steps.push_back(k * step);
    steps.push_back(-k * step);
  }
  return steps;
}

}  // namespace

PointCloud Decimate(const PointCloud& cloud, int max_points) {
  const std::size_t limit = static_cast<std::size_t>(max_points);
  if (cloud.size() <= limit) return cloud;
  PointCloud kept;
  kept.reserve(limit);
  for (std::size_t i = 0; i < limit; ++i) kept.push_back(cloud[i * cloud.size() / limit]);
  return kept;
}

std::vector<Hypothesis> MakeHypotheses(const IcpInitializerOptions& options) {
  const std::vector<double> yaws = SymmetricSteps(options.yaw_range_deg, options.yaw_step_deg);
  const std::vector<double> xy = SymmetricSteps(options.position_range_m, options.position_step_m);
  std::vector<std::pair<double, Hypothesis>> ranked;
  for (double yaw_deg : yaws) {
    for (double dx : xy) {
      for (double dy : xy) {
        // Normalised offset: a 10 deg yaw error costs as much as a 1 m position error when the
        // ranges are 30 deg and 3 m; the guess itself (all zero) comes first.
        const double yaw_term = options.yaw_range_deg > 0.0 ? yaw_deg / options.yaw_range_deg : 0;
        const double pos_range = options.position_range_m > 0.0 ? options.position_range_m : 1.0;
        const double cost = std::hypot(yaw_term, std::hypot(dx, dy) / pos_range);
        ranked.push_back({cost, Hypothesis{dx, dy, yaw_deg * kDegToRad}});
      }
    }
  }
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Hypothesis> hypotheses;
  for (const auto& entry : ranked) {
    if (static_cast<int>(hypotheses.size()) >= options.max_hypotheses) break;
    hypotheses.push_back(entry.second);
  }
  return hypotheses;
}

Eigen::Isometry3d ApplyHypothesis(const Eigen::Isometry3d& T_map_imu_guess, const Hypothesis& h) {
  Eigen::Isometry3d T = T_map_imu_guess;
  T.linear() = Eigen::AngleAxisd(h.dyaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
               T_map_imu_guess.linear();
  T.translation() += Eigen::Vector3d(h.dx_m, h.dy_m, 0.0);
  return T;
}

PoseQuality MeasureOverlap(const PointCloud& source, const registration::NeighborSearch& map,
                           const Eigen::Isometry3d& T_map_source,
                           const IcpInitializerOptions& options) {
  const double fitness_range_sq = options.fitness_max_range_m * options.fitness_max_range_m;
  const double inlier_sq = options.inlier_distance_m * options.inlier_distance_m;
  const float search_m =
      static_cast<float>(std::max(options.fitness_max_range_m, options.inlier_distance_m));
  std::size_t num_finite = 0, num_inliers = 0, num_fitness = 0;
  double sum_sq = 0.0;
  std::vector<registration::Neighbor> neighbors;
  for (const Eigen::Vector3f& p : source) {
    if (!p.allFinite()) continue;
    ++num_finite;
    map.KNearest((T_map_source * p.cast<double>()).cast<float>(), 1, search_m, &neighbors);
    if (neighbors.empty()) continue;
    const double d_sq = neighbors.front().squared_distance;
    if (d_sq <= inlier_sq) ++num_inliers;
    if (d_sq <= fitness_range_sq) {
      sum_sq += d_sq;
      ++num_fitness;
    }
  }
  PoseQuality quality;
  quality.fitness_score_m2 = num_fitness > 0 ? sum_sq / static_cast<double>(num_fitness)
                                             : std::numeric_limits<double>::infinity();
  quality.inlier_ratio =
      num_finite > 0 ? static_cast<double>(num_inliers) / static_cast<double>(num_finite) : 0.0;
  return quality;
}

namespace {

// Weakest eigenvalue of the normalised point-to-plane information (see MeasureQuality).
double Constraint(const std::vector<Eigen::Vector3d>& points,
                  const std::vector<Eigen::Vector3d>& normals, std::size_t num_finite) {
  if (points.size() < 6) return 0.0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& q : points) centroid += q;
  centroid /= static_cast<double>(points.size());
  double mean_sq_radius = 0.0;
  for (const Eigen::Vector3d& q : points) mean_sq_radius += (q - centroid).squaredNorm();
  const double length = std::sqrt(mean_sq_radius / points.size());
  if (!(length > 0.0)) return 0.0;
  Eigen::Matrix<double, 6, 6> information = Eigen::Matrix<double, 6, 6>::Zero();
  for (std::size_t i = 0; i < points.size(); ++i) {
    Eigen::Matrix<double, 6, 1> jacobian;
    jacobian << (points[i] - centroid).cross(normals[i]) / length, normals[i];
    information += jacobian * jacobian.transpose();
  }
  information /= static_cast<double>(num_finite);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> solver(information);
  return std::max(0.0, solver.eigenvalues()(0));
}

}  // namespace

bool LocalPlane(const registration::NeighborSearch& map, const Eigen::Vector3d& q_map, double max_nn_m,
                std::vector<registration::Neighbor>* neighbors, double* nn_squared_m2, registration::Plane* plane) {
  const float search_m = std::max(kPlaneRadiusM, static_cast<float>(max_nn_m));
  map.KNearest(q_map.cast<float>(), kPlaneNeighbors, search_m, neighbors);
  if (neighbors->empty()) return false;
  *nn_squared_m2 = neighbors->front().squared_distance;
  if (*nn_squared_m2 > max_nn_m * max_nn_m) return false;
  // The plane of the neighbours within kPlaneRadiusM (the search may reach farther).
  while (!neighbors->empty() &&
         neighbors->back().squared_distance > kPlaneRadiusM * kPlaneRadiusM) {
    neighbors->pop_back();
  }
  return neighbors->size() == static_cast<std::size_t>(kPlaneNeighbors) &&
         registration::FitPlane(*neighbors, kPlanarityM, plane);
}

PoseQuality MeasureQuality(const PointCloud& source, const registration::NeighborSearch& map,
                           const Eigen::Isometry3d& T_map_source,
                           const IcpInitializerOptions& options) {
  const double fitness_range_sq = options.fitness_max_range_m * options.fitness_max_range_m;
  const double inlier_sq = options.inlier_distance_m * options.inlier_distance_m;
  // One search reaches every measure's range (the plane's only for the inliers).
  const double reach_m = std::max(options.fitness_max_range_m, options.inlier_distance_m);
  std::size_t num_finite = 0, num_inliers = 0, num_fitness = 0;
  double sum_sq = 0.0, plane_sum_sq = 0.0;
  std::vector<Eigen::Vector3d> points, normals;  // inliers with a local plane
  std::vector<registration::Neighbor> neighbors;
  for (const Eigen::Vector3f& p : source) {
    if (!p.allFinite()) continue;
    ++num_finite;
    const Eigen::Vector3d q = T_map_source * p.cast<double>();
    double d_sq = std::numeric_limits<double>::infinity();
    registration::Plane plane;
    const bool has_plane = LocalPlane(map, q, reach_m, &neighbors, &d_sq, &plane);
    if (d_sq <= fitness_range_sq) {
      sum_sq += d_sq;
      ++num_fitness;
    }
    if (d_sq > inlier_sq) continue;
    ++num_inliers;
    if (!has_plane) continue;
    const double r = plane.Distance(q);
    plane_sum_sq += r * r;
    points.push_back(q);
    normals.push_back(plane.normal);
  }
  PoseQuality quality;
  quality.fitness_score_m2 = num_fitness > 0 ? sum_sq / static_cast<double>(num_fitness)
                                             : std::numeric_limits<double>::infinity();
  quality.plane_fitness_m2 =
      points.empty() ? 1.0 : plane_sum_sq / static_cast<double>(points.size());
  quality.inlier_ratio =
      num_finite > 0 ? static_cast<double>(num_inliers) / static_cast<double>(num_finite) : 0.0;
  quality.constraint = Constraint(points, normals, num_finite);
  return quality;
}

bool AreDistinct(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b, double translation_m,
                 double rotation_rad) {
  const Eigen::Isometry3d delta = a.inverse() * b;
  return delta.translation().norm() > translation_m ||
         Eigen::AngleAxisd(delta.linear()).angle() > rotation_rad;
}

}  // namespace internal

Eigen::Isometry3d GuessFromGravity(const Eigen::Vector3d& position_map, double yaw_rad,
                                   const Eigen::Vector3d& mean_specific_force_imu) {
  HYLO_CHECK(mean_specific_force_imu.allFinite() && mean_specific_force_imu.norm() > 0.0,
             "the mean specific force must be finite and non-zero");
  HYLO_CHECK(position_map.allFinite() && std::isfinite(yaw_rad), "non-finite guess");
  // At rest the accelerometer measures -g, i.e. the map's +z seen in the IMU frame.
  const Eigen::Matrix3d R_level =
      Eigen::Quaterniond::FromTwoVectors(mean_specific_force_imu, Eigen::Vector3d::UnitZ())
          .toRotationMatrix();
  Eigen::Isometry3d T_map_imu = Eigen::Isometry3d::Identity();
  T_map_imu.linear() =
      Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R_level;
  T_map_imu.translation() = position_map;
  return T_map_imu;
}

}  // namespace hylo::localization
