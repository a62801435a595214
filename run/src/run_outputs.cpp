#include "run_outputs.h"

#include <algorithm>
#include <fstream>
#include <stdexcept>

#include "hylo/io/atomic_file.h"

namespace hylo::run {
namespace {

constexpr const char* kPoseAxes[6] = {"x", "y", "z", "rx", "ry", "rz"};
constexpr const char* kTwistAxes[6] = {"vx", "vy", "vz", "wx", "wy", "wz"};

void WriteCovarianceHeader(std::ofstream& out, const char* prefix, const char* const axes[6]) {
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) out << ',' << prefix << '_' << axes[i] << '_' << axes[j];
  }
}

void WriteMatrix(std::ofstream& out, const Eigen::Matrix<double, 6, 6>& m) {
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) out << ',' << m(i, j);
  }
}

// A CSV written whole or not at all, with enough digits for nanometres and nanoseconds.
std::ofstream& CsvStream(io::AtomicFile* file) {
  file->stream().precision(9);
  return file->stream();
}

}  // namespace

std::vector<io::StampedPose> WorldTrajectory(const std::vector<estimation::NavState>& states,
                                             const Eigen::Vector3d& origin_world) {
  std::vector<io::StampedPose> trajectory;
  trajectory.reserve(states.size());
  for (const estimation::NavState& x : states) {
    io::StampedPose p;
    p.t_ns = x.t_ns;
    p.position = x.p_map_imu + origin_world;
    p.orientation = x.R_map_imu.unit_quaternion();
    trajectory.push_back(p);
  }
  return trajectory;
}

std::vector<estimation::NavState> LiveStates(const std::vector<odometry::ScanResult>& results,
                                            bool valid) {
  std::vector<estimation::NavState> states;
  states.reserve(results.size());
  for (const odometry::ScanResult& r : results) {
    if ((r.pose_status == odometry::PoseStatus::kValid) == valid) states.push_back(r.state);
  }
  return states;
}

void WriteOdometryCsv(const std::string& path, const std::vector<odometry::ScanResult>& results,
                      const Eigen::Vector3d& origin_world, const config::OutputFrames& output) {
  io::AtomicFile file(path);
  std::ofstream& out = CsvStream(&file);
  out << "t_s,frame_id,child_frame_id,x,y,z,qx,qy,qz,qw,vx,vy,vz,wx,wy,wz";
  WriteCovarianceHeader(out, "pose_cov", kPoseAxes);
  WriteCovarianceHeader(out, "twist_cov", kTwistAxes);
  out << ",odom_frame_id,map_odom_x,map_odom_y,map_odom_z,map_odom_qx,map_odom_qy,map_odom_qz,"
         "map_odom_qw,fitness_m2,inlier_ratio,matches,health_good,pose_status\n";
  for (const auto& r : results) {
    const Eigen::Vector3d p = r.state.p_map_imu + origin_world;
    const Eigen::Quaterniond& q = r.state.R_map_imu.unit_quaternion();
    out << io::FormatNsAsSeconds(r.t_ns) << ',' << output.map_frame << ',' << output.base_frame
        << ',' << p.x() << ',' << p.y() << ',' << p.z() << ',' << q.x() << ',' << q.y() << ','
        << q.z() << ',' << q.w();
    for (int i = 0; i < 3; ++i) out << ',' << r.linear_velocity_imu[i];
    for (int i = 0; i < 3; ++i) out << ',' << r.angular_velocity_imu[i];
    WriteMatrix(out, r.pose_covariance);
    WriteMatrix(out, r.twist_covariance);
    // map→odom in the world frame: the origin shifts its translation like every map pose.
    const Eigen::Vector3d t_mo = origin_world + r.T_map_odom.translation();
    const Eigen::Quaterniond& q_mo = r.T_map_odom.so3().unit_quaternion();
    out << ',' << output.odom_frame << ',' << t_mo.x() << ',' << t_mo.y() << ',' << t_mo.z()
        << ',' << q_mo.x() << ',' << q_mo.y() << ',' << q_mo.z() << ',' << q_mo.w() << ','
        << r.health.fitness_m2 << ',' << r.health.inlier_ratio << ',' << r.update.num_matches
        << ',' << (r.health.good ? 1 : 0) << ',' << odometry::ToString(r.pose_status) << '\n';
  }
  file.Commit();
}

void WriteTimingCsv(const std::string& path, const std::vector<odometry::ScanResult>& results) {
  io::AtomicFile file(path);
  std::ofstream& out = CsvStream(&file);
  out << "t_s,points,downsampled,matches,iterations,converged,applied,degenerate,"
         "deskew_ms,update_ms,map_ms,total_ms,cpu_ms,map_points\n";
  for (const auto& r : results) {
    out << io::FormatNsAsSeconds(r.t_ns) << ',' << r.raw_points << ',' << r.downsampled_points
        << ',' << r.update.num_matches << ',' << r.update.iterations << ','
        << r.update.converged << ',' << r.update.applied << ',' << r.update.degenerate << ','
        << r.deskew_ms << ',' << r.update_ms << ',' << r.map_ms << ',' << r.total_ms << ','
        << r.cpu_ms << ',' << r.map_points << '\n';
  }
  file.Commit();
}

double Percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t i = static_cast<std::size_t>(q * (values.size() - 1) + 0.5);
  return values[std::min(i, values.size() - 1)];
}

}  // namespace hylo::run
