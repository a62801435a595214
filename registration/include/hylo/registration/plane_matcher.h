#pragma once
// Point-to-plane data association shared by every estimator back-end (FAST-LIO2, Sec. IV-C):
// a scan point placed in the map with the current estimate gets its k nearest map points, a
// least-squares plane is fitted to them, and the plane is kept only if every neighbour lies
// within a threshold of it. The residual is the signed distance of the point to that plane.
// Neighbours that lie along a line fit every plane through it (see line_like_neighbors): the
// neighbourhood can be widened once before the plane is fitted.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "hylo/registration/neighbor_search.h"

namespace hylo::registration {

struct PlaneMatcherOptions {
  int num_neighbors = 5;                 ///< k nearest map points per plane, >= 3
  /// When the k neighbours lie along a line (see line_like_ratio), every plane through that
  /// line passes the planarity test and the normal is noise; matched against it, a scan is
  /// held where earlier scans lay (a spinning head's rings on the ground: points 0.5 m apart
  /// along a ring, metres between rings; a 16-beam head starting on a slope kept only 44 % of
  /// its true roll change in the first 2 s of motion). Such a point is matched again with this
  /// many neighbours, which reach across the line (or are fewer within
  /// max_neighbor_distance_m: no plane). <= num_neighbors: no second search. 12: from a sweep
  /// of the plain neighbour count on half of the scenario matrix (README).
  int line_like_neighbors = 12;
  /// The k neighbours are line-like when their RMS spread across their main direction is
  /// below planarity_threshold_m (a plane tilted about the line would pass the test) and below
  /// this fraction of their spread along it (elongated, whatever the map's resolution: a dense
  /// patch of a wall is small but not a line). In (0, 1]. 0.2: ring neighbourhoods measure
  /// ~0.05, a 0.1 m grid patch ~0.6; the real hand-held scans lost accuracy from 0.4 up, and
  /// 0.2 and 0.3 tied on the selection half of the scenario matrix (README).
  double line_like_ratio = 0.2;
  double max_neighbor_distance_m = 2.0;  ///< farther map points are not neighbours, m (> 0)
  double planarity_threshold_m = 0.1;    ///< every neighbour within this of the plane, m (> 0)
  /// Outlier gate on the residual, scaled by range as in FAST-LIO2: a match is kept when
  /// |r| < range_gate_factor · sqrt(range of the point from the sensor, m), m^0.5 (> 0).
  double range_gate_factor = 0.11;

  bool IsValid(std::string* why) const;
};

/// The plane nᵀx + offset = 0 with |n| = 1, in map coordinates.
struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0.0;  ///< m

  /// Signed point-to-plane distance, m.
  double Distance(const Eigen::Vector3d& point) const { return normal.dot(point) + offset; }
};

/// RMS spread of points along their main direction and across it within their plane: the
/// square roots of the largest and the middle eigenvalue of their covariance, m.
struct NeighborSpread {
  double along_m = 0.0;
  double across_m = 0.0;
};

/// Least-squares plane through `points` (smallest eigenvector of their covariance). False when
/// fewer than 3 points or when a point lies farther than `planarity_threshold_m` from it.
/// `spread` (optional) receives the points' spread; zeros for fewer than 3 points.
bool FitPlane(const std::vector<Neighbor>& points, double planarity_threshold_m, Plane* plane,
              NeighborSpread* spread = nullptr);

class PlaneMatcher {
 public:
  /// Keeps a reference to `map`: it must outlive the matcher.
  PlaneMatcher(const NeighborSearch& map, const PlaneMatcherOptions& options);

  /// The plane for a point already placed in the map; false when there are too few
  /// neighbours within range or they are not planar. Thread-safe if the map's queries are.
  bool Match(const Eigen::Vector3d& point_map, Plane* plane) const;

  /// The range-scaled residual gate (see PlaneMatcherOptions::range_gate_factor).
  bool PassesGate(double residual_m, double range_m) const;

  const NeighborSearch& map() const { return map_; }
  const PlaneMatcherOptions& options() const { return options_; }

 private:
  const NeighborSearch& map_;
  PlaneMatcherOptions options_;
};

}  // namespace hylo::registration
