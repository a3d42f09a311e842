// Marginals and conditionals of Gaussian mixtures (docs/design.md: the conditional's correct forms).
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "gaussian.hpp"
#include "graspmix/density/gmm.hpp"

namespace graspmix {

using detail::cholesky;
using detail::gaussian_log_density_centred;
using detail::kLog2Pi;
using detail::str;

namespace {

std::vector<int> checked_dims(const std::vector<int>& dims, int d, const char* what, bool allow_all) {
  std::vector<int> seen(d, 0);
  for (int k : dims) {
    if (k < 0 || k >= d) {
      throw std::invalid_argument(std::string(what) + ": dimension " + std::to_string(k) + " is outside [0, " +
                                  std::to_string(d) + ")");
    }
    if (seen[k]++) throw std::invalid_argument(std::string(what) + ": dimension " + std::to_string(k) + " repeated");
  }
  if (dims.empty()) throw std::invalid_argument(std::string(what) + ": no dimensions given");
  if (!allow_all && static_cast<int>(dims.size()) == d) {
    throw std::invalid_argument(std::string(what) + ": conditioning on every dimension leaves nothing");
  }
  std::vector<int> rest;
  for (int k = 0; k < d; ++k)
    if (!seen[k]) rest.push_back(k);
  return rest;
}

Eigen::MatrixXd sub(const Eigen::MatrixXd& S, const std::vector<int>& rows, const std::vector<int>& cols) {
  Eigen::MatrixXd out(rows.size(), cols.size());
  for (size_t i = 0; i < rows.size(); ++i)
    for (size_t j = 0; j < cols.size(); ++j) out(i, j) = S(rows[i], cols[j]);
  return out;
}

Eigen::VectorXd sub(const Eigen::VectorXd& v, const std::vector<int>& idx) {
  Eigen::VectorXd out(idx.size());
  for (size_t i = 0; i < idx.size(); ++i) out[i] = v[idx[i]];
  return out;
}

}  // namespace

GaussianMixture GaussianMixture::marginal(const std::vector<int>& dims) const {
  require_fitted("marginal");
  checked_dims(dims, dim(), "GaussianMixture.marginal", true);
  RowMatrixXd mu(n_components(), dims.size());
  std::vector<Eigen::MatrixXd> covs;
  for (int k = 0; k < n_components(); ++k) {
    mu.row(k) = sub(Eigen::VectorXd(means_.row(k).transpose()), dims).transpose();
    covs.push_back(sub(covariances_[k], dims, dims));
  }
  return from_parameters(weights_, mu, covs);
}

GaussianMixture GaussianMixture::condition(const std::vector<int>& given, const Eigen::VectorXd& values) const {
  require_fitted("condition");
  const std::vector<int> rest = checked_dims(given, dim(), "GaussianMixture.condition", false);
  if (values.size() != static_cast<Eigen::Index>(given.size())) {
    throw std::invalid_argument("GaussianMixture.condition: " + str(values.size()) + " values for " +
                                str(given.size()) + " given dimensions");
  }
  if (!values.allFinite()) throw std::invalid_argument("GaussianMixture.condition: values contain NaN or infinity");
  const int K = n_components();
  RowMatrixXd mu(K, rest.size());
  std::vector<Eigen::MatrixXd> covs;
  Eigen::VectorXd log_pi(K);
  for (int k = 0; k < K; ++k) {
    const Eigen::VectorXd m = means_.row(k).transpose();
    const Eigen::MatrixXd Suu = sub(covariances_[k], rest, rest), Sur = sub(covariances_[k], rest, given),
                          Srr = sub(covariances_[k], given, given);
    auto [Lr, ld_r] = cholesky(Srr, "the given block of covariance " + str(k));
    const Eigen::LLT<Eigen::MatrixXd> llt(Srr);
    const Eigen::VectorXd diff = values - sub(m, given);
    // Bishop 2.81-2.82: mu_u + Sigma_ur Sigma_rr^-1 (r - mu_r), Sigma_uu - Sigma_ur Sigma_rr^-1 Sigma_ru.
    mu.row(k) = (sub(m, rest) + Sur * llt.solve(diff)).transpose();
    Eigen::MatrixXd S = Suu - Sur * llt.solve(Sur.transpose());
    covs.push_back(0.5 * (S + S.transpose()));
    const Eigen::VectorXd z = Lr.triangularView<Eigen::Lower>().solve(diff);
    log_pi[k] = std::log(weights_[k]) - 0.5 * (z.squaredNorm() + given.size() * kLog2Pi + ld_r);
  }
  // pi^j = w^j N(r | mu_r^j, S_rr^j) / sum_k w^k N(r | mu_r^k, S_rr^k), in log space.
  const double m = log_pi.maxCoeff();
  if (!std::isfinite(m)) throw std::invalid_argument("GaussianMixture.condition: the given values have zero density");
  const Eigen::VectorXd pi = (log_pi.array() - m).exp();
  return from_parameters(pi / pi.sum(), mu, covs);
}

// ---- ConditionalGaussianMixture ------------------------------------------------------------

ConditionalGaussianMixture::ConditionalGaussianMixture(const GaussianMixture& joint, int u_dim) {
  if (!joint.fitted()) throw std::invalid_argument("ConditionalGaussianMixture: the joint mixture is not fitted");
  if (u_dim < 1 || u_dim > joint.dim()) {
    throw std::invalid_argument("ConditionalGaussianMixture: u_dim " + std::to_string(u_dim) + " outside [1, " +
                                std::to_string(joint.dim()) + "]");
  }
  u_dim_ = u_dim;
  r_dim_ = joint.dim() - u_dim;
  const int K = joint.n_components();
  log_w_ = joint.weights().array().log();
  mu_u_ = joint.means().leftCols(u_dim_);
  mu_r_ = joint.means().rightCols(r_dim_);
  log_det_cond_.resize(K);
  log_det_rr_.resize(K);
  for (int k = 0; k < K; ++k) {
    const Eigen::MatrixXd& S = joint.covariances()[k];
    const Eigen::MatrixXd Suu = S.topLeftCorner(u_dim_, u_dim_);
    if (r_dim_ == 0) {
      regression_.emplace_back(u_dim_, 0);
      chol_rr_.emplace_back(0, 0);
      log_det_rr_[k] = 0.0;
      auto [L, ld] = cholesky(Suu, "covariance of component " + str(k));
      chol_cond_.push_back(L);
      log_det_cond_[k] = ld;
      continue;
    }
    const Eigen::MatrixXd Sur = S.topRightCorner(u_dim_, r_dim_), Srr = S.bottomRightCorner(r_dim_, r_dim_);
    auto [Lr, ld_r] = cholesky(Srr, "feature block of covariance " + str(k));
    const Eigen::LLT<Eigen::MatrixXd> llt(Srr);
    Eigen::MatrixXd A = llt.solve(Sur.transpose()).transpose();
    Eigen::MatrixXd C = Suu - A * Sur.transpose();
    auto [Lc, ld_c] = cholesky(0.5 * (C + C.transpose()), "conditional covariance of component " + str(k));
    regression_.push_back(std::move(A));
    chol_rr_.push_back(std::move(Lr));
    chol_cond_.push_back(std::move(Lc));
    log_det_rr_[k] = ld_r;
    log_det_cond_[k] = ld_c;
  }
}

RowMatrixXd ConditionalGaussianMixture::log_conditional_weights(const Eigen::Ref<const RowMatrixXd>& R) const {
  const Eigen::Index K = log_w_.size();
  if (R.cols() != r_dim_) {
    throw std::invalid_argument("features have " + str(R.cols()) + " columns, the model expects " + str(r_dim_));
  }
  RowMatrixXd out(R.rows(), K);
  for (Eigen::Index k = 0; k < K; ++k) {
    if (r_dim_ == 0) {
      out.col(k).setConstant(log_w_[k]);
      continue;
    }
    const RowMatrixXd D = R.rowwise() - mu_r_.row(k);
    out.col(k) = gaussian_log_density_centred(D, chol_rr_[k], log_det_rr_[k]).array() + log_w_[k];
  }
  return out;
}

Eigen::VectorXd ConditionalGaussianMixture::log_feature_density(const Eigen::Ref<const RowMatrixXd>& R) const {
  return logsumexp_rows(log_conditional_weights(R));
}

Eigen::VectorXd ConditionalGaussianMixture::log_density(const Eigen::Ref<const RowMatrixXd>& U,
                                                        const Eigen::Ref<const RowMatrixXd>& R) const {
  if (U.cols() != u_dim_) {
    throw std::invalid_argument("poses have " + str(U.cols()) + " coordinates, the model expects " + str(u_dim_));
  }
  if (U.rows() != R.rows()) {
    throw std::invalid_argument(str(U.rows()) + " poses but " + str(R.rows()) + " feature rows");
  }
  RowMatrixXd logp = log_conditional_weights(R);
  logp.colwise() -= logsumexp_rows(logp);  // log pi^j(r)
  for (Eigen::Index k = 0; k < logp.cols(); ++k) {
    RowMatrixXd D = U.rowwise() - mu_u_.row(k);
    if (r_dim_ > 0) D -= (R.rowwise() - mu_r_.row(k)) * regression_[k].transpose();
    logp.col(k) += gaussian_log_density_centred(D, chol_cond_[k], log_det_cond_[k]);
  }
  return logsumexp_rows(logp);
}

RowMatrixXd ConditionalGaussianMixture::sample(const Eigen::Ref<const RowMatrixXd>& R, std::mt19937_64& rng) const {
  RowMatrixXd logp = log_conditional_weights(R);
  const Eigen::VectorXd norm = logsumexp_rows(logp);
  for (Eigen::Index i = 0; i < R.rows(); ++i) {
    // Every component's weight underflowed: the draw would pick the last component, not a sample.
    if (!std::isfinite(norm[i])) {
      throw std::invalid_argument("features row " + str(i) + " has zero density under every component");
    }
  }
  logp.colwise() -= norm;
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::normal_distribution<double> normal;
  RowMatrixXd out(R.rows(), u_dim_);
  Eigen::VectorXd z(u_dim_);
  for (Eigen::Index i = 0; i < R.rows(); ++i) {
    double u = uni(rng);
    Eigen::Index k = 0;
    for (; k + 1 < logp.cols(); ++k) {
      u -= std::exp(logp(i, k));
      if (u <= 0.0) break;
    }
    for (int j = 0; j < u_dim_; ++j) z[j] = normal(rng);
    Eigen::VectorXd mean = mu_u_.row(k).transpose();
    if (r_dim_ > 0) mean += regression_[k] * (R.row(i) - mu_r_.row(k)).transpose();
    out.row(i) = (mean + chol_cond_[k] * z).transpose();
  }
  return out;
}

}  // namespace graspmix
