// Sliding window: construction, IMU buffering, prediction and the per-scan update flow (the
// factor graph and the solver are in sliding_window_solve.cpp).
#include "hylo/estimation/sliding_window/sliding_window.h"

#include <algorithm>
#include <cmath>

#include "hylo/common/check.h"
#include "hylo/estimation/imu_propagation.h"
#include "hylo/estimation/lidar_update.h"
#include "hylo/registration/parallel.h"
#include "sliding_window_state.h"
#include "window_search.h"

namespace hylo::estimation {

using namespace state_index;  // NOLINT: index names only

SlidingWindow::SlidingWindow(const EstimatorOptions& options, const ImuOptions& imu)
    : BackendBase(options, imu) {
  const SlidingWindowOptions& o = options.sliding_window;
  if (!o.EstimatesCalibration()) return;
  if (!imu.enabled) {
    throw InternalError(
        "sliding_window.estimate_time_offset/estimate_extrinsic_rotation: "
        "online calibration needs the IMU");
  }
  calibration_ = std::make_unique<WindowCalibration>();
  calibration_->layout = {o.estimate_time_offset, o.estimate_extrinsic_rotation};
  calibration_->time_offset_sigma_s = o.time_offset_prior_sigma_s;
  calibration_->extrinsic_rotation_sigma_rad = o.extrinsic_rotation_prior_sigma_rad;
}

SlidingWindow::~SlidingWindow() = default;

void SlidingWindow::Initialize(const NavState& state, const StateCovariance& covariance) {
  FinalizeWindow();  // a restart (relocalization) ends what the window knew
  Restart(state);
  if (calibration_ != nullptr && !calibration_started_) {
    calibration_->T_imu_lidar_configured = state.T_imu_lidar;  // the configuration's
    calibration_started_ = true;
  } else if (calibration_ != nullptr) {
    // What the marginal prior knew of the calibration goes with the window; the estimate
    // stays, held by the configured prior's width around it.
    calibration_->RecentrePriors();
  }
  initial_covariance_ = 0.5 * (covariance + covariance.transpose());
  covariance_ = initial_covariance_;
  window_.clear();
  auto first = std::make_unique<WindowState>();
  first->t_ns = state.t_ns;
  first->blocks.FromNavState(state);
  window_.push_back(std::move(first));
  Eigen::Map<Eigen::Vector3d>{gravity_map_} = state.gravity_map;
  // The initial covariance becomes the first prior, on [θ, p, v, b_g, b_a, g] (or [θ, p]):
  // the blocks' order is the error-state order of nav_state.h.
  std::vector<BlockRef> blocks = StateBlockRefs(window_.front().get(), imu_options_.enabled);
  for (double* g : GlobalBlocks()) blocks.push_back({g, 3, false});
  const int dim = imu_options_.enabled ? kGravity + 3 : 6;
  const Eigen::MatrixXd information =
      initial_covariance_.topLeftCorner(dim, dim).ldlt().solve(Eigen::MatrixXd::Identity(dim, dim));
  prior_ = std::make_unique<MarginalPrior>(
      PriorFromInformation(blocks, information, Eigen::VectorXd::Zero(dim)));
}

void SlidingWindow::FinalizeWindow() {
  for (std::size_t k = 0; k < window_.size(); ++k) {
    if (!window_[k]->holds_scan) continue;
    finalized_.push_back(StateAt(k));
    window_[k]->holds_scan = false;  // final once
  }
}

std::vector<NavState> SlidingWindow::WindowStates() const {
  std::vector<NavState> states;
  for (std::size_t k = 0; k < window_.size(); ++k) states.push_back(StateAt(k));
  return states;
}

NavState SlidingWindow::StateAt(std::size_t index) const {
  NavState x = window_[index]->blocks.ToNavState(state_);
  x.t_ns = window_[index]->t_ns;
  if (imu_options_.enabled) x.gravity_map = Eigen::Map<const Eigen::Vector3d>(gravity_map_);
  if (calibration_ != nullptr) x.T_imu_lidar = calibration_->T_imu_lidar();
  return x;
}

lie::SE3d SlidingWindow::ObservationPose(std::size_t index) const {
  const NavState x = StateAt(index);
  if (calibration_ == nullptr) return x.T_map_imu();
  return calibration_->ObservationPose(x, window_[index]->rate_imu);
}

std::vector<BlockRef> SlidingWindow::CalibrationBlocks() {
  if (calibration_ == nullptr) return {};
  return calibration_->Blocks();
}

OnlineCalibration SlidingWindow::Calibration() const {
  OnlineCalibration c;
  if (calibration_ == nullptr) return c;
  const Eigen::VectorXd sigma = calibration_covariance_.diagonal().cwiseMax(0.0).cwiseSqrt();
  int next = 0;
  if (calibration_->layout.time_offset) {
    c.time_offset_estimated = true;
    c.time_offset_correction_s = calibration_->time_offset_s[0];
    if (sigma.size() > next) c.time_offset_sigma_s = sigma(next);
    next += 1;
  }
  if (calibration_->layout.extrinsic_rotation) {
    c.extrinsic_rotation_estimated = true;
    c.extrinsic_rotation_correction_rad = calibration_->RotationCorrection().Log();
    if (sigma.size() >= next + 3) c.extrinsic_rotation_sigma_rad = sigma.segment<3>(next);
  }
  return c;
}

std::vector<double*> SlidingWindow::GlobalBlocks() {
  if (!imu_options_.enabled) return {};
  return {gravity_map_};
}

void SlidingWindow::AppendState(const DeskewedScan& scan) {
  const NavState last = StateAt(window_.size() - 1);
  auto next = std::make_unique<WindowState>();
  next->t_ns = scan.t_ns;
  NavState predicted = PredictAt(scan.t_ns);
  if (imu_options_.enabled && !imu_.empty()) {
    next->imu =
        std::make_unique<ImuPreintegration>(last.gyro_bias, last.accel_bias, imu_options_.noise);
    Eigen::Vector3d turned_imu = Eigen::Vector3d::Zero();
    double span_s = 0.0;
    for (const ImuInterval& in : imu_.Intervals(last.t_ns, scan.t_ns)) {
      next->imu->Integrate(in);
      turned_imu += in.gyro_imu * in.dt_s;
      span_s += in.dt_s;
    }
    // The mean rate since the previous state, not a sample's: a sample carries the vibration,
    // which would bias a clock offset estimated from it toward zero. Set once, from the
    // samples before the state: a rate revised when later samples come (a mean centred on the
    // state) moved the older scans' residuals against the newest one's and biased the offset
    // by 3-5 ms on some scenarios.
    if (span_s > 0.0) next->rate_imu = turned_imu / span_s - last.gyro_bias;
    predicted = next->imu->Predict(last, last.gravity_map);
  }
  next->blocks.FromNavState(predicted);
  next->at_rest = TestStandstillBetween(last.t_ns, scan.t_ns, last.v_map_imu).at_rest;
  window_.push_back(std::move(next));
  SetNewestScan(scan);
  imu_.DropBefore(scan.t_ns);
  while (static_cast<int>(window_.size()) > options_.sliding_window.window_size) {
    MarginalizeOldest();
  }
}

void SlidingWindow::SetNewestScan(const DeskewedScan& scan) {
  WindowState& newest = *window_.back();
  newest.holds_scan = true;
  newest.points_imu.clear();
  newest.ranges_m.clear();
  newest.matches.clear();
  newest.MatchesChanged();
  newest.points_imu.reserve(scan.points_lidar.size());
  // With online calibration the points keep the configured extrinsic: the factors correct it.
  const lie::SE3d T_imu_lidar =
      calibration_ != nullptr ? calibration_->T_imu_lidar_configured : state_.T_imu_lidar;
  for (const Eigen::Vector3f& p : scan.points_lidar) {
    const Eigen::Vector3d p_lidar = p.cast<double>();
    newest.points_imu.push_back(T_imu_lidar * p_lidar);
    newest.ranges_m.push_back(p_lidar.norm());
  }
  KeepOwnPoints(&newest);
}

std::vector<lie::SE3d> SlidingWindow::ObservationPoses() const {
  std::vector<lie::SE3d> poses;
  poses.reserve(window_.size());
  for (std::size_t k = 0; k < window_.size(); ++k) poses.push_back(ObservationPose(k));
  return poses;
}

double SlidingWindow::LargestMotionSince(const std::vector<lie::SE3d>& poses) const {
  double largest = 0.0;
  for (std::size_t k = 0; k < window_.size() && k < poses.size(); ++k) {
    const lie::SE3d motion = poses[k].Inverse() * ObservationPose(k);
    largest = std::max({largest, motion.so3().Log().norm(), motion.translation().norm()});
  }
  return largest;
}

bool SlidingWindow::HasEarlierScans() const {
  for (std::size_t k = 0; k + 1 < window_.size(); ++k) {
    if (window_[k]->own_points != nullptr) return true;
  }
  return false;
}

std::size_t SlidingWindow::AssociateNewest(const registration::PlaneMatcher& planes) {
  WindowState& newest = *window_.back();
  const lie::SE3d T_map_imu = ObservationPose(window_.size() - 1);
  newest.matches.clear();
  newest.MatchesChanged();
  const std::size_t n = newest.points_imu.size();
  // Each point's plane on its own slot, then the matches in point order: the same whatever
  // the number of threads.
  point_planes_.resize(n);
  point_matched_.resize(n);
  registration::ParallelFor(n, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const Eigen::Vector3d p_map = T_map_imu * newest.points_imu[i];
      point_matched_[i] = planes.Match(p_map, &point_planes_[i]) &&
                          planes.PassesGate(point_planes_[i].Distance(p_map), newest.ranges_m[i]);
    }
  });
  for (std::size_t i = 0; i < n; ++i) {
    if (!point_matched_[i]) continue;
    newest.matches.push_back({newest.points_imu[i], point_planes_[i], LeastSquaresSqrtWeight(),
                              static_cast<uint32_t>(i)});
  }
  return newest.matches.size();
}

