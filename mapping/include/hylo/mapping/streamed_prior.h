#pragma once
// A prior map too large to hold at once: the part around the vehicle is held and renewed
// between scans off the scan path, and the rest can be read on demand when waiting for files
// is acceptable (the start, a lost vehicle). The map manager searches it as it searches a
// whole prior; hylo::tiles implements it over a tiled map directory. An interface here so that
// the map, which every estimator uses, does not depend on how or where the parts are stored.

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/registration/neighbor_search.h"

namespace hylo::mapping {

class StreamedPrior {
 public:
  virtual ~StreamedPrior() = default;

  /// Scan path, before the scan's queries: where the vehicle is (map frame), and the part
  /// that finished loading since the last call swapped in.
  virtual void Follow(const Eigen::Vector3f& position_map) = 0;
  /// On: queries also read the parts not held (synchronously) and Size() counts the whole
  /// map. Switched off, what was read on demand is dropped. Either way the newest finished
  /// part is swapped in.
  virtual void SetOnDemand(bool on_demand) = 0;
  /// Whether `position_map` lies on the map (on a part that holds points).
  virtual bool OnMap(const Eigen::Vector3f& position_map) const = 0;
  /// The loader's first failure ("" while none): the file and what is wrong with it.
  virtual std::string error() const = 0;

  /// The k nearest prior points, ascending (the held part, or the whole map on demand).
  virtual void KNearest(const Eigen::Vector3f& query, int k, float max_distance,
                        std::vector<registration::Neighbor>* neighbors) const = 0;
  /// Points the queries see: the held part, or the whole map on demand.
  virtual std::size_t Size() const = 0;
  /// Points held now.
  virtual std::size_t HeldSize() const = 0;
  /// The points held now, map frame.
  virtual PointCloud FlattenHeld() const = 0;
  /// Heap bytes of what is held (not of what was read on demand).
  virtual std::size_t MemoryBytes() const = 0;
};

}  // namespace hylo::mapping
