#pragma once
// Sliding-window smoother back-end: the last N scan states (pose, velocity, gyro and accel
// biases) optimised together with Ceres over
//   - IMU preintegration factors between consecutive states (imu_preintegration.h) whose
//     15-row residual includes the bias random walk, or without an IMU a constant-velocity
//     factor over three consecutive poses;
//   - point-to-plane factors of every scan in the window against the shared map planes;
//   - a Gaussian prior from marginalising the states that left the window (marginalization.h).
// With an IMU the gravity vector is estimated too (one block shared by the window, as the
// IESKF's δg); the extrinsic is held at its initial value.
//
// Plane association: only the newest scan is associated again between solver rounds. Once a
// scan has been registered the pipeline inserts its points into the map, so searching the map
// again for an older scan would find its own points and fit planes through them, which pins
// the pose instead of measuring it; older scans keep the planes found while they were newest
// (their residuals still move with their poses).

#include <deque>
#include <memory>
#include <vector>

#include "hylo/estimation/estimator.h"
#include "hylo/estimation/sliding_window_options.h"

namespace hylo::estimation {

struct WindowState;   // sliding_window.cpp
struct MarginalPrior;  // marginalization.h

class SlidingWindow final : public Estimator {
 public:
  /// Throws hylo::InternalError naming the field when `options` is not valid.
  explicit SlidingWindow(const Options& options);
  ~SlidingWindow() override;

  /// Clears the window and starts again from `state` (also used on relocalization).
  void Initialize(const NavState& state, const StateCovariance& covariance) override;
  void AddImu(const ImuSample& sample) override;
  NavState PredictAt(int64_t t_ns) const override;
  UpdateSummary Update(const DeskewedScan& scan,
                       const registration::PlaneMatcher& planes) override;

  bool initialized() const override { return initialized_; }
  const NavState& state() const override { return state_; }
  StateCovariance Covariance() const override { return covariance_; }

  /// States currently in the window, oldest first (for tests and diagnostics).
  std::vector<NavState> WindowStates() const;

 private:
  struct SolveReport {
    int iterations = 0;
    bool converged = false;
  };

  void AppendState(const DeskewedScan& scan);                     // sliding_window.cpp
  void SetNewestScan(const DeskewedScan& scan);
  void MarginalizeOldest();                                       // sliding_window.cpp
  void Solve(SolveReport* report, double budget_s);               // sliding_window_solve.cpp
  std::size_t AssociateNewest(const registration::PlaneMatcher& planes);
  void SearchYaw(const registration::PlaneMatcher& planes);
  void Reweight();
  void FinishUpdate(UpdateSummary* summary);
  void ComputeCovariance();
  NavState StateAt(std::size_t index) const;
  std::vector<double*> GlobalBlocks();  // blocks shared by the window (gravity with an IMU)

  Options options_;
  bool initialized_ = false;
  NavState state_;                      // newest state (time, gravity, extrinsic included)
  double gravity_map_[3] = {0.0, 0.0, -9.81};  // estimated gravity block (IMU mode), m/s²
  StateCovariance covariance_ = StateCovariance::Identity();
  StateCovariance initial_covariance_ = StateCovariance::Identity();
  std::deque<std::unique_ptr<WindowState>> window_;  // oldest first; stable block addresses
  std::unique_ptr<MarginalPrior> prior_;
  std::vector<ImuSample> imu_;          // buffered samples, time order
  Eigen::Vector3d omega_cv_imu_ = Eigen::Vector3d::Zero();  // no-IMU: body rate, rad/s
};

}  // namespace hylo::estimation
