#pragma once
// Point-to-point ICP (Besl & McKay 1992) with the closed-form SVD step of Arun et al. 1987 /
// Umeyama 1991, and PCL's Euclidean fitness score. The target is reached only through
// NeighborSearch, so the same code runs on the ikd-tree and on the brute-force reference.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/registration/neighbor_search.h"

namespace hylo::registration {

/// The similarity (or rigid) transform minimising sum_i |s R source_i + t - target_i|^2
/// (Umeyama 1991, Eqs. 40-42; with_scale = false gives Arun's rigid solution, s = 1).
/// `T` receives R and t, `scale` (may be nullptr) receives s. Returns false, leaving the
/// outputs untouched, for fewer than 3 pairs, a size mismatch, non-finite input, or a
/// degenerate geometry (all points nearly coincident or collinear: the rotation about the
/// line is then undetermined).
bool UmeyamaAlign(const std::vector<Eigen::Vector3d>& source,
                  const std::vector<Eigen::Vector3d>& target, bool with_scale, Eigen::Isometry3d* T,
                  double* scale = nullptr);

/// Euclidean fitness score as PCL defines it (Registration::getFitnessScore): the mean squared
/// distance from each transformed source point to its nearest target point, over the points
/// whose nearest neighbour lies within `max_range_m`. Unlike PCL, which compares a *squared*
/// distance with max_range, the range here is a distance in metres.
struct FitnessSummary {
  double fitness_score = std::numeric_limits<double>::infinity();  ///< m^2; inf if no pair
  std::size_t num_within = 0;  ///< source points with a target neighbour within range
  std::size_t num_source = 0;  ///< finite source points considered
  double inlier_ratio = 0.0;   ///< num_within / num_source (0 when no source point)
};
FitnessSummary FitnessScore(const PointCloud& source, const NeighborSearch& target,
                            const Eigen::Isometry3d& T_target_source,
                            double max_range_m = std::numeric_limits<double>::infinity());

/// Why an ICP run ended.
enum class IcpStatus {
  kConverged,              ///< increments fell below both epsilons
  kMaxIterations,          ///< max_iterations reached; T is the last estimate
  kInvalidOptions,         ///< Options::IsValid failed; T is the guess
  kEmptyInput,             ///< no finite source point or an empty target; T is the guess
  kNonFiniteGuess,         ///< the initial guess holds NaN/inf; T is the guess
  kTooFewCorrespondences,  ///< fewer than min_correspondences pairs; T is the last estimate
  kDegenerate,             ///< the SVD step was undetermined (collinear pairs)
};
const char* ToString(IcpStatus status);

struct IcpSummary {
  Eigen::Isometry3d T_target_source = Eigen::Isometry3d::Identity();  ///< result (see status)
  int iterations = 0;                                                 ///< SVD steps applied
  bool converged = false;                                             ///< status == kConverged
  IcpStatus status = IcpStatus::kEmptyInput;
  /// mean squared nearest distance at the result over the points within
  /// Options::fitness_max_range_m, m^2 (inf when none)
  double fitness_score = std::numeric_limits<double>::infinity();
  double inlier_ratio = 0.0;            ///< source points with a pair at the result / finite ones
  std::size_t num_correspondences = 0;  ///< pairs within max_correspondence_distance_m at the
                                        ///< result
  std::string message;                  ///< one line for logs
};

class Icp {
 public:
  struct Options {
    int max_iterations = 50;                     ///< SVD steps at most, >= 1
    double max_correspondence_distance_m = 1.0;  ///< pairs farther apart are ignored, m, > 0
    double translation_epsilon_m = 1e-5;  ///< converged when |increment translation| is below
                                          ///< this (and the rotation below its epsilon), m, > 0
    double rotation_epsilon_rad = 1e-6;   ///< converged when the increment angle is below
                                          ///< this, rad, > 0
    int min_correspondences = 10;         ///< fewer pairs stop the run with a status, >= 3
    /// range of the reported fitness score, m, > 0 (default: no limit, as PCL's default)
    double fitness_max_range_m = std::numeric_limits<double>::infinity();
    bool IsValid(std::string* why) const;
  };

  Icp() = default;
  explicit Icp(const Options& options) : options_(options) {}

  /// Registers `source` (its own frame) to `target` starting from `T_target_source_guess`.
  /// Bad input never throws: the summary carries the status and keeps the guess (or the last
  /// estimate for kTooFewCorrespondences / kDegenerate after some steps). Non-finite source
  /// points are skipped.
  IcpSummary Align(const PointCloud& source, const NeighborSearch& target,
                   const Eigen::Isometry3d& T_target_source_guess) const;

  const Options& options() const { return options_; }

 private:
  Options options_;
};

}  // namespace hylo::registration
