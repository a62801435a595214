// The only file of hylo::mapping that sees PCL.
#include "hylo/mapping/craft_mls.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>
#include <pcl/surface/mls.h>

#include <algorithm>
#include <numeric>

namespace hylo::mapping {

MlsOutput SmoothMls(const registration::PointCloud& points_local, double search_radius_m,
                    int polynomial_order, int num_threads, bool compute_normals) {
  auto input = pcl::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
  input->reserve(points_local.size());
  for (const Eigen::Vector3f& p : points_local) input->push_back({p.x(), p.y(), p.z()});

  pcl::MovingLeastSquares<pcl::PointXYZ, pcl::PointNormal> mls;
  mls.setInputCloud(input);
  mls.setSearchMethod(pcl::make_shared<pcl::search::KdTree<pcl::PointXYZ>>());
  mls.setSearchRadius(search_radius_m);
  mls.setPolynomialOrder(polynomial_order);
  mls.setComputeNormals(true);  // also used to recognise points MLS could not fit
  mls.setNumberOfThreads(static_cast<unsigned>(num_threads));
  pcl::PointCloud<pcl::PointNormal> smoothed;
  mls.process(smoothed);

  // With several threads PCL appends results in completion order; restore input order so the
  // output does not depend on the thread count.
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
    if (compute_normals) output.normals.push_back(normal.normalized());
  }
  return output;
}

}  // namespace hylo::mapping
