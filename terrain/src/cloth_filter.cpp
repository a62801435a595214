#include "hylo/terrain/cloth_filter.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "hylo/common/local_origin.h"
#include "hylo/common/option_checks.h"
#include "hylo/terrain/cloth_filter_cloth.h"
#include "hylo/terrain/cloth_filter_slope.h"
#include "hylo/terrain/cloth_filter_surface.h"

namespace hylo::terrain {
namespace {

// Particles beyond the points' bounding box on every side, so that border points have a full
// cell of cloth around them (their heights come from hole filling).
constexpr int kBufferCells = 2;
// The cloth starts this far above the highest inverted point (it must start above all of it).
constexpr double kStartClearanceM = 0.05;

template <typename T>
bool Fail(std::string* why, const char* field, T value, const char* constraint) {
  return FailOption(field, value, std::string("must be ") + constraint, why);
}

PointCloud InvertFinite(const PointCloud& points) {
  PointCloud inverted;
  inverted.reserve(points.size());
  for (const Eigen::Vector3f& p : points) {
    if (p.allFinite()) inverted.emplace_back(p.x(), p.y(), -p.z());
  }
  return inverted;
}

// The points the cloth lands on: all but the isolated low outliers (which would be spikes in
// the inverted cloud). Keeps all points when that would leave none.
PointCloud WithoutLowOutliers(const PointCloud& inverted, const ClothFilterOptions& options,
                              ClothFilterResult* result) {
  if (options.low_outlier_depth_m <= 0.0) return inverted;
  const std::vector<uint8_t> outlier =
      cloth::FindLowOutliers(inverted, options.low_outlier_cell_m, options.low_outlier_depth_m,
                             options.low_outlier_min_support, options.low_outlier_max_fraction);
  PointCloud kept;
  kept.reserve(inverted.size());
  for (std::size_t i = 0; i < inverted.size(); ++i) {
    if (!outlier[i]) kept.push_back(inverted[i]);
  }
  if (kept.empty()) return inverted;
  result->num_low_outliers = inverted.size() - kept.size();
  return kept;
}

cloth::ClothDynamics DynamicsFrom(const ClothFilterOptions& options) {
  cloth::ClothDynamics dynamics;
  dynamics.gravity = options.gravity;
  dynamics.time_step = options.time_step;
  dynamics.damping = options.damping;
  dynamics.rigidness = options.rigidness;
  return dynamics;
}

// Drops the cloth until it settles or the iteration budget is spent (paper Sec. 2.2).
void Simulate(const ClothFilterOptions& options, const std::vector<double>& surface_height_m,
              const ClothProgress& progress, cloth::Cloth* cloth, ClothFilterResult* result) {
  for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
    result->last_max_displacement_m = cloth->Step(surface_height_m);
    result->iterations = iteration;
    if (progress) progress(iteration, options.max_iterations);
    if (result->last_max_displacement_m < options.convergence_threshold_m) {
      result->converged = true;
      return;
    }
  }
}

// Classification (paper Sec. 2.4): distance from each point to the cloth, vertical (as the
// reference release) or to the cloth surface (ClothFilterOptions::class_distance_along_normal).
void Classify(const PointCloud& points_local, const cloth::Cloth& cloth, double threshold_m,
              bool along_normal, ClothFilterResult* result) {
  result->labels.assign(points_local.size(), GroundLabel::kInvalid);
  result->height_above_cloth_m.assign(points_local.size(), std::numeric_limits<float>::quiet_NaN());
  for (std::size_t i = 0; i < points_local.size(); ++i) {
    const Eigen::Vector3f& p = points_local[i];
    if (!p.allFinite()) {
      ++result->num_invalid;
      continue;
    }
    const Eigen::Vector2d xy = p.head<2>().cast<double>();
    // The cloth lives in the inverted frame: its height there is -(ground height).
    const double above_m = static_cast<double>(p.z()) + cloth.HeightAt(xy);
    result->height_above_cloth_m[i] = static_cast<float>(above_m);
    // Distance to the cloth surface: the vertical gap times the cosine of the cloth's tilt
    // (1 / sqrt(1 + |grad|^2)). On a 40 deg slope a ground point 0.6 m above a cloth that
    // smooths the terrain is 0.46 m from it.
    double distance_m = std::abs(above_m);
    if (along_normal) distance_m /= std::sqrt(1.0 + cloth.GradientAt(xy).squaredNorm());
    const bool ground = distance_m < threshold_m;
    result->labels[i] = ground ? GroundLabel::kGround : GroundLabel::kObject;
    ++(ground ? result->num_ground : result->num_objects);
  }
}

}  // namespace

