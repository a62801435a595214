#include "hylo/estimation/sliding_window/sliding_window_options.h"

#include <utility>

#include "hylo/common/enum_names.h"
#include "hylo/common/option_checks.h"

namespace hylo::estimation {
namespace {

using LinearSolver = SlidingWindowOptions::LinearSolver;
using RobustLoss = SlidingWindowOptions::RobustLoss;

const std::pair<LinearSolver, const char*> kSolverNames[] = {
    {LinearSolver::kSparseNormalCholesky, "sparse_normal_cholesky"},
    {LinearSolver::kDenseNormalCholesky, "dense_normal_cholesky"},
    {LinearSolver::kDenseSchur, "dense_schur"},
    {LinearSolver::kSparseSchur, "sparse_schur"},
    {LinearSolver::kDenseQr, "dense_qr"}};

}  // namespace

std::string ToString(LinearSolver solver) { return NameOf(kSolverNames, solver); }
bool ParseLinearSolver(const std::string& name, LinearSolver* solver) {
  return ValueOf(kSolverNames, name, solver);
}
std::string ToString(RobustLoss loss) { return registration::ToString(loss); }
bool ParseRobustLoss(const std::string& name, RobustLoss* loss) {
  return registration::ParseRobustKernelType(name, loss);
}

bool SlidingWindowOptions::IsValid(std::string* why) const {
  return CheckAtLeast("window_size", window_size, 2, "", why) &&
         CheckAtLeast("max_iterations", max_iterations, 1, "", why) &&
         CheckAtLeast("association_rounds", association_rounds, 1, "", why) &&
         CheckAtLeast("pair_points", pair_points, 1, "", why) &&
         CheckPositive("max_solver_time_s", max_solver_time_s, why) &&
         CheckNonNegative("rematch_threshold", rematch_threshold, why) &&
         CheckPositive("robust_loss_scale_m", robust_loss_scale_m, why) &&
         CheckPositive("time_offset_prior_sigma_s", time_offset_prior_sigma_s, why) &&
         CheckPositive("extrinsic_rotation_prior_sigma_rad", extrinsic_rotation_prior_sigma_rad,
                       why) &&
         CheckCalibrationWithoutPairs(why);
}

bool SlidingWindowOptions::CheckCalibrationWithoutPairs(std::string* why) const {
  // A pair's residual would need the calibration at both of its scans' times; not modelled.
  if (!EstimatesCalibration() || !scan_pairs) return true;
  if (why != nullptr) {
    *why = "estimate_time_offset and estimate_extrinsic_rotation need scan_pairs: false";
  }
  return false;
}

}  // namespace hylo::estimation
