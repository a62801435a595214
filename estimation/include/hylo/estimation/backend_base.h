#pragma once
// What every back-end keeps besides its own estimate, written once: the validated options, the
// live state, the IMU samples since the last update, the constant-velocity model used without
// an IMU, and the states finalized but not taken yet. A back-end derives from it and
// implements Initialize, Update, Covariance and Finish (Estimator); prediction, IMU buffering
// and the hand-over of finalized states are the same for all.

#include <cstddef>
#include <functional>
#include <vector>

#include "hylo/estimation/estimator.h"
#include "hylo/estimation/estimator_options.h"
#include "hylo/estimation/imu_buffer.h"
#include "hylo/estimation/imu_options.h"
#include "hylo/estimation/no_imu_motion.h"
#include "hylo/estimation/robust_registration.h"
#include "hylo/estimation/standstill.h"

namespace hylo::estimation {

class BackendBase : public Estimator {
 public:
  void AddImu(const ImuSample& sample) final { imu_.Add(sample); }
  NavState PredictAt(int64_t t_ns) const final;
  std::vector<NavState> PredictAlong(const std::vector<int64_t>& times_ns) const final;
  bool initialized() const final { return initialized_; }
  const NavState& state() const final { return state_; }
  void TakeFinalized(std::vector<NavState>* states) final;
  void SetScansExtendMap(bool extend) final { scans_extend_map_ = extend; }
  void SetCalibrationHeld(bool held) final { calibration_held_ = held; }

 protected:
  /// Throws hylo::InternalError naming the field when `options` or `imu` is not valid.
  BackendBase(const EstimatorOptions& options, const ImuOptions& imu);
  /// The shared part of Initialize: the live state, a fresh motion model, the IMU samples from
  /// `state`'s time on.
  void Restart(const NavState& state);
  /// The pose a lidar update starts from: `predicted`, turned by the no-IMU yaw search (which
  /// scores a candidate by `count_matches`) and aligned by the robust registration, where
  /// they are on; the alignment is reported in summary->robust.
  NavState UpdateStart(const NavState& predicted, const DeskewedScan& scan,
                       const registration::PlaneMatcher& planes,
                       const std::function<std::size_t(const NavState&)>& count_matches,
                       UpdateSummary* summary);
  /// After an applied update that went from `predicted` to `updated`: how far the motion
  /// model was off, for the robust registration's adaptive threshold.
  void LearnFromUpdate(const NavState& predicted, const NavState& updated);
  /// The standstill test over the buffered IMU samples in [t0_ns, t1_ns], for an estimate
  /// moving at `v_map` (standstill.h); call it before the samples are dropped.
  StandstillTest TestStandstillBetween(int64_t t0_ns, int64_t t1_ns,
                                       const Eigen::Vector3d& v_map) const;

  const EstimatorOptions options_;
  const ImuOptions imu_options_;
  bool initialized_ = false;
  NavState state_;                      // the live state
  ImuBuffer imu_;                       // samples since the last update
  ConstantVelocity constant_velocity_;  // the motion model without an IMU
  RobustRegistration robust_;           // the wide-basin start, when enabled
  std::vector<NavState> finalized_;     // finalized states not taken yet
  bool scans_extend_map_ = true;        // SetScansExtendMap
  bool calibration_held_ = false;       // SetCalibrationHeld
};

}  // namespace hylo::estimation
