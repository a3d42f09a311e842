#include "graspmix/density/gmm.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

#include <Eigen/Cholesky>

#include "gaussian.hpp"
#include "graspmix/core/se3.hpp"

namespace graspmix {

namespace {

using detail::cholesky;
using detail::gaussian_log_density_centred;
using detail::str;

const double kEps = std::numeric_limits<double>::epsilon();

Eigen::VectorXd checked_weights(const Eigen::VectorXd& w, Eigen::Index n, const char* what) {
  if (w.size() == 0) return Eigen::VectorXd::Ones(n);
  if (w.size() != n) {
    throw std::invalid_argument(std::string(what) + ": weights has " + str(w.size()) + " entries for " + str(n) +
                                " samples");
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!std::isfinite(w[i]) || w[i] <= 0.0) {
      throw std::invalid_argument(std::string(what) + ": weight " + str(i) + " is " + std::to_string(w[i]) +
                                  "; weights must be positive and finite");
    }
  }
  return w;
}

/// Greedy k-means++ (weighted): each new centre is the best of 2 + log K candidates drawn with
/// probability proportional to w_i D(x_i)^2.
RowMatrixXd kmeans_plusplus(const Eigen::Ref<const RowMatrixXd>& X, const Eigen::VectorXd& w, int K,
                            std::mt19937_64& rng) {
  const Eigen::Index n = X.rows();
  RowMatrixXd centres(K, X.cols());
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  auto draw = [&](const Eigen::VectorXd& p) {
    const double total = p.sum();
    double u = uni(rng) * total;
    for (Eigen::Index i = 0; i < n; ++i) {
      u -= p[i];
      if (u <= 0.0) return i;
    }
    return n - 1;
  };
  centres.row(0) = X.row(draw(w));
  Eigen::VectorXd d2 = (X.rowwise() - centres.row(0)).rowwise().squaredNorm();
  const int trials = 2 + static_cast<int>(std::log(static_cast<double>(K)));
  for (int k = 1; k < K; ++k) {
    const Eigen::VectorXd p = w.cwiseProduct(d2);
    if (!(p.sum() > 0.0)) {
      throw std::invalid_argument("GaussianMixture.fit: the data has fewer distinct points than the " + str(K) +
                                  " components asked for");
    }
    double best_cost = std::numeric_limits<double>::infinity();
    Eigen::Index best = 0;
    Eigen::VectorXd best_d2;
    for (int t = 0; t < trials; ++t) {
      const Eigen::Index c = draw(p);
      Eigen::VectorXd cand = (X.rowwise() - X.row(c)).rowwise().squaredNorm().cwiseMin(d2);
      const double cost = w.dot(cand);
      if (cost < best_cost) {
        best_cost = cost;
        best = c;
        best_d2 = std::move(cand);
      }
    }
    centres.row(k) = X.row(best);
    d2 = std::move(best_d2);
  }
  return centres;
}

}  // namespace

Eigen::VectorXd logsumexp_rows(const Eigen::Ref<const RowMatrixXd>& A) {
  Eigen::VectorXd out(A.rows());
  for (Eigen::Index i = 0; i < A.rows(); ++i) {
    const double m = A.row(i).maxCoeff();
    out[i] = std::isfinite(m) ? m + std::log((A.row(i).array() - m).exp().sum()) : m;
  }
  return out;
}

GaussianMixture::GaussianMixture(GmmSettings s) : settings_(s) {
  if (s.n_components < 1) throw std::invalid_argument("GaussianMixture: n_components must be >= 1");
  if (!(s.reg_covar >= 0.0) || !std::isfinite(s.reg_covar))
    throw std::invalid_argument("GaussianMixture: reg_covar must be finite and >= 0");
  if (s.max_iter < 1) throw std::invalid_argument("GaussianMixture: max_iter must be >= 1");
  if (!(s.tol >= 0.0)) throw std::invalid_argument("GaussianMixture: tol must be >= 0");
  if (s.n_init < 1) throw std::invalid_argument("GaussianMixture: n_init must be >= 1");
}

GaussianMixture GaussianMixture::from_parameters(const Eigen::VectorXd& weights, const RowMatrixXd& means,
                                                 const std::vector<Eigen::MatrixXd>& covariances) {
  const Eigen::Index K = weights.size();
  if (K < 1) throw std::invalid_argument("GaussianMixture.from_parameters: weights is empty");
  if (means.rows() != K || static_cast<Eigen::Index>(covariances.size()) != K) {
    throw std::invalid_argument("GaussianMixture.from_parameters: " + str(K) + " weights but " + str(means.rows()) +
                                " means and " + str(covariances.size()) + " covariances");
  }
  if (!weights.allFinite() || (weights.array() < 0).any() || !(weights.sum() > 0)) {
    throw std::invalid_argument("GaussianMixture.from_parameters: weights must be finite, >= 0, not all zero");
  }
  require_finite(means, "GaussianMixture.from_parameters: means");
  for (Eigen::Index k = 0; k < K; ++k) {
    const auto& S = covariances[k];
    if (S.rows() != means.cols() || S.cols() != means.cols()) {
      throw std::invalid_argument("GaussianMixture.from_parameters: covariance " + str(k) + " is " + str(S.rows()) +
                                  "x" + str(S.cols()) + ", expected " + str(means.cols()) + "x" + str(means.cols()));
    }
    if (!S.isApprox(S.transpose(), 1e-9)) {
      throw std::invalid_argument("GaussianMixture.from_parameters: covariance " + str(k) + " is not symmetric");
    }
  }
  GmmSettings s;
  s.n_components = static_cast<int>(K);
  GaussianMixture g(s);
  g.set_parameters(weights / weights.sum(), means, covariances);
  return g;
}

