#include "hylo/estimation/undistortion.h"

#include <algorithm>

#include "hylo/registration/parallel.h"

namespace hylo::estimation {

PointCloud PointsOf(const LidarScan& scan) {
  PointCloud points;
  points.reserve(scan.points.size());
  for (const ScanPoint& p : scan.points) points.push_back(p.position_lidar);
  return points;
}

SweepMotion::SweepMotion(int64_t start_ns, int64_t end_ns, const Estimator& estimator,
                         const std::vector<int64_t>& knot_times_ns) {
  // Knots: sweep start, IMU stamps strictly inside, sweep end; each carries T_end_lidar(t),
  // the lidar pose at t seen from the lidar at the sweep end.
  times_ns_.push_back(start_ns);
  for (int64_t t : knot_times_ns) {
    if (t > start_ns && t < end_ns) times_ns_.push_back(t);
  }
  std::sort(times_ns_.begin() + 1, times_ns_.end());
  if (end_ns > start_ns) times_ns_.push_back(end_ns);
  const std::vector<NavState> states = estimator.PredictAlong(times_ns_);
  const lie::SE3d T_end_map = (end_ns > start_ns ? states.back() : estimator.PredictAt(end_ns))
                                  .T_map_lidar()
                                  .Inverse();
  for (const NavState& x : states) {
    const lie::SE3d T_end_t = T_end_map * x.T_map_lidar();
    rotations_.push_back(T_end_t.so3().unit_quaternion());
    translations_.push_back(T_end_t.translation());
  }
  // Normalised linear interpolation of the quaternions where the knots are close (no
  // trigonometry per point) departs from slerp by about angle^3 / 250, under 5e-7 rad below
  // kNlerpMaxAngleRad (0.05 mm at 100 m). IMU knots at 100-400 Hz are 0.01-0.03 rad apart at
  // 3 rad/s; wider intervals (no IMU sample inside the sweep) keep slerp.
  constexpr double kNlerpMaxAngleRad = 0.05;
  use_nlerp_.assign(times_ns_.size(), 1);
  for (std::size_t k = 0; k + 1 < times_ns_.size(); ++k) {
    if (rotations_[k].dot(rotations_[k + 1]) < 0.0) rotations_[k + 1].coeffs() *= -1.0;
    use_nlerp_[k] = rotations_[k].angularDistance(rotations_[k + 1]) < kNlerpMaxAngleRad;
  }
}

Eigen::Vector3f SweepMotion::ToSweepEnd(int64_t scan_t_ns, const ScanPoint& p) const {
  const int64_t t = scan_t_ns + p.offset_ns;
  const std::size_t hi = std::min<std::size_t>(
      std::upper_bound(times_ns_.begin(), times_ns_.end(), t) - times_ns_.begin(),
      times_ns_.size() - 1);
  const std::size_t lo = hi == 0 ? 0 : hi - 1;
  const double span = static_cast<double>(times_ns_[hi] - times_ns_[lo]);
  const double w = span > 0.0 ? std::clamp((t - times_ns_[lo]) / span, 0.0, 1.0) : 0.0;
  Eigen::Quaterniond q;
  if (use_nlerp_[lo]) {
    q.coeffs() = (1.0 - w) * rotations_[lo].coeffs() + w * rotations_[hi].coeffs();
    q.normalize();
  } else {
    q = rotations_[lo].slerp(w, rotations_[hi]);
  }
  const Eigen::Vector3d trans = (1.0 - w) * translations_[lo] + w * translations_[hi];
  return (q * p.position_lidar.cast<double>() + trans).cast<float>();
}

PointCloud SweepMotion::ToSweepEnd(const LidarScan& scan) const {
  if (times_ns_.empty()) return PointsOf(scan);
  PointCloud points(scan.points.size());
  registration::ParallelFor(scan.points.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) points[i] = ToSweepEnd(scan.t_ns, scan.points[i]);
  });
  return points;
}

PointCloud Undistort(const LidarScan& scan, const Estimator& estimator,
                     const std::vector<int64_t>& knot_times_ns) {
  return SweepMotion(scan.t_ns, scan.end_t_ns, estimator, knot_times_ns).ToSweepEnd(scan);
}

}  // namespace hylo::estimation
