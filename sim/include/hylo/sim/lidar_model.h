#pragma once
// A spinning 16-beam lidar. Each laser fires at its own time (column start + its slot in
// the firing sequence), from the pose the sensor has at that instant (the column's exact
// spline pose carried to second order over the <= 45 us of the firing sequence: < 1e-8 m),
// so the scans carry real motion distortion; every return gets its time offset from the scan start
// and its ring. Range noise, grazing-angle and random dropouts, min/max range as in the datasheets.

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "hylo/common/sensor_data.h"
#include "hylo/sim/trajectory.h"
#include "hylo/sim/world.h"

namespace hylo::sim {

enum class LidarModel { kVlp16, kRs16 };
/// "vlp16" / "rs16".
std::string ToString(LidarModel model);
bool ParseLidarModel(const std::string& name, LidarModel* model);

/// The beams in firing order. VLP-16 (user manual, laser IDs 0..15): -15, 1, -13, 3, ...,
/// 15 deg, one laser every 2.304 us. RS-16 (RoboSense channels 0..15): -15 .. -1 deg then
/// 15 .. 1 deg; the 3 us slot is a nominal value.
struct BeamTable {
  std::array<double, 16> elevation_deg{};  ///< per firing slot, deg (up positive)
  std::array<uint16_t, 16> ring{};         ///< ring per slot: rank of elevation, 0 = lowest
  int64_t slot_ns = 0;                     ///< time between two lasers of one column, ns
};
BeamTable MakeBeamTable(LidarModel model);

struct LidarOptions {
  LidarModel model = LidarModel::kVlp16;  ///< beam table
  double rate_hz = 10.0;                  ///< revolutions per second, Hz
  double column_deg = 0.2;                ///< azimuth step between columns, deg
  double min_range_m = 0.8;               ///< closer returns are discarded, m
  double max_range_m = 100.0;             ///< farther surfaces give no return, m
  double range_noise_m = 0.02;            ///< Gaussian range noise (1 sigma), m
  double dropout_probability = 0.01;      ///< random missing returns, [0, 1)
  double min_incidence_cos = 0.03;        ///< grazing returns below this cos are lost
  double intensity_noise = 2.0;           ///< intensity noise (1 sigma), driver units
  double start_azimuth_deg = 180.0;       ///< azimuth of the first column (lidar frame), deg
  /// Mounting: maps lidar points into the IMU frame. Non-identity by default.
  Eigen::Isometry3d T_imu_lidar = DefaultExtrinsic();
  /// Lidar clock minus true time: stamps = true time + offset (0 = synchronised), ns.
  int64_t time_offset_ns = 0;

  static Eigen::Isometry3d DefaultExtrinsic();
  bool IsValid(std::string* why) const;
  int64_t period_ns() const;
  int columns() const;
};

/// Ground truth of one return (for tests and evaluation).
struct ReturnTruth {
  Eigen::Vector3d point_map = Eigen::Vector3d::Zero();  ///< noise-free hit, m
  double true_range_m = 0.0;                            ///< noise-free range, m
  int32_t primitive = -1;                               ///< World primitive, -1 = ground
};

class LidarSimulator {
 public:
  LidarSimulator(const LidarOptions& options, const World& world, const Trajectory& trajectory,
                 uint64_t seed);

  /// Scan `index` (true times [index, index + 1) * period since the session start), stamped
  /// `session_start_ns + index * period + time_offset_ns`. `truth`, if given, receives one
  /// entry per returned point.
  LidarScan Scan(int index, int64_t session_start_ns,
                 std::vector<ReturnTruth>* truth = nullptr) const;
  int64_t period_ns() const { return options_.period_ns(); }
  const BeamTable& beams() const { return beams_; }

 private:
  LidarOptions options_;
  BeamTable beams_;
  const World& world_;
  const Trajectory& trajectory_;
  uint64_t seed_;
  std::array<Eigen::Vector2d, 16> elevation_cos_sin_;
};

}  // namespace hylo::sim
