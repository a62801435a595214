#pragma once
// The state-estimation strategy: one interface, two back-ends (the IESKF of FAST-LIO2 in
// ieskf/, a sliding-window Ceres smoother in sliding_window/), chosen by the configuration key
// `backend` (EstimatorOptions, estimator_options.h).
//
// What the interface asks of a back-end is what both can do without knowing the other:
// it takes *raw* IMU samples (the smoother preintegrates them between scans, the filter
// propagates), it can predict the nominal state at any time after its last update from the
// buffered IMU (undistortion needs poses inside a scan), and it updates from one deskewed,
// downsampled scan given the shared plane queries on the map. Everything around it (queue,
// initialisation, undistortion, map, localization) is shared code in OdometryPipeline.
//
// Two views of the estimate: the *live* state (state(), after the newest update, what a robot
// steers by) and *finalized* states (TakeFinalized(), each scan's state once the back-end will
// not change it any more). The filter finalizes each state as it updates it; the smoother when
// the state leaves its window, with everything the later scans taught it. Trajectories and
// their errors use finalized states; the odometry stream uses the live one.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "hylo/common/point_types.h"
#include "hylo/common/sensor_data.h"
#include "hylo/estimation/nav_state.h"
#include "hylo/estimation/robust_registration.h"
#include "hylo/registration/plane_matcher.h"

namespace hylo::estimation {

struct EstimatorOptions;  // estimator_options.h
struct ImuOptions;        // imu_options.h

/// A scan after undistortion: every point expressed in the lidar frame at `t_ns` (the scan
/// end), usually downsampled.
struct DeskewedScan {
  int64_t t_ns = 0;         ///< time all points refer to, ns
  PointCloud points_lidar;  ///< m, lidar frame at t_ns
};

/// What one Update did. A failed or partial update keeps the predicted state and says why.
struct UpdateSummary {
  int iterations = 0;            ///< update iterations run
  std::size_t num_points = 0;    ///< points offered
  std::size_t num_matches = 0;   ///< points with an accepted plane in the last iteration
  bool converged = false;        ///< the last step was below the convergence thresholds
  bool applied = false;          ///< the lidar correction was applied (enough matches)
  bool degenerate = false;       ///< some pose direction is (nearly) unobserved
  double min_translation_information = 0.0;  ///< see LidarUpdateOptions, 0..1
  double min_rotation_information = 0.0;     ///< see LidarUpdateOptions, m²
  double rms_residual_m = 0.0;   ///< RMS point-to-plane residual of the matches, m
  /// The IMU showed the vehicle at rest over the interval: the back-end holds v = 0 beside the
  /// scan wherever its update runs (standstill.h).
  bool standstill = false;
  /// The solve stopped at its wall-time budget (sliding_window.max_solver_time_s) before it
  /// converged or ran all its iterations: the state then depends on the machine's speed and
  /// load. Without one iteration the update is not applied (the prediction stands).
  bool out_of_time = false;
  /// Per offered point, its point-to-plane residual at the final state (m), NaN where the
  /// point had no plane. How well the scan fits the map, without a second search of it.
  std::vector<float> point_residuals_m;
  RobustAlignment robust;        ///< the robust registration's start (attempts 0 when off)
  std::string message;           ///< empty when all went well; otherwise why not
};

/// What a back-end estimated online of the sensor set-up's calibration: corrections to the
/// configured values, each with its standard deviation from the estimator's information.
/// Nothing is estimated unless the configuration asks (sliding_window.estimate_*,
/// ieskf.online_extrinsic).
struct OnlineCalibration {
  bool time_offset_estimated = false;
  /// Add to the configured lidar.time_offset_s: a scan stamped t (lidar clock) was taken at
  /// t + time_offset_s + correction on the IMU's clock, s.
  double time_offset_correction_s = 0.0;
  double time_offset_sigma_s = 0.0;
  bool extrinsic_rotation_estimated = false;
  /// R_imu_lidar = Exp(correction) · R_imu_lidar(configured): rotation vector, IMU frame, rad.
  Eigen::Vector3d extrinsic_rotation_correction_rad = Eigen::Vector3d::Zero();
  Eigen::Vector3d extrinsic_rotation_sigma_rad = Eigen::Vector3d::Zero();
  bool extrinsic_translation_estimated = false;
  /// t_imu_lidar = configured + correction: IMU frame, m.
  Eigen::Vector3d extrinsic_translation_correction_m = Eigen::Vector3d::Zero();
  Eigen::Vector3d extrinsic_translation_sigma_m = Eigen::Vector3d::Zero();
};

class Estimator {
 public:
  enum class Backend { kIeskf, kSlidingWindow };

