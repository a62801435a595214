#pragma once
// The ISPRS filter test's scoring (shared/data/README.md): each of the held samples with its
// reference ground labels, and the confusion counts of a ground filter's labels against them
// (type I, type II, total error, Cohen's kappa). Shared by the real-data tests of the ground
// back-ends and the leave-one-out benchmark, so that every figure is computed one way.

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "hylo/terrain/ground_label.h"

namespace hylo::terrain::isprs {

/// Exact-coordinate key: the ISPRS ground files are an exact subset of the full samples, and
/// the CSF reference lists coordinates with 6 decimals (rounded to 1 mm here).
struct PointKey {
  int64_t x, y, z;
  bool operator==(const PointKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct PointKeyHash {
  std::size_t operator()(const PointKey& k) const {
    return std::hash<int64_t>()(k.x * 73856093 ^ k.y * 19349663 ^ k.z * 83492791);
  }
};
PointKey KeyOf(const Eigen::Vector3d& p);

/// Confusion counts with ground as the positive class (ISPRS filter test definitions).
struct Confusion {
  double ground_as_ground = 0, ground_as_object = 0, object_as_ground = 0, object_as_object = 0;
  double TypeI() const { return ground_as_object / (ground_as_ground + ground_as_object); }
  double TypeII() const { return object_as_ground / (object_as_ground + object_as_object); }
  double Total() const { return (ground_as_object + object_as_ground) / N(); }
  double N() const {
    return ground_as_ground + ground_as_object + object_as_ground + object_as_object;
  }
  double Kappa() const;
};

/// One sample: its points (UTM) and, per point, whether the reference calls it ground.
struct Sample {
  std::string name;                     ///< "samp11"
  std::vector<Eigen::Vector3d> points;  ///< m, UTM
  std::vector<uint8_t> is_ground;       ///< per point
};

/// The 7 samples in ../shared/data/isprs, in the order the tables print them.
const std::vector<std::string>& SampleNames();

/// Reads isprs/<name>-utm.pcd and its -ground subset from the data directory (throws when
/// absent: tests check with HYLO_REQUIRE_DATA first).
Sample LoadSample(const std::string& name);

/// Labels (one per point of `sample`) against the reference; invalid labels count as objects.
Confusion Score(const Sample& sample, const std::vector<GroundLabel>& labels);

/// The header and one row of the per-sample tables: name, type I, type II, total, kappa (%).
const char* TableHeader();
std::string TableRow(const std::string& name, const Confusion& c);

}  // namespace hylo::terrain::isprs
