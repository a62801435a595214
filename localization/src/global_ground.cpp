// The ground under the vehicle, from its own levelled scan (global_bnb.h).
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "global_bnb.h"

namespace hylo::localization::internal {
namespace {

// Ground returns of a 16-beam sensor start 2-4 m away; within 10 m every sector of an open
// site holds some, and a slope of up to 20 deg changes the ground by a few metres over that
// distance: the plane through them, not their height alone, says what lies under the sensor.
constexpr double kGroundRadiusM = 10.0;
constexpr int kSectors = 16;
constexpr double kSectorQuantile = 0.1;  // the lowest tenth of a sector's returns: its ground
constexpr std::size_t kMinSectorPoints = 10;
constexpr int kMinSectorsForPlane = 5;
constexpr double kOutlierM = 0.25;  // sectors whose ground is off the plane (a ditch, a kerb)
constexpr double kMaxSlope = 0.6;   // tan(31 deg): steeper is not ground a vehicle stands on

struct GroundSample {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  bool used = true;
};

// Least-squares plane z = a x + b y + c through the used samples; false when degenerate.
bool FitPlane(const std::vector<GroundSample>& samples, Eigen::Vector3d* abc) {
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  int n = 0;
  for (const GroundSample& s : samples) {
    if (!s.used) continue;
    const Eigen::Vector3d row(s.mean.x(), s.mean.y(), 1.0);
    A += row * row.transpose();
    rhs += row * s.mean.z();
    ++n;
  }
  if (n < kMinSectorsForPlane) return false;
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(A);
  if (lu.rank() < 3) return false;
  *abc = lu.solve(rhs);
  return abc->allFinite() && std::hypot((*abc)(0), (*abc)(1)) <= kMaxSlope;
}

}  // namespace

bool GroundUnderSensor(const PointCloud& levelled, double* ground_z) {
  std::array<std::vector<Eigen::Vector3f>, kSectors> sectors;
  for (const Eigen::Vector3f& q : levelled) {
    const float r = q.head<2>().norm();
    if (r > kGroundRadiusM) continue;
    const double a = std::atan2(q.y(), q.x()) + M_PI;  // [0, 2 pi]
    sectors[std::min(kSectors - 1, static_cast<int>(a / (2.0 * M_PI) * kSectors))].push_back(q);
  }
  std::vector<GroundSample> samples;
  std::vector<float> all_low;  // every sector's ground returns, for the fallback
  for (std::vector<Eigen::Vector3f>& sector : sectors) {
    if (sector.size() < kMinSectorPoints) continue;
    std::sort(sector.begin(), sector.end(),
              [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) { return a.z() < b.z(); });
    const std::size_t low = std::max<std::size_t>(
        3, static_cast<std::size_t>(kSectorQuantile * static_cast<double>(sector.size())));
    GroundSample s;
    for (std::size_t i = 0; i < low; ++i) {
      s.mean += sector[i].cast<double>();
      all_low.push_back(sector[i].z());
    }
    s.mean /= static_cast<double>(low);
    samples.push_back(s);
  }
  if (samples.empty()) return false;
  // Two rounds: fit, drop sectors off the plane, fit again.
  Eigen::Vector3d abc;
  for (int round = 0; round < 2; ++round) {
    if (!FitPlane(samples, &abc)) break;
    bool dropped = false;
    for (GroundSample& s : samples) {
      const double residual = s.mean.z() - (abc(0) * s.mean.x() + abc(1) * s.mean.y() + abc(2));
      if (s.used && std::abs(residual) > kOutlierM) {
        s.used = false;
        dropped = true;
      }
    }
    if (!dropped) {
      *ground_z = abc(2);
      return true;
    }
  }
  if (FitPlane(samples, &abc)) {
    *ground_z = abc(2);
    return true;
  }
  // Too few sectors for a plane (walls close around): the median of their ground returns.
  std::nth_element(all_low.begin(), all_low.begin() + all_low.size() / 2, all_low.end());
  *ground_z = all_low[all_low.size() / 2];
  return true;
}

}  // namespace hylo::localization::internal
