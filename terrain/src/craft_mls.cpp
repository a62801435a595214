// The only file of hylo::mapping that sees PCL.
#include "hylo/terrain/craft_mls.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/surface/mls.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>
#include <thread>

#include "hylo/common/check.h"

namespace hylo::terrain {
namespace {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

int NumCoefficients(int order) { return (order + 1) * (order + 2) / 2; }

// Degrees of freedom the scale test's noise estimate needs: its relative standard deviation is
// about 1 / sqrt(2 dof), ~20 % here (chi-square); fewer and the test would reject at random.
constexpr int kMinNoiseDof = 12;

// Single scale: PCL's MovingLeastSquares over the query indices, neighbours from all of input.
MlsOutput PclMls(const Cloud::Ptr& input, const std::vector<std::size_t>& queries,
                 const MlsSettings& s) {
  pcl::MovingLeastSquares<pcl::PointXYZ, pcl::PointNormal> mls;
  mls.setInputCloud(input);
  mls.setIndices(pcl::make_shared<pcl::Indices>(queries.begin(), queries.end()));
  mls.setSearchMethod(pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>());
  mls.setSearchRadius(s.search_radius_m);
  mls.setPolynomialOrder(s.polynomial_order);
  mls.setComputeNormals(true);  // also used to recognise points MLS could not fit
  mls.setNumberOfThreads(static_cast<unsigned>(s.num_threads));
  pcl::PointCloud<pcl::PointNormal> smoothed;
  mls.process(smoothed);

  // With several threads PCL appends results in completion order; restore input order (= query
  // order, queries are ascending) so the output does not depend on the thread count.
  const pcl::PointIndicesPtr source = mls.getCorrespondingIndices();
  std::vector<std::size_t> order(smoothed.size());
  std::iota(order.begin(), order.end(), 0);
  if (source && source->indices.size() == smoothed.size()) {
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return source->indices[a] < source->indices[b];
    });
  }
  MlsOutput output;
  output.points.reserve(smoothed.size());
  for (const std::size_t k : order) {
    const pcl::PointNormal& q = smoothed[k];
    const Eigen::Vector3f position(q.x, q.y, q.z);
    const Eigen::Vector3f normal(q.normal_x, q.normal_y, q.normal_z);
    // Too few neighbours to fit a surface: PCL leaves the normal NaN.
    if (!position.allFinite() || !normal.allFinite()) continue;
    output.points.push_back(position);
    if (s.compute_normals) output.normals.push_back(normal.normalized());
  }
  return output;
}

// One MLS fit (PCL's MLSResult, as MovingLeastSquares does it) at one scale.
struct ScaleFit {
  bool ok = false;
  Eigen::Vector3d point, normal;  ///< projected query point and surface normal
  double residual_rms_m = 0.0;    ///< RMS height of the neighbours off the fitted surface
  int num_neighbours = 0;
  int num_coefficients = 1;      ///< parameters actually fitted (1: PCL fell back to the plane)
  double variance_factor = 1.0;  ///< variance of the point's height / noise variance
};

// Coordinates of `p` in the fit's frame (mean, u, v, plane normal): (u, v) and the height w.
Eigen::Vector3d FitCoordinates(const pcl::MLSResult& mls, const Eigen::Vector3d& p) {
  const Eigen::Vector3d delta = p - mls.mean;
  return {delta.dot(mls.u_axis), delta.dot(mls.v_axis), delta.dot(mls.plane_normal)};
}

// Order <= 3: at most 10 coefficients, kept on the stack (this runs per neighbour).
using Terms = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 10, 1>;
using TermMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 10, 10>;

// The polynomial's terms u^i v^j at (u, v), in the order MLSResult::computeMLSSurface uses.
Terms PolynomialTerms(int order, double u, double v) {
  Terms terms(NumCoefficients(order));
  int j = 0;
  double u_pow = 1.0;
  for (int ui = 0; ui <= order; ++ui) {
    double v_pow = 1.0;
    for (int vi = 0; vi <= order - ui; ++vi) {
      terms(j++) = u_pow * v_pow;
      v_pow *= v;
    }
    u_pow *= u;
  }
  return terms;
}

