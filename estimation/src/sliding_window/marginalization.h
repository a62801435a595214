#pragma once
// Marginalisation for the sliding-window smoother (private: uses Ceres types).
//
// The factors touching the oldest state are linearised once, at the current estimate, into
// dense normal equations H δ = −g over the tangent spaces of their blocks; the Schur
// complement removes the oldest state's blocks m and leaves, on the kept blocks k,
//   H* = H_kk − H_km H_mm⁻¹ H_mk        g* = g_k − H_km H_mm⁻¹ g_m
// (Sibley et al., "Sliding window filter with application to planetary landing", JFR 2010;
// Leutenegger et al., OKVIS, IJRR 2015, Sec. IV-D). It is kept as the prior factor
// ½‖r0 + J (x ⊟ x_lin)‖² with JᵀJ = H*, Jᵀr0 = g*, whose Jacobian stays the one at x_lin
// (first-estimate Jacobians for the prior; the kept blocks' other factors are relinearised
// as usual, the documented approximation of VINS-Mono and OKVIS).

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <vector>

namespace hylo::estimation {

/// A parameter block and its tangent space: a rotation (4 → 3, SO3Manifold) or Euclidean.
struct BlockRef {
  double* values = nullptr;
  int ambient_size = 0;
  bool rotation = false;
  int tangent_size() const { return rotation ? 3 : ambient_size; }
};

/// A residual block: its cost function (not owned) and parameter blocks, in order.
struct FactorRef {
  const ceres::CostFunction* cost = nullptr;
  std::vector<double*> blocks;
};

/// The prior r(x) = r0 + J·(x ⊟ x_lin) over `blocks`.
struct MarginalPrior {
  std::vector<BlockRef> blocks;
  std::vector<std::vector<double>> x_lin;  ///< each block's ambient values at linearisation
  Eigen::MatrixXd J;
  Eigen::VectorXd r0;
  int tangent_dim() const { return static_cast<int>(J.cols()); }
};

class MarginalPriorFactor final : public ceres::CostFunction {
 public:
  /// Keeps a reference to `prior`, which must outlive the factor.
  explicit MarginalPriorFactor(const MarginalPrior& prior);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  const MarginalPrior& prior_;
};

/// Dense H = Σ JᵀJ and g = Σ Jᵀr of `factors` at the blocks' current values, over the
/// tangent spaces of `order` (every block a factor uses must be in `order`).
void Linearize(const std::vector<FactorRef>& factors, const std::vector<BlockRef>& order,
               Eigen::MatrixXd* H, Eigen::VectorXd* g);

/// Marginalises the first `num_marginalized` blocks of `order` out of `factors`; the prior
/// is on the remaining blocks at their current values.
MarginalPrior Marginalize(const std::vector<FactorRef>& factors, const std::vector<BlockRef>& order,
                          int num_marginalized);

/// The prior of a Gaussian with information `H` (and zero mean error) on `blocks` at their
/// current values, e.g. the initial covariance's inverse.
MarginalPrior PriorFromInformation(const std::vector<BlockRef>& blocks, const Eigen::MatrixXd& H,
                                   const Eigen::VectorXd& g);

/// Offset of each block of `order` in the stacked tangent vector; returns the total size.
int TangentOffsets(const std::vector<BlockRef>& order, std::vector<int>* offsets);

}  // namespace hylo::estimation
