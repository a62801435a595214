#pragma once
// The two static kd-trees the ikd-tree is measured against, behind one small interface:
// nanoflann's KDTreeSingleIndexAdaptor (nanoflann_tree.h) and PCL's KdTreeFLANN.
// Both must be rebuilt from scratch whenever the map changes.

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include <memory>
#include <vector>

#include "nanoflann_tree.h"

namespace hylo::benchmarks {

/// PCL's tree keeps its own copy of the cloud (FLANN matrix); the PCL cloud it is given is
/// converted here, outside the timed Build, via SetCloud.
class PclTree final : public StaticTree {
 public:
  const char* Name() const override { return "pcl_kdtree_flann"; }
  static pcl::PointCloud<pcl::PointXYZ>::Ptr ToPcl(const PointCloud& points) {
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
    cloud->resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      (*cloud)[i] = pcl::PointXYZ(points[i].x(), points[i].y(), points[i].z());
    }
    return cloud;
  }
  void SetCloud(pcl::PointCloud<pcl::PointXYZ>::Ptr cloud) { cloud_ = std::move(cloud); }
  void Build(const PointCloud&) override {
    tree_ = std::make_unique<pcl::KdTreeFLANN<pcl::PointXYZ>>();
    tree_->setInputCloud(cloud_);
  }
  void KNearest(const Eigen::Vector3f& query, int k, std::vector<float>* d2) override {
    tree_->nearestKSearch(pcl::PointXYZ(query.x(), query.y(), query.z()), k, indices_, *d2);
  }

 private:
  pcl::PointCloud<pcl::PointXYZ>::Ptr cloud_;
  std::unique_ptr<pcl::KdTreeFLANN<pcl::PointXYZ>> tree_;
  std::vector<int> indices_;
};

}  // namespace hylo::benchmarks
