#pragma once
// What every back-end's lidar update shares: the measurement model's settings (section
// `lidar_update:` of a run configuration) and the report of how a scan fits the map at the
// final state (residuals, degeneracy), so both back-ends judge a scan the same way.

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "hylo/estimation/estimator.h"

namespace hylo::estimation {

struct LidarUpdateOptions {
  /// σ of one point-to-plane residual, m (> 0). Not the sensor's range noise (1-2 cm): the
  /// planes come from a map of the same scans, and the errors of neighbouring matches are
  /// correlated, so the residuals carry less information than N independent 1-2 cm ones.
  /// Weighted as 2 cm, the first metre of motion pulled the attitude ~0.5° off the IMU's
  /// gravity and the rest of the drive carried it as vertical drift (scenario matrix: worst
  /// 0.89 % with a consumer IMU). With zero-velocity updates at standstill (standstill.h) both
  /// halves of the scenario matrix pick 5 cm among 3, 4 and 5, and each half's worst drift falls
  /// where the other half chose it (README, scenario matrix).
  double lidar_noise_m = 0.05;
  int min_matches = 20;         ///< fewer matched points: no correction, scan reported (>= 6)
  /// Degeneracy: smallest eigenvalue of Σ n nᵀ / N (translation information per match, 0..1)
  /// below this flags the scan degenerate (a plane or corridor leaves a direction unseen),
  /// (>= 0).
  double min_translation_information = 0.02;
  /// ... or of Σ (q×n)(q×n)ᵀ / N (rotation information per match, q the point in the IMU
  /// frame), m² (>= 0).
  double min_rotation_information = 0.05;

  bool IsValid(std::string* why) const;
};

/// The fit of one scan's plane matches at the final state, filled point by point and turned
/// into the UpdateSummary's residuals, RMS and degeneracy figures.
class LidarFit {
 public:
  /// A scan of `num_points` points, none matched yet.
  explicit LidarFit(std::size_t num_points);

  /// Point `index` (IMU frame `point_imu`, m) matched a plane of normal `normal_imu` (IMU
  /// frame) with residual `residual_m`. `in_update`: it passed the residual gate and so
  /// constrained the update (only those count for the RMS and the information).
  void Add(std::size_t index, const Eigen::Vector3d& point_imu, const Eigen::Vector3d& normal_imu,
           double residual_m, bool in_update);

  /// Moves the residuals into `summary` and sets its RMS and degeneracy figures (and the
  /// message when degenerate).
  void Report(const LidarUpdateOptions& options, UpdateSummary* summary);

 private:
  std::vector<float> residuals_m_;
  Eigen::Matrix3d translation_information_ = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d rotation_information_ = Eigen::Matrix3d::Zero();
  double sum_squared_residual_ = 0.0;
  std::size_t num_in_update_ = 0;
};

/// "too few plane matches (N < M): prediction only", the message of an update not applied.
std::string TooFewMatchesMessage(std::size_t matches, int min_matches);

}  // namespace hylo::estimation
