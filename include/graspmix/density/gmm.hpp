#pragma once
// Gaussian mixtures with full covariances, fitted by weighted EM (the paper's eq:density_mixture),
// with closed-form marginals and conditionals (eq:mu_var_ur and neighbours, in the corrected forms of
// docs/design.md: Sigma_{u|r} = Sigma_uu - Sigma_ur Sigma_rr^-1 Sigma_ru and conditional weights normalised
// with the w^k kept in the denominator).
#include <cstdint>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "graspmix/core/types.hpp"

namespace graspmix {

/// How a GaussianMixture is fitted.
struct GmmSettings {
  int n_components = 1;     ///< K
  double reg_covar = 1e-6;  ///< added to every covariance diagonal (units of the data squared)
  int max_iter = 100;       ///< EM iterations per initialisation
  double tol = 1e-3;        ///< convergence threshold on the change of the mean log-likelihood
  int n_init = 1;           ///< initialisations; the best lower bound wins
  std::uint64_t seed = 0;   ///< seeds the k-means++ initialisation (no time-based seeds anywhere)
};

/// Diagnostics of the last fit.
struct GmmFitResult {
  bool converged = false;
  int n_iter = 0;               ///< EM iterations of the winning initialisation
  double lower_bound = 0.0;     ///< weighted mean log-likelihood of the winning fit
  std::vector<double> history;  ///< lower bound at every iteration of the winning initialisation
  int best_init = 0;
};

class GaussianMixture {
 public:
  explicit GaussianMixture(GmmSettings settings = {});

  /// A mixture from its parameters: weights (K), means (K, d), covariances (K of d x d).
  /// Weights are normalised; covariances must be symmetric positive definite.
  static GaussianMixture from_parameters(const Eigen::VectorXd& weights, const RowMatrixXd& means,
                                         const std::vector<Eigen::MatrixXd>& covariances);

  /// Weighted EM. X is (N, d); weights (N) must be positive (empty = all ones); means_init (K, d)
  /// replaces the k-means++ start when given. Throws std::invalid_argument on bad or degenerate data.
  const GmmFitResult& fit(const Eigen::Ref<const RowMatrixXd>& X, const Eigen::VectorXd& weights = {},
                          const RowMatrixXd& means_init = {});

  /// Log density of every row of X (N).
  Eigen::VectorXd score_samples(const Eigen::Ref<const RowMatrixXd>& X) const;
  /// Weighted mean log density (empty weights = plain mean).
  double score(const Eigen::Ref<const RowMatrixXd>& X, const Eigen::VectorXd& weights = {}) const;
  /// Posterior responsibilities (N, K).
  RowMatrixXd predict_proba(const Eigen::Ref<const RowMatrixXd>& X) const;
  /// n draws (n, d) from the caller's generator.
  RowMatrixXd sample(int n, std::mt19937_64& rng) const;
  RowMatrixXd sample(int n, std::uint64_t seed) const;

  /// The mixture of the listed dimensions (in that order) with the others integrated out.
  GaussianMixture marginal(const std::vector<int>& dims) const;
  /// The mixture over the remaining dimensions (in increasing order) given x[given_dims] = values.
  GaussianMixture condition(const std::vector<int>& given_dims, const Eigen::VectorXd& values) const;

  bool fitted() const { return weights_.size() > 0; }
  int n_components() const { return static_cast<int>(weights_.size()); }
  int dim() const { return static_cast<int>(means_.cols()); }
  const GmmSettings& settings() const { return settings_; }
  const GmmFitResult& result() const { return result_; }
  const Eigen::VectorXd& weights() const { return weights_; }
  const RowMatrixXd& means() const { return means_; }
  const std::vector<Eigen::MatrixXd>& covariances() const { return covariances_; }
  /// Lower Cholesky factors of the covariances.
  const std::vector<Eigen::MatrixXd>& cholesky_factors() const { return chol_; }

  /// log N(x_i | mu_k, Sigma_k) + log w_k for every row and component (N, K).
  RowMatrixXd weighted_log_component_densities(const Eigen::Ref<const RowMatrixXd>& X) const;

 private:
  void set_parameters(Eigen::VectorXd weights, RowMatrixXd means, std::vector<Eigen::MatrixXd> covariances);
  /// The phases of fit: an M-step from (unnormalised) responsibilities R (N, K) of the samples X with
  /// weights w (summing to w_sum), and one EM run started from hard assignment to the nearest centre.
  void m_step(const Eigen::Ref<const RowMatrixXd>& X, const Eigen::VectorXd& w, double w_sum, const RowMatrixXd& R);
  GmmFitResult run_em(const Eigen::Ref<const RowMatrixXd>& X, const Eigen::VectorXd& w, double w_sum,
                      const RowMatrixXd& centres);
  void require_fitted(const char* what) const;
  void require_dim(const Eigen::Ref<const RowMatrixXd>& X, const char* what) const;

  GmmSettings settings_;
  GmmFitResult result_;
  Eigen::VectorXd weights_;
  RowMatrixXd means_;
  std::vector<Eigen::MatrixXd> covariances_;
  std::vector<Eigen::MatrixXd> chol_;
  Eigen::VectorXd log_det_;  ///< log |Sigma_k|
};

/// p(u | r) of a joint mixture over x = (u, r) for many different r at once: every component's
/// regression matrix Sigma_ur Sigma_rr^-1 and conditional Cholesky factor are computed once, so
/// evaluating or sampling for a batch of (u, r) pairs costs no refactorisation.
class ConditionalGaussianMixture {
 public:
  ConditionalGaussianMixture() = default;
  /// The leading u_dim dimensions of `joint` are u, the rest are r.
  ConditionalGaussianMixture(const GaussianMixture& joint, int u_dim);

  int u_dim() const { return u_dim_; }
  int r_dim() const { return r_dim_; }
  /// log pi^j(r) for every row of R (N, K): the conditional mixture weights.
  RowMatrixXd log_conditional_weights(const Eigen::Ref<const RowMatrixXd>& R) const;
  /// log p(u_i | r_i) for row pairs (N).
  Eigen::VectorXd log_density(const Eigen::Ref<const RowMatrixXd>& U, const Eigen::Ref<const RowMatrixXd>& R) const;
  /// log p(r_i) (N): the marginal over features (eq:density_mixture_features).
  Eigen::VectorXd log_feature_density(const Eigen::Ref<const RowMatrixXd>& R) const;
  /// One draw of u given each row of R (N, u_dim).
  RowMatrixXd sample(const Eigen::Ref<const RowMatrixXd>& R, std::mt19937_64& rng) const;

 private:
  int u_dim_ = 0, r_dim_ = 0;
  Eigen::VectorXd log_w_;
  RowMatrixXd mu_u_, mu_r_;
  std::vector<Eigen::MatrixXd> regression_;  ///< Sigma_ur Sigma_rr^-1 (u_dim x r_dim)
  std::vector<Eigen::MatrixXd> chol_cond_;   ///< chol(Sigma_uu - Sigma_ur Sigma_rr^-1 Sigma_ru)
  std::vector<Eigen::MatrixXd> chol_rr_;     ///< chol(Sigma_rr)
  Eigen::VectorXd log_det_cond_, log_det_rr_;
};

/// log sum exp of each row, safe for rows of -inf.
Eigen::VectorXd logsumexp_rows(const Eigen::Ref<const RowMatrixXd>& A);

}  // namespace graspmix
