#pragma once
// Static IMU initialisation: with the vehicle at rest, the mean specific force is gravity seen
// in the IMU frame (roll, pitch and the gravity magnitude), the mean rate is the gyro bias.
// Yaw is unobservable and set to zero (the map frame is defined by the first pose).
// A vehicle that moves meanwhile (a log that starts on the move) still gets a start: roll and
// pitch from the mean specific force, which then also holds the vehicle's mean acceleration,
// and no gyro bias (the mean rate is the turn); the caller starts it with wider uncertainty.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "hylo/common/sensor_data.h"
#include "hylo/estimation/nav_state.h"

namespace hylo::estimation {

struct ImuInitializerOptions {
  double duration_s = 1.0;               ///< rest period averaged, s (> 0)
  double max_accel_std_mps2 = 0.15;      ///< larger spread of |a| means moving, m/s² (> 0)
  double max_gyro_std_radps = 0.02;      ///< larger spread of ω means moving, rad/s (> 0)
  double max_gyro_mean_radps = 0.05;     ///< larger mean rate is turning, not bias, rad/s (> 0)
  double gravity_tolerance_mps2 = 0.3;   ///< | |mean a| − g | must stay below, m/s² (> 0)
  bool IsValid(std::string* why) const;
};

class ImuInitializer {
 public:
  /// kDone: at rest; kMoving: the vehicle moves (state() is the moving estimate, message()
  /// says what showed it); kFailed: unusable data (e.g. accelerations in the wrong unit).
  enum class Status { kCollecting, kDone, kMoving, kFailed };

  ImuInitializer(const ImuInitializerOptions& options, double gravity_mps2);

  /// Adds a sample; once `duration_s` is covered, decides (kDone or kFailed).
  Status Add(const ImuSample& sample);

  Status status() const { return status_; }
  /// The initial state (kDone, kMoving): rotation from gravity, gyro bias, t_ns = last sample.
  const NavState& state() const { return state_; }
  /// Why it failed (kFailed) or why the vehicle is taken to move (kMoving), with the figures.
  const std::string& message() const { return message_; }

 private:
  void Decide();

  ImuInitializerOptions options_;
  double gravity_mps2_;
  std::vector<ImuSample> samples_;
  Status status_ = Status::kCollecting;
  NavState state_;
  std::string message_;
};

}  // namespace hylo::estimation
