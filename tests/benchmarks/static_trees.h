#pragma once
// The two static kd-trees the ikd-tree is measured against, behind one small interface:
// nanoflann's KDTreeSingleIndexAdaptor (Debian libnanoflann-dev 1.4.3) and PCL's KdTreeFLANN.
// Both must be rebuilt from scratch whenever the map changes.

#include <pcl/kdtree/kdtree_flann.h>
#include <pcl/point_types.h>

#include <memory>
#include <nanoflann.hpp>
#include <vector>

#include "hylo/registration/point_types.h"

namespace hylo::benchmarks {

class StaticTree {
 public:
  virtual ~StaticTree() = default;
  virtual const char* Name() const = 0;
  /// (Re)builds the index over `points` (kept alive by the caller until the next Build).
  virtual void Build(const registration::PointCloud& points) = 0;
  /// Squared distances of the k nearest points to `query`, nearest first.
  virtual void KNearest(const Eigen::Vector3f& query, int k, std::vector<float>* d2) = 0;
};

class NanoflannTree final : public StaticTree {
 public:
  const char* Name() const override { return "nanoflann"; }
  void Build(const registration::PointCloud& points) override {
    adaptor_.points = &points;
    index_ = std::make_unique<Index>(3, adaptor_, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  }
  void KNearest(const Eigen::Vector3f& query, int k, std::vector<float>* d2) override {
    indices_.resize(k);
    d2->resize(k);
    const std::size_t found = index_->knnSearch(query.data(), k, indices_.data(), d2->data());
    d2->resize(found);
  }

 private:
  struct Adaptor {  // nanoflann's dataset concept over a PointCloud
    const registration::PointCloud* points = nullptr;
    std::size_t kdtree_get_point_count() const { return points->size(); }
    float kdtree_get_pt(std::size_t i, std::size_t dim) const { return (*points)[i][dim]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
      return false;
    }
  };
  using Index = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Adaptor>,
                                                    Adaptor, 3, uint32_t>;
  Adaptor adaptor_;
  std::unique_ptr<Index> index_;
  std::vector<uint32_t> indices_;
};

/// PCL's tree keeps its own copy of the cloud (FLANN matrix); the PCL cloud it is given is
/// converted here, outside the timed Build, via SetCloud.
class PclTree final : public StaticTree {
 public:
  const char* Name() const override { return "pcl_kdtree_flann"; }
  static pcl::PointCloud<pcl::PointXYZ>::Ptr ToPcl(const registration::PointCloud& points) {
    auto cloud = std::make_shared<pcl::PointCloud<pcl::PointXYZ>>();
    cloud->resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      (*cloud)[i] = pcl::PointXYZ(points[i].x(), points[i].y(), points[i].z());
    }
    return cloud;
  }
  void SetCloud(pcl::PointCloud<pcl::PointXYZ>::Ptr cloud) { cloud_ = std::move(cloud); }
  void Build(const registration::PointCloud&) override {
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
