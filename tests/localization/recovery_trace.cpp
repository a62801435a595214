// A recovery case's run, scan by scan (recovery_trace.h).
#include "localization/recovery_trace.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "hylo/common/time.h"

namespace hylo::testing {
namespace {

// The angle between the estimated and the true up direction in the IMU frame, degrees.
double TiltErrorDeg(const Eigen::Matrix3d& R_map_imu, const Eigen::Matrix3d& R_world_imu) {
  const Eigen::Vector3d up_estimated = R_map_imu.transpose() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d up_true = R_world_imu.transpose() * Eigen::Vector3d::UnitZ();
  return std::acos(std::clamp(up_estimated.dot(up_true), -1.0, 1.0)) * 180.0 / M_PI;
}

}  // namespace

void WriteRecoveryTrace(const RecoveryRun& run, const DriveTruth& truth, const std::string& backend,
                        const std::string& dir) {
  const RecoveryCase& c = run.recovery_case();
  std::filesystem::create_directories(dir);
  const std::string stem = dir + "/s" + std::to_string(c.scenario) + "_c" +
                           std::to_string(c.index) + "_" + backend;
  std::ofstream scans(stem + ".csv");
  std::ofstream events(stem + ".events");
  if (!scans || !events) throw std::runtime_error("cannot write the trace " + stem);
  const auto since_return_s = [&](int64_t t_ns) { return NanosToSeconds(t_ns - c.return_t_ns); };
  scans << "t_s,status,x_m,y_m,z_m,true_x_m,true_y_m,true_z_m,error_m,speed_mps,true_speed_mps,"
           "inlier_ratio,matches,update_applied,wall_ms,cpu_ms,tilt_error_deg,deskew_ms,update_ms,"
           "map_ms,iterations\n";
  for (const odometry::ScanResult& r : run.session().results()) {
    const Eigen::Vector3d p = r.state.p_map_imu;
    const Eigen::Vector3d truth_map = truth.PoseAt(r.t_ns).translation() - run.origin_world();
    scans << since_return_s(r.t_ns) << ',' << odometry::ToString(r.pose_status) << ',' << p.x()
          << ',' << p.y() << ',' << p.z() << ',' << truth_map.x() << ',' << truth_map.y() << ','
          << truth_map.z() << ',' << (p - truth_map).norm() << ',' << r.state.v_map_imu.norm()
          << ',' << truth.SpeedAt(r.t_ns) << ',' << r.health.inlier_ratio << ','
          << r.health.num_matches << ',' << r.update.applied << ',' << r.total_ms << ','
          << r.cpu_ms << ',' << TiltErrorDeg(r.state.R_map_imu.Matrix(), truth.PoseAt(r.t_ns).linear())
          << ',' << r.deskew_ms << ',' << r.update_ms << ',' << r.map_ms << ','
          << r.update.iterations << '\n';
  }
  for (const localization::LocalizationEvent& e : run.session().pipeline().events()) {
    const Eigen::Vector3d truth_map = truth.PoseAt(e.t_ns).translation() - run.origin_world();
    events << since_return_s(e.t_ns) << " s " << localization::ToString(e.kind) << " (error "
           << (e.T_map_imu.translation() - truth_map).norm() << " m): " << e.message << '\n';
  }
}

}  // namespace hylo::testing