void SlidingWindow::Reweight() {
  // Iteratively reweighted least squares (robust_kernel.h): the kernel's weight at the
  // current estimate, fixed during the next solver round.
  const registration::RobustKernel kernel = options_.sliding_window.Kernel();
  // Without a kernel every weight stays the one the matches were made with.
  if (kernel.type == registration::RobustKernel::Type::kNone) return;
  const double lidar_noise_m = options_.lidar_update.lidar_noise_m;
  for (std::size_t k = 0; k < window_.size(); ++k) {
    const lie::SE3d T_map_imu = ObservationPose(k);
    const Eigen::Matrix3d R = T_map_imu.so3().Matrix();
    const Eigen::Vector3d p = T_map_imu.translation();
    bool changed = false;
    for (PlaneMatch& m : window_[k]->matches) {
      const double w = kernel.Weight(m.plane.Distance(R * m.point_imu + p));
      const double sqrt_weight = std::sqrt(w) / lidar_noise_m;
      changed = changed || sqrt_weight != m.sqrt_weight;
      m.sqrt_weight = sqrt_weight;
    }
    if (changed) window_[k]->MatchesChanged();
    for (ScanPairMatches& pair : window_[k]->pairs) {
      const lie::SE3d T_earlier_map = pair.earlier->blocks.ToNavState(state_).T_map_imu().Inverse();
      for (PlaneMatch& m : pair.matches) {
        const double w = kernel.Weight(m.plane.Distance(T_earlier_map * (T_map_imu * m.point_imu)));
        m.sqrt_weight = std::sqrt(w) / lidar_noise_m;
      }
    }
  }
}

