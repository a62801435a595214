#pragma once
// The project's own point types. The core works on these and on Eigen; PCL types appear only
// in the few files that call PCL algorithms.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace hylo {

/// A lidar return as a driver delivers it.
struct ScanPoint {
  Eigen::Vector3f position_lidar = Eigen::Vector3f::Zero();  ///< lidar frame at the point's time, m
  float intensity = 0.f;  ///< driver units (0..255 for most 16-beam sensors)
  int32_t offset_ns = 0;  ///< time of the return after the scan start, ns (>= 0)
  uint16_t ring = 0;      ///< laser index, 0 = lowest beam where the driver provides it
};

/// A set of 3-D positions (a map, a downsampled scan). float: map coordinates are kept
/// near zero by an origin offset, so float resolution is sub-millimetre over kilometres.
using PointCloud = std::vector<Eigen::Vector3f>;

/// The points of `cloud` with every coordinate finite, in order.
inline PointCloud FinitePoints(const PointCloud& cloud) {
  PointCloud finite;
  finite.reserve(cloud.size());
  for (const Eigen::Vector3f& p : cloud) {
    if (p.allFinite()) finite.push_back(p);
  }
  return finite;
}

}  // namespace hylo
