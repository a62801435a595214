// Sliding window: construction, IMU buffering, prediction and the per-scan update flow (the
// factor graph and the solver are in sliding_window_solve.cpp).
#include "hylo/estimation/sliding_window.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "hylo/common/check.h"
#include "hylo/common/time.h"
#include "hylo/estimation/imu_propagation.h"
#include "sliding_window_state.h"

namespace hylo::estimation {

using namespace state_index;  // NOLINT: index names only

SlidingWindow::SlidingWindow(const Options& options) : options_(options) {
  std::string why;
  if (!options_.IsValid(&why)) throw InternalError("invalid options: " + why);
}

SlidingWindow::~SlidingWindow() = default;

void SlidingWindow::Initialize(const NavState& state, const StateCovariance& covariance) {
  state_ = state;
  initial_covariance_ = 0.5 * (covariance + covariance.transpose());
  covariance_ = initial_covariance_;
  omega_cv_imu_.setZero();
  window_.clear();
  auto first = std::make_unique<WindowState>();
  first->t_ns = state.t_ns;
  first->blocks.FromNavState(state);
  window_.push_back(std::move(first));
  Eigen::Map<Eigen::Vector3d>{gravity_map_} = state.gravity_map;
  // The initial covariance becomes the first prior, on [θ, p, v, b_g, b_a, g] (or [θ, p]):
  // the blocks' order is the error-state order of nav_state.h.
  std::vector<BlockRef> blocks = StateBlockRefs(window_.front().get(), options_.use_imu);
  for (double* g : GlobalBlocks()) blocks.push_back({g, 3, false});
  const int dim = options_.use_imu ? kGravity + 3 : 6;
  const Eigen::MatrixXd information =
      initial_covariance_.topLeftCorner(dim, dim).ldlt().solve(Eigen::MatrixXd::Identity(dim, dim));
  prior_ = std::make_unique<MarginalPrior>(
      PriorFromInformation(blocks, information, Eigen::VectorXd::Zero(dim)));
  initialized_ = true;
  auto first_after = std::upper_bound(imu_.begin(), imu_.end(), state.t_ns,
                                      [](int64_t t, const ImuSample& s) { return t < s.t_ns; });
  if (first_after != imu_.begin()) imu_.erase(imu_.begin(), first_after - 1);
}

void SlidingWindow::AddImu(const ImuSample& sample) {
  if (!options_.use_imu) return;
  if (!imu_.empty() && sample.t_ns <= imu_.back().t_ns) return;  // the queue sorts; ignore
  imu_.push_back(sample);
}

NavState SlidingWindow::PredictAt(int64_t t_ns) const {
  return PredictNominal(state_, imu_, options_.use_imu, omega_cv_imu_, t_ns);
}

std::vector<NavState> SlidingWindow::WindowStates() const {
  std::vector<NavState> states;
  for (std::size_t k = 0; k < window_.size(); ++k) states.push_back(StateAt(k));
  return states;
}

NavState SlidingWindow::StateAt(std::size_t index) const {
  NavState x = window_[index]->blocks.ToNavState(state_);
  x.t_ns = window_[index]->t_ns;
  if (options_.use_imu) x.gravity_map = Eigen::Map<const Eigen::Vector3d>(gravity_map_);
  return x;
}

std::vector<double*> SlidingWindow::GlobalBlocks() {
  if (!options_.use_imu) return {};
  return {gravity_map_};
}

void SlidingWindow::AppendState(const DeskewedScan& scan) {
  const NavState last = StateAt(window_.size() - 1);
  auto next = std::make_unique<WindowState>();
  next->t_ns = scan.t_ns;
  NavState predicted = PredictAt(scan.t_ns);
  if (options_.use_imu && !imu_.empty()) {
    next->imu = std::make_unique<ImuPreintegration>(last.gyro_bias, last.accel_bias,
                                                    options_.imu_noise);
    for (const ImuInterval& in : MakeIntervals(imu_, last.t_ns, scan.t_ns)) {
      next->imu->Integrate(in);
    }
    predicted = next->imu->Predict(last, last.gravity_map);
  }
  next->blocks.FromNavState(predicted);
  window_.push_back(std::move(next));
  SetNewestScan(scan);
  // Keep the last sample at or before the scan: the next interval interpolates from it.
  auto first_after = std::upper_bound(imu_.begin(), imu_.end(), scan.t_ns,
                                      [](int64_t t, const ImuSample& s) { return t < s.t_ns; });
  if (first_after != imu_.begin()) imu_.erase(imu_.begin(), first_after - 1);
  while (static_cast<int>(window_.size()) > options_.sliding_window.window_size) {
    MarginalizeOldest();
  }
}

void SlidingWindow::SetNewestScan(const DeskewedScan& scan) {
  WindowState& newest = *window_.back();
  newest.points_imu.clear();
  newest.ranges_m.clear();
  newest.matches.clear();
  newest.points_imu.reserve(scan.points_lidar.size());
  for (const Eigen::Vector3f& p : scan.points_lidar) {
    const Eigen::Vector3d p_lidar = p.cast<double>();
    newest.points_imu.push_back(state_.T_imu_lidar * p_lidar);
    newest.ranges_m.push_back(p_lidar.norm());
  }
}

std::size_t SlidingWindow::AssociateNewest(const registration::PlaneMatcher& planes) {
  WindowState& newest = *window_.back();
  const lie::SE3d T_map_imu = StateAt(window_.size() - 1).T_map_imu();
  newest.matches.clear();
  registration::Plane plane;
  for (std::size_t i = 0; i < newest.points_imu.size(); ++i) {
    const Eigen::Vector3d p_map = T_map_imu * newest.points_imu[i];
    if (!planes.Match(p_map, &plane)) continue;
    if (!planes.PassesGate(plane.Distance(p_map), newest.ranges_m[i])) continue;
    newest.matches.push_back({newest.points_imu[i], plane, 1.0});
  }
  return newest.matches.size();
}

void SlidingWindow::SearchYaw(const registration::PlaneMatcher& planes) {
  // The IESKF's no-IMU aid (Ieskf::SearchYaw): a hand-held sensor at a low scan rate turns
  // more between scans than plane association can recover from.
  const SlidingWindowOptions& o = options_.sliding_window;
  const double range = o.no_imu_yaw_search_deg * M_PI / 180.0;
  const double step = o.no_imu_yaw_search_step_deg * M_PI / 180.0;
  StateBlocks& blocks = window_.back()->blocks;
  const NavState prior = StateAt(window_.size() - 1);
  NavState best = prior;
  std::size_t best_matches = 0;
  for (double yaw = -range; yaw <= range + 1e-9; yaw += step) {
    NavState candidate = prior;
    candidate.R_map_imu = lie::SO3d::Exp(Eigen::Vector3d(0.0, 0.0, yaw)) * prior.R_map_imu;
    blocks.FromNavState(candidate);
    const std::size_t matches = AssociateNewest(planes);
    if (matches > best_matches) {
      best_matches = matches;
      best = candidate;
    }
  }
  blocks.FromNavState(best);
}

void SlidingWindow::Reweight() {
  // Iteratively reweighted least squares: the robust loss's weight ρ'(r²) at the current
  // estimate, fixed during the next solver round (Zhang, "Parameter estimation techniques",
  // IVC 1997, Sec. 5.1). Huber: 1 inside c, c/|r| outside; Cauchy: 1/(1 + r²/c²).
  const SlidingWindowOptions& o = options_.sliding_window;
  const double c = o.robust_loss_scale_m;
  const bool huber = o.robust_loss == "huber", cauchy = o.robust_loss == "cauchy";
  for (std::size_t k = 0; k < window_.size(); ++k) {
    const lie::SE3d T_map_imu = StateAt(k).T_map_imu();
    const Eigen::Matrix3d R = T_map_imu.so3().Matrix();
    const Eigen::Vector3d p = T_map_imu.translation();
    for (PlaneMatch& m : window_[k]->matches) {
      const double r = std::abs(m.plane.Distance(R * m.point_imu + p));
      double w = 1.0;
      if (huber) {
        w = r <= c ? 1.0 : c / r;
      } else if (cauchy) {
        w = 1.0 / (1.0 + (r * r) / (c * c));
      }
      m.sqrt_weight = std::sqrt(w) / o.lidar_noise_m;
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
  const StateBlocks predicted = newest.blocks;
  if (planes.map().Size() == 0) {
    summary.message = "map is empty: prediction only";
  } else {
    const SlidingWindowOptions& o = options_.sliding_window;
    if (!options_.use_imu && o.no_imu_yaw_search_deg > 0.0) SearchYaw(planes);
    for (int round = 0; round < o.association_rounds; ++round) {
      summary.num_matches = AssociateNewest(planes);
      if (static_cast<int>(summary.num_matches) < o.min_matches) {
        summary.message = "too few plane matches (" + std::to_string(summary.num_matches) +
                          " < " + std::to_string(o.min_matches) + "): prediction only";
        newest.matches.clear();
        newest.blocks = predicted;
        summary.applied = false;
        break;
      }
      Reweight();
      SolveReport report;
      Solve(&report, o.max_solver_time_s / o.association_rounds);
      summary.iterations += report.iterations;
      summary.converged = report.converged;
      summary.applied = true;
    }
  }
  state_ = StateAt(window_.size() - 1);
  if (summary.applied) FinishUpdate(&summary);
  if (!options_.use_imu && state_.t_ns > before.t_ns) {
    const double dt = NanosToSeconds(state_.t_ns - before.t_ns);
    state_.v_map_imu = (state_.p_map_imu - before.p_map_imu) / dt;
    omega_cv_imu_ = lie::Minus(state_.R_map_imu, before.R_map_imu) / dt;
    newest.blocks.FromNavState(state_);
  }
  ComputeCovariance();
  return summary;
}

void SlidingWindow::FinishUpdate(UpdateSummary* summary) {
  // Degeneracy and fit from the newest scan's matches at the final estimate, as the IESKF.
  const WindowState& newest = *window_.back();
  Eigen::Matrix3d translation_info = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d rotation_info = Eigen::Matrix3d::Zero();
  double sum_sq = 0.0;
  const lie::SE3d T_map_imu = state_.T_map_imu();
  const lie::SO3d R_imu_map = state_.R_map_imu.Inverse();
  for (const PlaneMatch& m : newest.matches) {
    const Eigen::Vector3d n_imu = R_imu_map * m.plane.normal;
    const Eigen::Vector3d h_theta = m.point_imu.cross(n_imu);
    translation_info += m.plane.normal * m.plane.normal.transpose();
    rotation_info += h_theta * h_theta.transpose();
    const double r = m.plane.Distance(T_map_imu * m.point_imu);
    sum_sq += r * r;
  }
  const double n = static_cast<double>(std::max<std::size_t>(newest.matches.size(), 1));
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(translation_info / n, Eigen::EigenvaluesOnly);
  summary->min_translation_information = eig.eigenvalues()(0);
  eig.computeDirect(rotation_info / n, Eigen::EigenvaluesOnly);
  summary->min_rotation_information = eig.eigenvalues()(0);
  const SlidingWindowOptions& o = options_.sliding_window;
  summary->degenerate = summary->min_translation_information < o.min_translation_information ||
                        summary->min_rotation_information < o.min_rotation_information;
  summary->rms_residual_m = std::sqrt(sum_sq / n);
  if (summary->degenerate) {
    summary->message = "degenerate geometry: a pose direction is unobserved";
  }
}

}  // namespace hylo::estimation