void GaussianMixture::set_parameters(Eigen::VectorXd weights, RowMatrixXd means,
                                     std::vector<Eigen::MatrixXd> covariances) {
  const Eigen::Index K = weights.size();
  std::vector<Eigen::MatrixXd> chol(K);
  Eigen::VectorXd log_det(K);
  for (Eigen::Index k = 0; k < K; ++k) {
    auto [L, ld] = cholesky(covariances[k], "covariance of component " + str(k));
    chol[k] = std::move(L);
    log_det[k] = ld;
  }
  weights_ = std::move(weights);
  means_ = std::move(means);
  covariances_ = std::move(covariances);
  chol_ = std::move(chol);
  log_det_ = std::move(log_det);
}

void GaussianMixture::require_fitted(const char* what) const {
  // invalid_argument (ValueError in Python, like scikit-learn's NotFittedError): the caller passed an unfitted model.
  if (!fitted()) {
    throw std::invalid_argument(std::string("GaussianMixture.") + what +
                                ": the mixture is not fitted yet (call fit, or make it with from_parameters)");
  }
}

void GaussianMixture::require_dim(const Eigen::Ref<const RowMatrixXd>& X, const char* what) const {
  require_fitted(what);
  if (X.cols() != dim()) {
    throw std::invalid_argument(std::string("GaussianMixture.") + what + ": X has " + str(X.cols()) +
                                " columns, the mixture has " + str(dim()) + " dimensions");
  }
  require_finite(X, (std::string("GaussianMixture.") + what + ": X").c_str());
}

RowMatrixXd GaussianMixture::weighted_log_component_densities(const Eigen::Ref<const RowMatrixXd>& X) const {
  const Eigen::Index K = n_components();
  RowMatrixXd out(X.rows(), K);
  for (Eigen::Index k = 0; k < K; ++k) {
    const RowMatrixXd D = X.rowwise() - means_.row(k);
    out.col(k) = gaussian_log_density_centred(D, chol_[k], log_det_[k]).array() + std::log(weights_[k]);
  }
  return out;
}

void GaussianMixture::m_step(const Eigen::Ref<const RowMatrixXd>& X, const Eigen::VectorXd& w, double w_sum,
                             const RowMatrixXd& R) {
  const int K = settings_.n_components;
  const Eigen::Index d = X.cols();
  const Eigen::MatrixXd reg = settings_.reg_covar * Eigen::MatrixXd::Identity(d, d);
  const RowMatrixXd Rw = R.array().colwise() * w.array();
  Eigen::VectorXd nk = Rw.colwise().sum().transpose();
  for (int k = 0; k < K; ++k) {
    if (!(nk[k] > 10.0 * kEps * w_sum)) {
      throw std::invalid_argument("GaussianMixture.fit: component " + str(k) +
                                  " lost all support (no sample is responsible for it); use fewer components");
    }
  }
  RowMatrixXd means = (Rw.transpose() * X).array().colwise() / nk.array();
  std::vector<Eigen::MatrixXd> covs(K);
  for (int k = 0; k < K; ++k) {
    const RowMatrixXd D = X.rowwise() - means.row(k);
    covs[k] = (D.array().colwise() * Rw.col(k).array()).matrix().transpose() * D / nk[k] + reg;
    covs[k] = 0.5 * (covs[k] + covs[k].transpose());
  }
  set_parameters(nk / w_sum, std::move(means), std::move(covs));
}

