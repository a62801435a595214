#pragma once
// The state-estimation strategy: one interface, two back-ends (the IESKF of FAST-LIO2 and,
// later, a sliding-window Ceres smoother), chosen by the configuration key `backend`.
//
// What the interface asks of a back-end is what both can do without knowing the other:
// it takes *raw* IMU samples (the smoother preintegrates them between scans, the filter
// propagates), it can predict the nominal state at any time after its last update from the
// buffered IMU (undistortion needs poses inside a scan), and it updates from one deskewed,
// downsampled scan given the shared plane queries on the map. Everything around it (queue,
// initialisation, undistortion, map) is shared code in OdometryPipeline.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>

#include "hylo/estimation/ieskf_options.h"
#include "hylo/estimation/imu_noise.h"
#include "hylo/estimation/measurements.h"
#include "hylo/estimation/nav_state.h"
#include "hylo/estimation/sliding_window_options.h"
#include "hylo/registration/plane_matcher.h"
#include "hylo/registration/point_types.h"

namespace hylo::estimation {

/// A scan after undistortion: every point expressed in the lidar frame at `t_ns` (the scan
/// end), usually downsampled.
struct DeskewedScan {
  int64_t t_ns = 0;                      ///< time all points refer to, ns
  registration::PointCloud points_lidar; ///< m, lidar frame at t_ns
};

/// What one Update did. A failed or partial update keeps the predicted state and says why.
struct UpdateSummary {
  int iterations = 0;            ///< update iterations run
  std::size_t num_points = 0;    ///< points offered
  std::size_t num_matches = 0;   ///< points with an accepted plane in the last iteration
  bool converged = false;        ///< the last step was below the convergence thresholds
  bool applied = false;          ///< the lidar correction was applied (enough matches)
  bool degenerate = false;       ///< some pose direction is (nearly) unobserved
  double min_translation_information = 0.0;  ///< see IeskfOptions, 0..1
  double min_rotation_information = 0.0;     ///< see IeskfOptions, m²
  double rms_residual_m = 0.0;   ///< RMS point-to-plane residual of the matches, m
  std::string message;           ///< empty when all went well; otherwise why not
};

class Estimator {
 public:
  enum class Backend { kIeskf, kSlidingWindow };

  struct Options {
    Backend backend = Backend::kIeskf;  ///< from the `backend` key
    bool use_imu = true;                ///< false: constant-velocity model, no IMU (imu: none)
    ImuNoise imu_noise;                 ///< continuous-time IMU noise
    IeskfOptions ieskf;                 ///< used when backend == kIeskf
    SlidingWindowOptions sliding_window;  ///< used when backend == kSlidingWindow
    bool IsValid(std::string* why) const;
  };

  virtual ~Estimator() = default;

  /// The back-end chosen by options.backend. Throws hylo::InternalError for invalid options
  /// and std::invalid_argument for a back-end that is not built.
  static std::unique_ptr<Estimator> Create(const Options& options);

  /// Starts from `state` with covariance `covariance` (order of nav_state.h).
  virtual void Initialize(const NavState& state, const StateCovariance& covariance) = 0;
  /// Buffers one IMU sample (samples must come in time order; older ones are ignored).
  virtual void AddImu(const ImuSample& sample) = 0;
  /// Nominal state at `t_ns` propagated from the last update with the buffered IMU (held at
  /// the last sample beyond it). For t_ns before the state time, the state itself.
  virtual NavState PredictAt(int64_t t_ns) const = 0;
  /// Propagates to scan.t_ns and corrects with point-to-plane residuals from `planes`.
  virtual UpdateSummary Update(const DeskewedScan& scan,
                               const registration::PlaneMatcher& planes) = 0;

  virtual bool initialized() const = 0;
  /// The state after the last Update (or Initialize).
  virtual const NavState& state() const = 0;
  /// The full error-state covariance at state(), order of nav_state.h. Blocks a back-end
  /// does not estimate (e.g. a fixed extrinsic) hold their initial values.
  virtual StateCovariance Covariance() const = 0;
  /// 6×6 pose covariance, order [δp (map, m); δθ (IMU frame, rad)] (nav_state.h).
  virtual PoseCovariance6 PoseCovariance() const { return PoseBlock(Covariance()); }
};

/// "ieskf" / "sliding_window".
std::string ToString(Estimator::Backend backend);
bool ParseBackend(const std::string& name, Estimator::Backend* backend);

}  // namespace hylo::estimation