  virtual ~Estimator() = default;

  /// The back-end chosen by options.backend, for the inertial sensor `imu` (or none). Throws
  /// hylo::InternalError naming the field when `options` or `imu` is not valid.
  static std::unique_ptr<Estimator> Create(const EstimatorOptions& options, const ImuOptions& imu);

  /// Starts from `state` with covariance `covariance` (order of nav_state.h). States of an
  /// earlier start that were not finalized yet are finalized first.
  virtual void Initialize(const NavState& state, const StateCovariance& covariance) = 0;
  /// Buffers one IMU sample (samples must come in time order; older ones are ignored).
  virtual void AddImu(const ImuSample& sample) = 0;
  /// Nominal state at `t_ns` propagated from the last update with the buffered IMU (held at
  /// the last sample beyond it). For t_ns before the state time, the state itself.
  virtual NavState PredictAt(int64_t t_ns) const = 0;
  /// PredictAt at each of `times_ns` (ascending), the same states. A back-end with buffered
  /// IMU overrides it to walk its samples once: after a long lidar gap with the IMU running,
  /// a sweep's dozen knots would otherwise each re-integrate every sample of the gap.
  virtual std::vector<NavState> PredictAlong(const std::vector<int64_t>& times_ns) const {
    std::vector<NavState> states;
    states.reserve(times_ns.size());
    for (int64_t t : times_ns) states.push_back(PredictAt(t));
    return states;
  }
  /// Carries the live state forward to `t_ns` on the IMU samples added so far, as the next
  /// Update would (both split the walk at a sample stamp, so the result is the same), when no
  /// scan came for a while: a long lidar gap's propagation is then paid as the IMU arrives,
  /// not all by the first scan after it. Never past a time a scan may still come for. A
  /// back-end that integrates the IMU only at its updates leaves the state where it is.
  virtual void CarryForward(int64_t /*t_ns*/) {}
  /// Whether the scans registered from now on join the map the updates search (SLAM; hybrid
  /// mode once started; odometry off a tiled prior), told before each Update; default true.
  /// A back-end whose scans join the map only once finalized (the smoother) then searches its
  /// newer scans too where the map has too few points; against a fixed prior it must not: its
  /// own scans would vouch for its pose in the scan's health.
  virtual void SetScansExtendMap(bool extend) = 0;
  /// Whether the online calibration (OnlineCalibration) must stay where it is in the next
  /// updates, told before each Update; default false. While searching, the scans register
  /// against a scratch map the same scans built: there the extrinsic's tilt trades against the
  /// accelerometer bias instead of being observed. A back-end without calibration ignores it.
  virtual void SetCalibrationHeld(bool /*held*/) {}
  /// Propagates to scan.t_ns and corrects with point-to-plane residuals from `planes`.
  virtual UpdateSummary Update(const DeskewedScan& scan,
                               const registration::PlaneMatcher& planes) = 0;

  virtual bool initialized() const = 0;
  /// The live state: after the last Update (or Initialize).
  virtual const NavState& state() const = 0;
  /// The full error-state covariance at state(), order of nav_state.h. Blocks a back-end
  /// does not estimate (e.g. a fixed extrinsic) hold their initial values.
  virtual StateCovariance Covariance() const = 0;
  /// 6×6 pose covariance, order [δp (map, m); δθ (IMU frame, rad)] (nav_state.h).
  virtual PoseCovariance6 PoseCovariance() const { return PoseBlock(Covariance()); }

  /// Appends the states finalized since the last call, one per updated scan, oldest first.
  virtual void TakeFinalized(std::vector<NavState>* states) = 0;
  /// The log ended: every state still open becomes final (the smoother's window).
  virtual void Finish() = 0;
  /// The calibration estimated online so far (nothing by default).
  virtual OnlineCalibration Calibration() const { return {}; }
};

/// "ieskf" / "sliding_window".
std::string ToString(Estimator::Backend backend);
bool ParseBackend(const std::string& name, Estimator::Backend* backend);

}  // namespace hylo::estimation
