#pragma once
// The small interface the benchmarks' static kd-trees share, and the first of them: nanoflann's
// KDTreeSingleIndexAdaptor (Debian libnanoflann-dev 1.4.3, header only). A static tree must be
// rebuilt from scratch whenever the map changes.

#include <Eigen/Core>
#include <memory>
#include <nanoflann.hpp>
#include <vector>

#include "hylo/common/point_types.h"

namespace hylo::benchmarks {

class StaticTree {
 public:
  virtual ~StaticTree() = default;
  virtual const char* Name() const = 0;
  /// (Re)builds the index over `points` (kept alive by the caller until the next Build).
  virtual void Build(const PointCloud& points) = 0;
  /// Squared distances of the k nearest points to `query`, nearest first.
  virtual void KNearest(const Eigen::Vector3f& query, int k, std::vector<float>* d2) = 0;
};

class NanoflannTree final : public StaticTree {
 public:
  const char* Name() const override { return "nanoflann"; }
  void Build(const PointCloud& points) override {
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
    const PointCloud* points = nullptr;
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

}  // namespace hylo::benchmarks
