// Gaps in the data: how a state is carried through a lidar gap while the IMU runs, how the
// first scan after a gap is taken (propagated, not registered, for the supervisor to confirm),
// and the restart after a gap in which the IMU was silent too.
#include <algorithm>
#include <cmath>

#include "hylo/localization/icp_initializer.h"
#include "hylo/odometry/odometry_pipeline.h"

namespace hylo::odometry {
namespace {

// How far a scan may trail the newest IMU sample when it arrives (its sweep, then the
// driver's latency: tens of milliseconds in practice), ns. A state carried through a lidar
// gap stays this far behind the newest sample, so that no scan starts before it.
constexpr int64_t kScanMayTrailImuNs = 1'000'000'000;

}  // namespace

void OdometryPipeline::AddImu(const ImuSample& sample) {
  queue_.AddImu(sample);
  CarryThroughLidarGap();
}

void OdometryPipeline::CarryThroughLidarGap() {
  if ((status_ != Status::kRunning && status_ != Status::kLost) || !options_.imu.enabled ||
      queue_.pending_scans() > 0 || !estimator_->initialized()) {
    return;
  }
  // Called for every IMU sample: while scans come the state is well within a second of the
  // newest sample, and this returns before the usual interval (a median) is computed.
  const int64_t state_ns = estimator_->state().t_ns;
  const int64_t until_ns = queue_.newest_imu_ns() - kScanMayTrailImuNs;
  if (until_ns <= state_ns) return;
  const int64_t usual_ns = scan_clock_.UsualIntervalNs();
  if (usual_ns == 0) return;
  // Carried in steps of a data gap (three usual scan intervals): through a lidar gap, a few
  // dozen samples at a time, as they arrive.
  const auto gap_ns = static_cast<int64_t>(ScanIntervalClock::kGapIntervals * usual_ns);
  if (until_ns - state_ns <= gap_ns) return;
  // Not across a silence of the IMU as long as a data gap: the first scan after it restarts
  // the estimator instead (RestartAfterBlindGap).
  const std::vector<ImuSample> imu = queue_.PopContinuousImu(state_ns, until_ns, gap_ns);
  if (imu.empty()) return;
  for (const ImuSample& s : imu) estimator_->AddImu(s);
  estimator_->CarryForward(imu.back().t_ns);
}

bool OdometryPipeline::AfterDataGapInMap(int64_t scan_end_ns) const {
  return supervisor_ && supervisor_->started() && !supervisor_->searching() &&
         supervisor_->on_map() && scan_clock_.GapBefore(scan_end_ns) > 0.0;
}

bool OdometryPipeline::RestartAfterBlindGap(int64_t scan_end_ns, const std::vector<ImuSample>& imu) {
  if (!options_.imu.enabled || imu.empty() || !AfterDataGapInMap(scan_end_ns)) {
    return false;  // a lidar that kept coming corrected the state through an IMU gap
  }
  // The estimator's state is the last scan's (or carried on from it by the IMU while the lidar
  // was silent): without IMU samples since then for longer than a data gap, it would be
  // propagated blind across the gap (by samples interpolated over it), and its attitude,
  // velocity and position with it.
  const estimation::NavState& before = estimator_->state();
  const int64_t usual_ns = scan_clock_.UsualIntervalNs();
  if (usual_ns == 0) return false;
  // The longest silence since that scan (the samples may begin before the gap), and the first
  // sample after it.
  std::size_t after = 0;
  int64_t longest_ns = imu.front().t_ns - before.t_ns;
  for (std::size_t k = 1; k < imu.size(); ++k) {
    if (imu[k].t_ns - imu[k - 1].t_ns > longest_ns) {
      longest_ns = imu[k].t_ns - imu[k - 1].t_ns;
      after = k;
    }
  }
  if (longest_ns <= ScanIntervalClock::kGapIntervals * usual_ns) return false;
  // What the gap leaves known: the biases, and the heading and place it began at. Roll and
  // pitch come again from the accelerometer (gravity, plus whatever the vehicle accelerates,
  // as in a start on the move), the velocity is unknown: the moving start's uncertainty.
  Eigen::Vector3d specific_force_imu = Eigen::Vector3d::Zero();
  for (std::size_t k = after; k < imu.size(); ++k) {
    specific_force_imu += imu[k].accel_imu / static_cast<double>(imu.size() - after);
  }
  estimation::NavState x = before;
  x.t_ns = imu[after].t_ns;
  const Eigen::Matrix3d R = before.R_map_imu.Matrix();
  const Eigen::Isometry3d levelled = localization::GuessFromGravity(
      before.p_map_imu, std::atan2(R(1, 0), R(0, 0)), specific_force_imu);
  x.R_map_imu = lie::SO3d(Eigen::Quaterniond(levelled.rotation()));
  x.v_map_imu.setZero();
  estimator_->Initialize(x, options_.initial_uncertainty.MovingCovariance(x));
  return true;
}

}  // namespace hylo::odometry
