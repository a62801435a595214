// Sliding window: the factor graph, the Ceres solve, marginalisation and the covariance of the
// newest state (the scan flow is in sliding_window.cpp).
#include <Eigen/Cholesky>
#include <algorithm>

#include "hylo/common/check.h"
#include "hylo/common/time.h"
#include "hylo/estimation/sliding_window/sliding_window.h"
#include "hylo/estimation/sliding_window/so3_manifold.h"
#include "sliding_window_state.h"

namespace hylo::estimation {
namespace {

ceres::LinearSolverType CeresSolverType(SlidingWindowOptions::LinearSolver solver) {
  using LinearSolver = SlidingWindowOptions::LinearSolver;
  switch (solver) {
    case LinearSolver::kSparseNormalCholesky:
      return ceres::SPARSE_NORMAL_CHOLESKY;
    case LinearSolver::kDenseNormalCholesky:
      return ceres::DENSE_NORMAL_CHOLESKY;
    case LinearSolver::kDenseSchur:
      return ceres::DENSE_SCHUR;
    case LinearSolver::kSparseSchur:
      return ceres::SPARSE_SCHUR;
    case LinearSolver::kDenseQr:
      return ceres::DENSE_QR;
  }
  throw InternalError("unknown linear solver " + std::to_string(static_cast<int>(solver)));
}

}  // namespace

std::vector<BlockRef> StateBlockRefs(WindowState* s, bool use_imu) {
  std::vector<BlockRef> refs{{s->blocks.rotation, 4, true}, {s->blocks.position, 3, false}};
  if (use_imu) refs.push_back({s->blocks.speed_bias, 9, false});
  return refs;
}

bool Touches(const FactorRef& factor, const std::vector<BlockRef>& blocks) {
  for (double* b : factor.blocks) {
    for (const BlockRef& r : blocks) {
      if (r.values == b) return true;
    }
  }
  return false;
}

FactorSet BuildFactors(const Window& window, const MarginalPrior* prior, double* gravity_map,
                       WindowCalibration* calibration, const EstimatorOptions& options,
                       bool use_imu) {
  FactorSet set;
  const auto add = [&set](ceres::CostFunction* cost, std::vector<double*> blocks) {
    set.owned.emplace_back(cost);
    set.refs.push_back({cost, std::move(blocks)});
  };
  if (prior != nullptr && prior->r0.size() > 0) {
    std::vector<double*> blocks;
    for (const BlockRef& b : prior->blocks) blocks.push_back(b.values);
    add(new MarginalPriorFactor(*prior), blocks);
  }
  std::vector<double*> calibration_blocks;
  if (calibration != nullptr) {
    WindowCalibration& c = *calibration;
    if (c.layout.time_offset) {
      add(MakeTimeOffsetPriorFactor(c.time_offset_prior_s, c.time_offset_sigma_s),
          {c.time_offset_s});
    }
    if (c.layout.extrinsic_rotation) {
      add(MakeRotationPriorFactor(c.extrinsic_rotation_prior, c.extrinsic_rotation_sigma_rad),
          {c.extrinsic_rotation});
    }
    for (const BlockRef& b : c.Blocks()) calibration_blocks.push_back(b.values);
  }
  const NoImuOptions& o = options.no_imu;
  for (std::size_t k = 0; k < window.size(); ++k) {
    StateBlocks& x = window[k]->blocks;
    if (!window[k]->matches.empty() && calibration != nullptr) {
      std::vector<double*> blocks{x.rotation, x.position, x.speed_bias};
      blocks.insert(blocks.end(), calibration_blocks.begin(), calibration_blocks.end());
      add(new CalibratedScanPlaneFactor(window[k]->matches, calibration->layout,
                                        window[k]->rate_imu,
                                        calibration->T_imu_lidar_configured.translation()),
          std::move(blocks));
    } else if (!window[k]->matches.empty()) {
      add(new ScanPlaneFactor(window[k]->PlaneSummary()), {x.rotation, x.position});
    }
    for (const ScanPairMatches& pair : window[k]->pairs) {
      if (pair.matches.empty()) continue;
      StateBlocks& e = pair.earlier->blocks;
      add(new ScanPairFactor(pair.matches), {x.rotation, x.position, e.rotation, e.position});
    }
    if (use_imu && window[k]->at_rest) {
      add(new ZeroVelocityFactor(options.standstill.velocity_noise_mps), {x.speed_bias});
    }
    if (k == 0) continue;
    StateBlocks& w = window[k - 1]->blocks;
    if (use_imu && window[k]->imu != nullptr) {
      add(new ImuFactor(*window[k]->imu), {w.rotation, w.position, w.speed_bias, x.rotation,
                                           x.position, x.speed_bias, gravity_map});
    } else if (!use_imu && k >= 2) {
      StateBlocks& v = window[k - 2]->blocks;
      const double dt_ab = NanosToSeconds(window[k - 1]->t_ns - window[k - 2]->t_ns);
      const double dt_bc = NanosToSeconds(window[k]->t_ns - window[k - 1]->t_ns);
      add(MakeConstantVelocityFactor(dt_ab, dt_bc, o.cv_translation_noise, o.cv_rotation_noise),
          {v.rotation, v.position, w.rotation, w.position, x.rotation, x.position});
    }
  }
  return set;
}

void SlidingWindow::Solve(SolveReport* report, double budget_s) {
  const FactorSet factors = BuildFactors(window_, prior_.get(), gravity_map_, calibration_.get(),
                                         options_, imu_options_.enabled);
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  static SO3Manifold manifold;  // stateless
  for (const auto& s : window_) {
    for (const BlockRef& b : StateBlockRefs(s.get(), imu_options_.enabled)) {
      problem.AddParameterBlock(b.values, b.ambient_size, b.rotation ? &manifold : nullptr);
    }
  }
  for (double* g : GlobalBlocks()) problem.AddParameterBlock(g, 3);
  // At rest neither a clock offset nor the extrinsic moves a scan's points relative to the
  // IMU's motion: the calibration would wander on noise. It waits for the vehicle to move,
  // and stays while the caller holds it (SetCalibrationHeld: a search's scratch map).
  const bool window_at_rest =
      std::all_of(window_.begin() + 1, window_.end(), [](const auto& s) { return s->at_rest; });
  for (const BlockRef& b : CalibrationBlocks()) {
    problem.AddParameterBlock(b.values, b.ambient_size, b.rotation ? &manifold : nullptr);
    if (window_at_rest || calibration_held_) problem.SetParameterBlockConstant(b.values);
  }
  for (const FactorRef& f : factors.refs) {
    problem.AddResidualBlock(const_cast<ceres::CostFunction*>(f.cost), nullptr, f.blocks);
  }
  const SlidingWindowOptions& o = options_.sliding_window;
  ceres::Solver::Options solver;
  solver.linear_solver_type = CeresSolverType(o.linear_solver);
  solver.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  solver.max_num_iterations = o.max_iterations;
  solver.max_solver_time_in_seconds = std::max(budget_s, 1e-3);
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver, &problem, &summary);
  report->iterations = static_cast<int>(summary.iterations.size()) - 1;  // [0] is the start
  report->converged = summary.termination_type == ceres::CONVERGENCE;
  // Ceres ends without convergence when out of iterations or out of time.
  report->out_of_time =
      summary.termination_type == ceres::NO_CONVERGENCE && report->iterations < o.max_iterations;
}

