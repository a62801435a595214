#include "marginalization.h"

#include <Eigen/Eigenvalues>
#include <algorithm>

#include "hylo/common/check.h"
#include "hylo/estimation/sliding_window/so3_manifold.h"
#include "hylo/lie/so3.h"

namespace hylo::estimation {
namespace {

using RowMajorMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// Eigenvalues below this are treated as unobserved directions (information units of the
// whitened residuals, so an absolute threshold, as VINS-Mono's).
constexpr double kMinEigenvalue = 1e-8;

lie::SO3d Rotation(const double* q_xyzw) { return lie::SO3d(Eigen::Quaterniond(q_xyzw)); }

// x ⊟ x_lin of one block (tangent).
Eigen::VectorXd BlockMinus(const BlockRef& block, const double* x, const double* x_lin) {
  if (block.rotation) return lie::Minus(Rotation(x), Rotation(x_lin));
  return Eigen::Map<const Eigen::VectorXd>(x, block.ambient_size) -
         Eigen::Map<const Eigen::VectorXd>(x_lin, block.ambient_size);
}

// Ambient Jacobian (rows × ambient, row-major) → tangent Jacobian.
Eigen::MatrixXd ToTangent(const BlockRef& block, const RowMajorMatrix& ambient) {
  if (!block.rotation) return ambient;
  return ambient * RotationPlusJacobian(block.values);
}

// Pseudo-inverse of a symmetric positive semi-definite matrix.
Eigen::MatrixXd PseudoInverse(const Eigen::MatrixXd& H) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (H + H.transpose()));
  const Eigen::VectorXd inv =
      (eig.eigenvalues().array() > kMinEigenvalue).select(eig.eigenvalues().array().inverse(), 0.0);
  return eig.eigenvectors() * inv.asDiagonal() * eig.eigenvectors().transpose();
}

}  // namespace

int TangentOffsets(const std::vector<BlockRef>& order, std::vector<int>* offsets) {
  offsets->clear();
  int total = 0;
  for (const BlockRef& b : order) {
    offsets->push_back(total);
    total += b.tangent_size();
  }
  return total;
}

MarginalPriorFactor::MarginalPriorFactor(const MarginalPrior& prior) : prior_(prior) {
  set_num_residuals(static_cast<int>(prior.r0.size()));
  for (const BlockRef& b : prior.blocks) mutable_parameter_block_sizes()->push_back(b.ambient_size);
}

bool MarginalPriorFactor::Evaluate(double const* const* parameters, double* residuals,
                                   double** jacobians) const {
  const int m = num_residuals();
  Eigen::VectorXd dx(prior_.tangent_dim());
  int offset = 0;
  for (std::size_t b = 0; b < prior_.blocks.size(); ++b) {
    const BlockRef& block = prior_.blocks[b];
    dx.segment(offset, block.tangent_size()) =
        BlockMinus(block, parameters[b], prior_.x_lin[b].data());
    offset += block.tangent_size();
  }
  Eigen::Map<Eigen::VectorXd>(residuals, m) = prior_.r0 + prior_.J * dx;
  if (jacobians == nullptr) return true;
  offset = 0;
  for (std::size_t b = 0; b < prior_.blocks.size(); ++b) {
    const BlockRef& block = prior_.blocks[b];
    const int t = block.tangent_size();
    if (jacobians[b] != nullptr) {
      Eigen::Map<RowMajorMatrix> out(jacobians[b], m, block.ambient_size);
      if (block.rotation) {
        // d Log(R_lin⁻¹ R Exp(δ))/dδ = Jr⁻¹(dθ); then lifted to the quaternion (so3_manifold.h).
        const Eigen::Vector3d d_theta = dx.segment<3>(offset);
        const Eigen::MatrixXd tangent =
            prior_.J.middleCols(offset, 3) * lie::SO3d::RightJacobianInverse(d_theta);
        out = tangent * (4.0 * RotationPlusJacobian(parameters[b]).transpose());
      } else {
        out = prior_.J.middleCols(offset, t);
      }
    }
    offset += t;
  }
  return true;
}

