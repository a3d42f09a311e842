#pragma once
// The Gaussian kernels shared by the mixture's fit and evaluation (gmm.cpp) and its marginals and
// conditionals (gmm_conditional.cpp): private to src/density/.
#include <algorithm>
#include <string>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "graspmix/core/types.hpp"

namespace graspmix::detail {

constexpr double kLog2Pi = 1.8378770664093454836;
constexpr Eigen::Index kParallelRows = 4096;  // below this, threads cost more than they save

inline std::string str(Eigen::Index v) { return std::to_string(v); }

/// Lower Cholesky factor and log determinant; throws naming the component when not positive definite.
inline std::pair<Eigen::MatrixXd, double> cholesky(const Eigen::MatrixXd& S, const std::string& what) {
  Eigen::LLT<Eigen::MatrixXd> llt(S);
  if (llt.info() != Eigen::Success || !S.allFinite()) {
    throw std::invalid_argument(what +
                                " is not positive definite (degenerate data: increase reg_covar, "
                                "use fewer components, or give more distinct points)");
  }
  Eigen::MatrixXd L = llt.matrixL();
  return {L, 2.0 * L.diagonal().array().log().sum()};
}

/// -0.5 * (d log 2 pi + log|S| + maha) for every row of D (already centred), given L = chol(S).
inline Eigen::VectorXd gaussian_log_density_centred(const Eigen::Ref<const RowMatrixXd>& D, const Eigen::MatrixXd& L,
                                                    double log_det) {
  const Eigen::Index n = D.rows(), d = D.cols();
  Eigen::VectorXd out(n);
  const Eigen::Index block = 1024;
  const Eigen::Index n_blocks = (n + block - 1) / block;
#pragma omp parallel for schedule(static) if (n >= kParallelRows)
  for (Eigen::Index b = 0; b < n_blocks; ++b) {
    const Eigen::Index start = b * block, len = std::min(block, n - start);
    Eigen::MatrixXd Z = D.middleRows(start, len).transpose();
    L.triangularView<Eigen::Lower>().solveInPlace(Z);
    out.segment(start, len) = -0.5 * (Z.colwise().squaredNorm().transpose().array() + (d * kLog2Pi + log_det));
  }
  return out;
}

}  // namespace graspmix::detail