UpdateSummary SlidingWindow::Update(const DeskewedScan& scan,
                                    const registration::PlaneMatcher& planes) {
  UpdateSummary summary;
  summary.num_points = scan.points_lidar.size();
  if (!initialized_) {
    summary.message = "estimator not initialised";
    return summary;
  }
  if (scan.t_ns < state_.t_ns) {
    summary.message = "scan time is before the last state: ignored";
    return summary;
  }
  const NavState before = state_;
  if (scan.t_ns == state_.t_ns) {
    SetNewestScan(scan);  // e.g. the first scan without IMU, registered at the initial time
  } else {
    AppendState(scan);
  }
  WindowState& newest = *window_.back();
  summary.standstill = newest.at_rest;
  if (planes.map().Size() == 0 && !(scans_extend_map_ && HasEarlierScans())) {
    summary.message = "map is empty: prediction only";
  } else {
    Correct(scan, planes, &summary);
  }
  state_ = StateAt(window_.size() - 1);
  if (summary.applied) FinishUpdate(&summary);
  if (!imu_options_.enabled && state_.t_ns > before.t_ns) {
    constant_velocity_.Learn(before, &state_);
    newest.blocks.FromNavState(state_);
  }
  ComputeCovariance();
  return summary;
}

void SlidingWindow::Correct(const DeskewedScan& scan, const registration::PlaneMatcher& planes,
                            UpdateSummary* summary) {
  WindowState& newest = *window_.back();
  const StateBlocks predicted = newest.blocks;
  const NavState predicted_state = StateAt(window_.size() - 1);
  const SlidingWindowOptions& o = options_.sliding_window;
  // The map holds finalized scans only. Where the scans extend it, the window's own scans
  // fill in its gaps at the window's current estimate of their poses: for the wide-basin
  // start always (it wants the nearest geometry), for the planes of the update unless they
  // are paired (scan_pairs).
  std::vector<MapAndWindowSearch::Scan> earlier;
  for (std::size_t k = 0; scans_extend_map_ && k + 1 < window_.size(); ++k) {
    if (window_[k]->own_points == nullptr) continue;
    earlier.push_back({window_[k]->own_points.get(), &window_[k]->points_imu, ObservationPose(k)});
  }
  const MapAndWindowSearch map_and_window(planes.map(), std::move(earlier));
  const registration::PlaneMatcher map_and_window_planes(map_and_window, planes.options());
  const registration::PlaneMatcher& update_planes = o.scan_pairs ? planes : map_and_window_planes;
  const auto associate = [&] {
    return AssociateNewest(update_planes) + (o.scan_pairs ? AssociatePairs(planes.options()) : 0);
  };
  newest.blocks.FromNavState(UpdateStart(
      predicted_state, scan, map_and_window_planes,
      [&](const NavState& candidate) {
        newest.blocks.FromNavState(candidate);
        return associate();
      },
      summary));
  const int min_matches = options_.lidar_update.min_matches;
  std::vector<lie::SE3d> searched_at;  // each state's observation pose at the last search
  for (int round = 0; round < o.association_rounds; ++round) {
    // A search again finds the same planes when no pose moved, and it is most of a round's
    // cost on a dense head; the filter skips it the same way (ieskf.rematch_threshold).
    if (round == 0 || LargestMotionSince(searched_at) > o.rematch_threshold) {
      summary->num_matches = associate();
      searched_at = ObservationPoses();
    }
    if (static_cast<int>(summary->num_matches) < min_matches) {
      summary->message = TooFewMatchesMessage(summary->num_matches, min_matches);
      newest.matches.clear();
      newest.MatchesChanged();
      newest.pairs.clear();
      newest.blocks = predicted;
      summary->applied = false;
      return;
    }
    Reweight();
    SolveReport report;
    Solve(&report, o.max_solver_time_s / o.association_rounds);
    summary->iterations += report.iterations;
    summary->converged = report.converged;
    summary->out_of_time = summary->out_of_time || report.out_of_time;
    summary->applied = true;
  }
  if (summary->iterations == 0) {
    // The budget ended every round before its first iteration (a loaded machine): the state
    // is the prediction, and the update must not be reported as a lidar correction.
    summary->message =
        "the solve's time budget (sliding_window.max_solver_time_s) ended "
        "before its first iteration: the prediction stands";
    newest.blocks = predicted;
    summary->applied = false;
    return;
  }
  LearnFromUpdate(predicted_state, StateAt(window_.size() - 1));
}