ScaleFit FitScale(const Cloud& cloud, int query, const pcl::Indices& neighbours, double radius_m,
                  int order) {
  ScaleFit f;
  if (neighbours.size() < 3) return f;  // as MovingLeastSquares: no fit below 3 neighbours
  pcl::MLSResult mls;
  mls.computeMLSSurface(cloud, query, neighbours, radius_m, order);
  if (!mls.valid) return f;
  const int nr_coeff = NumCoefficients(order);
  const pcl::MLSResult::MLSProjectionResults proj =
      mls.projectQueryPoint(pcl::MLSResult::SIMPLE, nr_coeff);
  f.num_neighbours = static_cast<int>(neighbours.size());
  const bool polynomial = order > 1 && f.num_neighbours >= nr_coeff && mls.c_vec.size() > 0 &&
                          std::isfinite(mls.c_vec[0]);
  f.num_coefficients = polynomial ? nr_coeff : 1;
  // Residuals, and the variance of the projected point's height per unit noise variance: for
  // the weighted least squares c = A^-1 P W f, Var(c) = sigma^2 A^-1 (P W^2 P^T) A^-1, and the
  // point sits at height c_0; on the plane alone it is the centroid's, sigma^2 / n.
  double sum_sq = 0.0;
  const int p = polynomial ? nr_coeff : 1;
  TermMatrix a = TermMatrix::Zero(p, p), b = TermMatrix::Zero(p, p);
  for (const pcl::index_t k : neighbours) {
    const Eigen::Vector3d uvw = FitCoordinates(mls, cloud[k].getVector3fMap().cast<double>());
    if (!polynomial) {
      sum_sq += uvw.z() * uvw.z();
      continue;
    }
    const Terms terms = PolynomialTerms(order, uvw.x(), uvw.y());
    const double r = uvw.z() - terms.dot(mls.c_vec);
    sum_sq += r * r;
    // MLSResult's default weight (private there): exp(-d^2 / radius^2), d from the mean.
    const double w = std::exp(-uvw.squaredNorm() / (radius_m * radius_m));
    a.noalias() += w * terms * terms.transpose();
    b.noalias() += w * w * terms * terms.transpose();
  }
  if (polynomial) {
    const TermMatrix a_inv = a.inverse();
    f.variance_factor = (a_inv * b * a_inv)(0, 0);
  } else {
    f.variance_factor = 1.0 / f.num_neighbours;
  }
  const int dof = std::max(1, f.num_neighbours - f.num_coefficients - 2);
  f.residual_rms_m = std::sqrt(sum_sq / dof);
  f.point = proj.point;
  f.normal = proj.normal;
  f.ok = f.point.allFinite() && f.normal.allFinite() && std::isfinite(f.variance_factor);
  return f;
}

// Two-scale choice by the intersection-of-confidence-intervals rule (Goldenshluger and
// Nemirovski 1997; Katkovnik 1999): the large-scale estimate is taken while it lies within
// the confidence intervals of the small-scale one, i.e. while the extra neighbours only
// reduce variance; otherwise (the large neighbourhood is no single height field: a pole seen
// from all sides, a bend, a thin part) the small-scale estimate, whose bias is smaller.
// The standard deviations come from FitScale's variance factors and the local noise, the
// small fit's residual RMS (the large fit's residuals would grow with the very bias tested).
bool LargeScaleConsistent(const ScaleFit& large, const ScaleFit& small, double sigmas) {
  const double noise_m = small.residual_rms_m;
  const double sd_large = noise_m * std::sqrt(large.variance_factor);
  const double sd_small = noise_m * std::sqrt(small.variance_factor);
  // Only the offset across the surface counts: a slide along it does not change the surface.
  const double offset_m = std::abs((large.point - small.point).dot(large.normal.normalized()));
  return offset_m <= sigmas * (sd_large + sd_small);
}