void SlidingWindow::MarginalizeOldest() {
  WindowState* oldest = window_.front().get();
  if (oldest->holds_scan) finalized_.push_back(StateAt(0));  // no later scan can correct it
  if (!options_.sliding_window.marginalize) {
    prior_.reset();  // what the oldest state knew is forgotten with it
  } else {
    const FactorSet all = BuildFactors(window_, prior_.get(), gravity_map_, calibration_.get(),
                                       options_, imu_options_.enabled);
    std::vector<BlockRef> order = StateBlockRefs(oldest, imu_options_.enabled);
    const int num_marginalized = static_cast<int>(order.size());
    std::vector<FactorRef> touching;
    for (const FactorRef& f : all.refs) {
      if (Touches(f, order)) touching.push_back(f);
    }
    // The kept blocks: every other block those factors use, in window order, then gravity.
    std::vector<BlockRef> candidates;
    for (std::size_t k = 1; k < window_.size(); ++k) {
      for (const BlockRef& b : StateBlockRefs(window_[k].get(), imu_options_.enabled)) {
        candidates.push_back(b);
      }
    }
    for (double* g : GlobalBlocks()) candidates.push_back({g, 3, false});
    for (const BlockRef& b : CalibrationBlocks()) candidates.push_back(b);
    for (const BlockRef& b : candidates) {
      const auto uses = [&b](const FactorRef& f) { return Touches(f, {b}); };
      if (std::any_of(touching.begin(), touching.end(), uses)) order.push_back(b);
    }
    prior_ = std::make_unique<MarginalPrior>(Marginalize(touching, order, num_marginalized));
  }
  // The pairs with the oldest scan are in the prior now (they touched its blocks).
  for (auto& state : window_) {
    std::vector<ScanPairMatches>& pairs = state->pairs;
    pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                               [oldest](const ScanPairMatches& p) { return p.earlier == oldest; }),
                pairs.end());
  }
  window_.pop_front();
  window_.front()->imu.reset();  // its factor linked the state just removed
}