GmmFitResult GaussianMixture::run_em(const Eigen::Ref<const RowMatrixXd>& X, const Eigen::VectorXd& w, double w_sum,
                                     const RowMatrixXd& centres) {
  const int K = settings_.n_components;
  const Eigen::Index n = X.rows();
  // Hard assignment to the nearest centre starts EM (scikit-learn's 'k-means++' initialisation).
  RowMatrixXd R = RowMatrixXd::Zero(n, K);
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Index best;
    (centres.rowwise() - X.row(i)).rowwise().squaredNorm().minCoeff(&best);
    R(i, best) = 1.0;
  }
  m_step(X, w, w_sum, R);
  GmmFitResult res;
  double lower = -std::numeric_limits<double>::infinity();
  for (int it = 1; it <= settings_.max_iter; ++it) {
    const double prev = lower;
    RowMatrixXd logp = weighted_log_component_densities(X);
    const Eigen::VectorXd norm = logsumexp_rows(logp);
    lower = w.dot(norm) / w_sum;
    res.history.push_back(lower);
    res.n_iter = it;
    logp.colwise() -= norm;
    // Responsibilities below e^-700 would be subnormal numbers, which make every product in the
    // M-step an order of magnitude slower; they are zero to double precision anyway.
    m_step(X, w, w_sum, (logp.array() < -700.0).select(0.0, logp.array().exp()).matrix());
    if (std::abs(lower - prev) < settings_.tol) {
      res.converged = true;
      break;
    }
  }
  res.lower_bound = lower;
  return res;
}

const GmmFitResult& GaussianMixture::fit(const Eigen::Ref<const RowMatrixXd>& X, const Eigen::VectorXd& weights_in,
                                         const RowMatrixXd& means_init) {
  const int K = settings_.n_components;
  const Eigen::Index n = X.rows(), d = X.cols();
  if (n == 0 || d == 0) throw std::invalid_argument("GaussianMixture.fit: X is empty (" + str(n) + "x" + str(d) + ")");
  require_finite(X, "GaussianMixture.fit: X");
  if (n < K) {
    throw std::invalid_argument("GaussianMixture.fit: " + str(n) + " samples are fewer than the " + str(K) +
                                " components");
  }
  const Eigen::VectorXd w = checked_weights(weights_in, n, "GaussianMixture.fit");
  const double w_sum = w.sum();
  if (means_init.size() != 0 && (means_init.rows() != K || means_init.cols() != d)) {
    throw std::invalid_argument("GaussianMixture.fit: means_init is " + str(means_init.rows()) + "x" +
                                str(means_init.cols()) + ", expected " + str(K) + "x" + str(d));
  }

  std::mt19937_64 rng(settings_.seed);
  bool have_best = false;
  GmmFitResult best;
  Eigen::VectorXd best_w;
  RowMatrixXd best_mu;
  std::vector<Eigen::MatrixXd> best_cov;
  std::string last_error;
  for (int init = 0; init < settings_.n_init; ++init) {
    try {
      const RowMatrixXd centres = means_init.size() ? means_init : kmeans_plusplus(X, w, K, rng);
      GmmFitResult res = run_em(X, w, w_sum, centres);
      if (!have_best || res.lower_bound > best.lower_bound) {
        res.best_init = init;
        best = std::move(res);
        best_w = weights_;
        best_mu = means_;
        best_cov = covariances_;
        have_best = true;
      }
    } catch (const std::invalid_argument& e) {
      last_error = e.what();  // another initialisation may still succeed
    }
  }
  if (!have_best) throw std::invalid_argument(last_error);
  set_parameters(best_w, best_mu, best_cov);
  result_ = std::move(best);
  return result_;
}

Eigen::VectorXd GaussianMixture::score_samples(const Eigen::Ref<const RowMatrixXd>& X) const {
  require_dim(X, "score_samples");
  return logsumexp_rows(weighted_log_component_densities(X));
}

double GaussianMixture::score(const Eigen::Ref<const RowMatrixXd>& X, const Eigen::VectorXd& weights) const {
  require_dim(X, "score");
  if (X.rows() == 0) throw std::invalid_argument("GaussianMixture.score: X is empty");
  const Eigen::VectorXd w = checked_weights(weights, X.rows(), "GaussianMixture.score");
  return w.dot(score_samples(X)) / w.sum();
}

RowMatrixXd GaussianMixture::predict_proba(const Eigen::Ref<const RowMatrixXd>& X) const {
  require_dim(X, "predict_proba");
  RowMatrixXd logp = weighted_log_component_densities(X);
  logp.colwise() -= logsumexp_rows(logp);
  return logp.array().exp();
}

RowMatrixXd GaussianMixture::sample(int n, std::mt19937_64& rng) const {
  require_fitted("sample");
  if (n < 0) throw std::invalid_argument("GaussianMixture.sample: n must be >= 0");
  std::discrete_distribution<int> pick(weights_.data(), weights_.data() + weights_.size());
  std::normal_distribution<double> normal;
  RowMatrixXd out(n, dim());
  Eigen::VectorXd z(dim());
  for (int i = 0; i < n; ++i) {
    const int k = pick(rng);
    for (int j = 0; j < dim(); ++j) z[j] = normal(rng);
    out.row(i) = means_.row(k) + (chol_[k] * z).transpose();
  }
  return out;
}

RowMatrixXd GaussianMixture::sample(int n, std::uint64_t seed) const {
  std::mt19937_64 rng(seed);
  return sample(n, rng);
}

}  // namespace graspmix