bool ClothFilterOptions::IsValid(std::string* why) const {
  if (!(cloth_resolution_m > 0.0))
    return Fail(why, "cloth_resolution_m", cloth_resolution_m, "> 0");
  if (rigidness < 1 || rigidness > 10) return Fail(why, "rigidness", rigidness, "in [1, 10]");
  if (!(time_step > 0.0)) return Fail(why, "time_step", time_step, "> 0");
  if (max_iterations < 1) return Fail(why, "max_iterations", max_iterations, ">= 1");
  if (!(class_threshold_m > 0.0)) return Fail(why, "class_threshold_m", class_threshold_m, "> 0");
  if (!(slope_height_threshold_m > 0.0)) {
    return Fail(why, "slope_height_threshold_m", slope_height_threshold_m, "> 0");
  }
  if (!(slope_max_cloth_gap_m > 0.0)) {
    return Fail(why, "slope_max_cloth_gap_m", slope_max_cloth_gap_m, "> 0");
  }
  if (slope_min_region_particles < 0) {
    return Fail(why, "slope_min_region_particles", slope_min_region_particles, ">= 0");
  }
  if (!(convergence_threshold_m >= 0.0)) {
    return Fail(why, "convergence_threshold_m", convergence_threshold_m, ">= 0");
  }
  if (!(low_outlier_depth_m >= 0.0)) {
    return Fail(why, "low_outlier_depth_m", low_outlier_depth_m, ">= 0");
  }
  if (!(low_outlier_cell_m > 0.0))
    return Fail(why, "low_outlier_cell_m", low_outlier_cell_m, "> 0");
  if (low_outlier_min_support < 1) {
    return Fail(why, "low_outlier_min_support", low_outlier_min_support, ">= 1");
  }
  if (!(low_outlier_max_fraction >= 0.0 && low_outlier_max_fraction < 1.0)) {
    return Fail(why, "low_outlier_max_fraction", low_outlier_max_fraction, "in [0, 1)");
  }
  if (!(gravity > 0.0)) return Fail(why, "gravity", gravity, "> 0");
  if (!(damping >= 0.0 && damping < 1.0)) return Fail(why, "damping", damping, "in [0, 1)");
  return true;
}

ClothFilterResult FilterGroundLocal(const PointCloud& points_local,
                                    const ClothFilterOptions& options,
                                    const ClothProgress& progress) {
  std::string why;
  if (!options.IsValid(&why)) throw std::invalid_argument(why);
  ClothFilterResult result;
  const PointCloud inverted = InvertFinite(points_local);
  if (inverted.empty()) {
    result.labels.assign(points_local.size(), GroundLabel::kInvalid);
    result.num_invalid = points_local.size();
    result.message = points_local.empty() ? "empty cloud" : "no finite point in the cloud";
    return result;
  }
  Eigen::Vector3f min_p = inverted.front();
  Eigen::Vector3f max_p = inverted.front();
  for (const Eigen::Vector3f& p : inverted) {
    min_p = min_p.cwiseMin(p);
    max_p = max_p.cwiseMax(p);
  }
  const cloth::ClothGrid grid =
      cloth::ClothGrid::Covering(min_p.head<2>().cast<double>(), max_p.head<2>().cast<double>(),
                                 options.cloth_resolution_m, kBufferCells);
  const PointCloud landing = WithoutLowOutliers(inverted, options, &result);
  const cloth::InvertedSurface surface =
      cloth::RasterizeInvertedSurface(grid, landing, options.hole_fill);
  float top_z = landing.front().z();
  for (const Eigen::Vector3f& p : landing) top_z = std::max(top_z, p.z());
  cloth::Cloth cloth(grid, top_z + kStartClearanceM, DynamicsFrom(options));
  Simulate(options, surface.height_m, progress, &cloth, &result);
  if (options.slope_smoothing) {
    result.num_pinned_by_slope = cloth::SmoothSteepSlopes(
        surface.height_m, options.slope_height_threshold_m, options.slope_max_cloth_gap_m,
        options.slope_min_region_particles, &cloth);
  }
  Classify(points_local, cloth, options.class_threshold_m, options.class_distance_along_normal,
           &result);
  result.cloth_cols = grid.cols;
  result.cloth_rows = grid.rows;
  result.num_hole_particles = surface.num_filled_holes;
  result.ok = true;
  std::ostringstream os;
  os << result.num_ground << " ground, " << result.num_objects << " objects, cloth " << grid.cols
     << "x" << grid.rows << ", " << result.iterations << " iterations"
     << (result.converged ? " (converged)" : " (iteration limit)");
  result.message = os.str();
  return result;
}

ClothFilterResult FilterGround(const std::vector<Eigen::Vector3d>& points_world,
                               const ClothFilterOptions& options, const ClothProgress& progress) {
  const Eigen::Vector3d origin_world = ChooseOrigin(points_world);
  ClothFilterResult result =
      FilterGroundLocal(ToLocal(points_world, origin_world), options, progress);
  result.origin_world = origin_world;
  return result;
}

}  // namespace hylo::terrain