void Linearize(const std::vector<FactorRef>& factors, const std::vector<BlockRef>& order,
               Eigen::MatrixXd* H, Eigen::VectorXd* g) {
  std::vector<int> offsets;
  const int n = TangentOffsets(order, &offsets);
  H->setZero(n, n);
  g->setZero(n);
  for (const FactorRef& f : factors) {
    const int m = f.cost->num_residuals();
    const std::size_t nb = f.blocks.size();
    std::vector<RowMajorMatrix> ambient(nb);
    std::vector<double*> jac_ptrs(nb);
    std::vector<int> index(nb);
    for (std::size_t b = 0; b < nb; ++b) {
      const auto it = std::find_if(order.begin(), order.end(),
                                   [&](const BlockRef& r) { return r.values == f.blocks[b]; });
      HYLO_CHECK(it != order.end(), "a factor's block is missing from the ordering");
      index[b] = static_cast<int>(it - order.begin());
      ambient[b].resize(m, it->ambient_size);
      jac_ptrs[b] = ambient[b].data();
    }
    Eigen::VectorXd r(m);
    if (!f.cost->Evaluate(f.blocks.data(), r.data(), jac_ptrs.data())) continue;
    std::vector<Eigen::MatrixXd> tangent(nb);
    for (std::size_t b = 0; b < nb; ++b) tangent[b] = ToTangent(order[index[b]], ambient[b]);
    for (std::size_t a = 0; a < nb; ++a) {
      const int oa = offsets[index[a]], ta = order[index[a]].tangent_size();
      g->segment(oa, ta) += tangent[a].transpose() * r;
      for (std::size_t b = 0; b < nb; ++b) {
        const int ob = offsets[index[b]], tb = order[index[b]].tangent_size();
        H->block(oa, ob, ta, tb) += tangent[a].transpose() * tangent[b];
      }
    }
  }
}

MarginalPrior Marginalize(const std::vector<FactorRef>& factors, const std::vector<BlockRef>& order,
                          int num_marginalized) {
  Eigen::MatrixXd H;
  Eigen::VectorXd g;
  Linearize(factors, order, &H, &g);
  std::vector<int> offsets;
  const int n = TangentOffsets(order, &offsets);
  const int m = num_marginalized < static_cast<int>(order.size()) ? offsets[num_marginalized] : n;
  const int k = n - m;
  const Eigen::MatrixXd H_mm_inv = PseudoInverse(H.topLeftCorner(m, m));
  const Eigen::MatrixXd H_km = H.bottomLeftCorner(k, m);
  const Eigen::MatrixXd H_schur = H.bottomRightCorner(k, k) - H_km * H_mm_inv * H_km.transpose();
  const Eigen::VectorXd g_schur = g.tail(k) - H_km * (H_mm_inv * g.head(m));
  const std::vector<BlockRef> kept(order.begin() + num_marginalized, order.end());
  return PriorFromInformation(kept, H_schur, g_schur);
}

MarginalPrior PriorFromInformation(const std::vector<BlockRef>& blocks, const Eigen::MatrixXd& H,
                                   const Eigen::VectorXd& g) {
  MarginalPrior prior;
  prior.blocks = blocks;
  for (const BlockRef& b : blocks) prior.x_lin.emplace_back(b.values, b.values + b.ambient_size);
  // H = U S Uᵀ: J = S^½ Uᵀ and r0 = S^-½ Uᵀ g over the observed directions only.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (H + H.transpose()));
  const Eigen::ArrayXd s = eig.eigenvalues().array();
  const int n = static_cast<int>(s.size());
  int first = 0;
  while (first < n && s(first) <= kMinEigenvalue) ++first;
  const int rank = n - first;
  const Eigen::MatrixXd U = eig.eigenvectors().rightCols(rank);
  const Eigen::ArrayXd sqrt_s = s.tail(rank).sqrt();
  prior.J = sqrt_s.matrix().asDiagonal() * U.transpose();
  prior.r0 = sqrt_s.inverse().matrix().asDiagonal() * (U.transpose() * g);
  return prior;
}

}  // namespace hylo::estimation
