#pragma once
// Zero-velocity updates (section `standstill:` of a run configuration), shared by both
// back-ends: detecting from the IMU that the vehicle stands still over a scan interval, and the
// pseudo-measurement v_map = 0 each back-end then adds beside the scan.
//
// Why: at standstill a sparse or degenerate scan (few returns, a start on a slope) lets a lidar
// update move the pose, and the velocity and accelerometer bias follow it; the IMU knows better,
// because at rest it shows nothing but its white noise.
//
// The test compares the samples' spread over the interval with the spread the datasheet's noise
// densities predict at the sample rate, for both sensors (the idea of Skog et al., "Zero-velocity
// detection: an algorithm evaluation", IEEE TBME 2010, with the threshold stated as a ratio of
// spreads rather than an absolute value, so one setting serves every IMU grade). Two guards keep
// it from stopping a vehicle that moves:
//  - an IMU cannot tell rest from straight motion at constant speed, so the estimate must already
//    be nearly stopped (`max_speed_mps`): the update holds a vehicle still, it never stops one;
//  - the interval must hold enough samples for a spread to mean anything (`min_samples`).
// Engine vibration at rest raises the spread above the threshold: there is then no update, which
// loses the aid and nothing else.

#include <cstdint>
#include <string>
#include <vector>

#include "hylo/common/sensor_data.h"
#include "hylo/estimation/imu_options.h"

namespace hylo::estimation {

struct StandstillOptions {
  bool enabled = true;  ///< false: no zero-velocity updates
  /// Largest spread of the samples over the interval (the largest axis' standard deviation), as
  /// a multiple of the white-noise spread the datasheet predicts (density · √rate), for the
  /// accelerometer and the gyro alike (>= 1).
  double max_spread_ratio = 3.0;
  double max_speed_mps = 0.1;        ///< estimated speed above which it moves, m/s (> 0)
  double velocity_noise_mps = 0.01;  ///< standard deviation of the v = 0 measurement, m/s (> 0)
  int min_samples = 5;               ///< IMU samples the interval must hold (>= 3)

  bool IsValid(std::string* why) const;
};

/// The test over one interval, with its figures (for traces and tests).
struct StandstillTest {
  bool at_rest = false;
  int samples = 0;           ///< IMU samples inside the interval
  double accel_ratio = 0.0;  ///< accelerometer spread / datasheet spread (inf without noise)
  double gyro_ratio = 0.0;   ///< gyro spread / datasheet spread
  double speed_mps = 0.0;    ///< the estimate's speed the test was given
};

/// Whether the IMU `samples` stamped within [t0_ns, t1_ns] show the vehicle at rest, given the
/// estimate's speed `speed_mps` (the back-ends give the last update's, at t0_ns). Always false
/// when the options or the IMU are off.
StandstillTest TestStandstill(const std::vector<ImuSample>& samples, int64_t t0_ns, int64_t t1_ns,
                              double speed_mps, const ImuOptions& imu,
                              const StandstillOptions& options);

}  // namespace hylo::estimation