void SlidingWindow::FinishUpdate(UpdateSummary* summary) {
  // Residuals, fit and degeneracy from the newest scan's matches at the final estimate.
  const WindowState& newest = *window_.back();
  LidarFit fit(newest.points_imu.size());
  const lie::SE3d T_map_imu = ObservationPose(window_.size() - 1);
  const lie::SO3d R_imu_map = T_map_imu.so3().Inverse();
  std::vector<char> in_fit(newest.points_imu.size(), 0);
  for (const PlaneMatch& m : newest.matches) {
    fit.Add(m.point_index, m.point_imu, R_imu_map * m.plane.normal,
            m.plane.Distance(T_map_imu * m.point_imu), true);
    in_fit[m.point_index] = 1;
  }
  // A point without a map plane is judged by its plane in the latest earlier scan (the map
  // lags the window: it holds finalized scans only).
  for (auto pair = newest.pairs.rbegin(); pair != newest.pairs.rend(); ++pair) {
    const NavState earlier = pair->earlier->blocks.ToNavState(state_);
    const lie::SE3d T_earlier_imu = earlier.T_map_imu().Inverse() * T_map_imu;
    const lie::SO3d R_imu_earlier = T_earlier_imu.so3().Inverse();
    for (const PlaneMatch& m : pair->matches) {
      if (in_fit[m.point_index] != 0) continue;
      fit.Add(m.point_index, m.point_imu, R_imu_earlier * m.plane.normal,
              m.plane.Distance(T_earlier_imu * m.point_imu), true);
      in_fit[m.point_index] = 1;
    }
  }
  fit.Report(options_.lidar_update, summary);
}

}  // namespace hylo::estimation