struct PointResult {
  bool ok = false;
  bool small_scale = false;
  Eigen::Vector3f point, normal;
};

// The small fit's order: the highest (<= the large fit's) that leaves the noise estimate
// kMinNoiseDof degrees of freedom; -1 when even a plane cannot (the test would have no power).
int SmallScaleOrder(std::size_t num_neighbours, int order) {
  for (; order >= 0; --order) {
    if (static_cast<int>(num_neighbours) >= NumCoefficients(order) + 2 + kMinNoiseDof) break;
  }
  return order;
}

PointResult SmoothOnePoint(const Cloud& cloud, const pcl::search::KdTree<pcl::PointXYZ>& tree,
                           int query, const MlsSettings& s) {
  PointResult out;
  pcl::Indices neighbours;
  std::vector<float> sq_distances;
  tree.radiusSearch(cloud[query], s.search_radius_m, neighbours, sq_distances);
  const ScaleFit large = FitScale(cloud, query, neighbours, s.search_radius_m, s.polynomial_order);
  if (!large.ok) return out;
  pcl::Indices near;
  const float small_sq = static_cast<float>(s.small_radius_m * s.small_radius_m);
  for (std::size_t k = 0; k < neighbours.size(); ++k) {
    if (sq_distances[k] <= small_sq) near.push_back(neighbours[k]);
  }
  const int small_order = SmallScaleOrder(near.size(), s.polynomial_order);
  ScaleFit small;
  if (small_order >= 0) small = FitScale(cloud, query, near, s.small_radius_m, small_order);
  out.small_scale = small.ok && !LargeScaleConsistent(large, small, s.consistency_sigmas);
  const ScaleFit& chosen = out.small_scale ? small : large;
  out.point = chosen.point.cast<float>();
  out.normal = chosen.normal.normalized().cast<float>();
  out.ok = true;
  return out;
}

MlsOutput ScaleAdaptiveMls(const Cloud::Ptr& input, const std::vector<std::size_t>& queries,
                           const MlsSettings& s) {
  pcl::search::KdTree<pcl::PointXYZ> tree(false);
  tree.setInputCloud(input);
  std::vector<PointResult> results(queries.size());
  std::atomic<std::size_t> next{0};
  constexpr std::size_t kBlock = 1000;
  const auto work = [&] {
    for (std::size_t begin; (begin = next.fetch_add(kBlock)) < results.size();) {
      const std::size_t end = std::min(results.size(), begin + kBlock);
      for (std::size_t i = begin; i < end; ++i) {
        results[i] = SmoothOnePoint(*input, tree, static_cast<int>(queries[i]), s);
      }
    }
  };
  std::vector<std::thread> helpers;
  for (int t = 1; t < s.num_threads; ++t) helpers.emplace_back(work);
  work();
  for (std::thread& t : helpers) t.join();
  MlsOutput output;
  output.points.reserve(results.size());
  for (const PointResult& r : results) {
    if (!r.ok) continue;
    output.points.push_back(r.point);
    if (s.compute_normals) output.normals.push_back(r.normal);
    output.num_small_scale += r.small_scale;
  }
  return output;
}

}  // namespace

MlsOutput SmoothMls(const PointCloud& support, const std::vector<std::size_t>& queries,
                    const MlsSettings& settings) {
  HYLO_CHECK(std::is_sorted(queries.begin(), queries.end()), "queries must be ascending");
  HYLO_CHECK(queries.empty() || queries.back() < support.size(), "query outside the support");
  if (queries.empty()) return {};
  auto input = pcl::make_shared<Cloud>();
  input->reserve(support.size());
  for (const Eigen::Vector3f& p : support) input->push_back({p.x(), p.y(), p.z()});
  return settings.small_radius_m > 0.0 ? ScaleAdaptiveMls(input, queries, settings)
                                       : PclMls(input, queries, settings);
}

}  // namespace hylo::terrain