void SlidingWindow::ComputeCovariance() {
  // Marginal covariance of the newest state: the newest block columns of H⁻¹, where H is the
  // Gauss-Newton information of the whole window at the estimate (the marginal prior holds
  // what the removed states knew).
  const FactorSet all = BuildFactors(window_, prior_.get(), gravity_map_, calibration_.get(),
                                     options_, imu_options_.enabled);
  // The calibration's blocks first, so that the newest state and gravity stay the last columns.
  std::vector<BlockRef> order = CalibrationBlocks();
  std::vector<int> offsets;
  const int calibration_dim = TangentOffsets(order, &offsets);
  for (const auto& s : window_) {
    for (const BlockRef& b : StateBlockRefs(s.get(), imu_options_.enabled)) order.push_back(b);
  }
  for (double* g : GlobalBlocks()) order.push_back({g, 3, false});
  Eigen::MatrixXd H;
  Eigen::VectorXd g;
  Linearize(all.refs, order, &H, &g);
  const int n = static_cast<int>(H.rows());
  // The newest state's 15 columns, then gravity's 3: the order of nav_state.h.
  const int dim = imu_options_.enabled ? kImuFactorDim + 3 : 6;
  // A tiny ridge keeps unobserved directions (e.g. no lidar yet) finite instead of NaN.
  H.diagonal().array() += 1e-9;
  Eigen::MatrixXd wanted = Eigen::MatrixXd::Zero(n, calibration_dim + dim);
  wanted.leftCols(calibration_dim) = Eigen::MatrixXd::Identity(n, n).leftCols(calibration_dim);
  wanted.rightCols(dim) = Eigen::MatrixXd::Identity(n, n).rightCols(dim);
  const Eigen::MatrixXd columns = H.ldlt().solve(wanted);
  const Eigen::MatrixXd P = columns.bottomRightCorner(dim, dim);
  calibration_covariance_ = columns.topLeftCorner(calibration_dim, calibration_dim);
  covariance_ = initial_covariance_;
  covariance_.topRows(dim).setZero();
  covariance_.leftCols(dim).setZero();
  // Without an IMU only [θ, p] are estimated; velocity (a finite difference), the biases and
  // gravity keep their initial values, like the extrinsic.
  covariance_.topLeftCorner(dim, dim) = 0.5 * (P + P.transpose());
}

}  // namespace hylo::estimation
