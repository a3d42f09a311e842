// Gaussian mixtures: EM monotonicity, weights as repetitions, closed-form conditionals against
// brute-force Gaussian algebra, sampling moments, and clear errors on degenerate data.
#include <cmath>
#include <random>

#include <gtest/gtest.h>
#include <Eigen/LU>

#include "graspmix/density/gmm.hpp"

using namespace graspmix;

namespace {

RowMatrixXd two_blobs(int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> z;
  RowMatrixXd X(n, 3);
  for (int i = 0; i < n; ++i) {
    const bool second = i % 3 == 0;
    X.row(i) << z(rng) + (second ? 5.0 : 0.0), 0.5 * z(rng) + (second ? -2.0 : 1.0), 0.2 * z(rng) + 0.3 * X(i, 0);
  }
  return X;
}

GaussianMixture random_mixture(int K, int d, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> z;
  std::uniform_real_distribution<double> u(0.2, 1.0);
  Eigen::VectorXd w(K);
  RowMatrixXd mu(K, d);
  std::vector<Eigen::MatrixXd> covs;
  for (int k = 0; k < K; ++k) {
    w[k] = u(rng);
    for (int j = 0; j < d; ++j) mu(k, j) = 2.0 * z(rng);
    Eigen::MatrixXd A(d, d);
    for (int i = 0; i < d; ++i)
      for (int j = 0; j < d; ++j) A(i, j) = z(rng);
    covs.push_back(A * A.transpose() / d + 0.3 * Eigen::MatrixXd::Identity(d, d));
  }
  return GaussianMixture::from_parameters(w, mu, covs);
}

double gaussian_log_pdf(const Eigen::VectorXd& x, const Eigen::VectorXd& mu, const Eigen::MatrixXd& S) {
  const Eigen::VectorXd d = x - mu;
  return -0.5 * (d.dot(S.inverse() * d) + x.size() * std::log(2 * M_PI) + std::log(S.determinant()));
}

}  // namespace

TEST(Gmm, LowerBoundNeverDecreases) {
  const RowMatrixXd X = two_blobs(600, 4);
  GmmSettings s;
  s.n_components = 3;
  s.reg_covar = 0.0;
  s.tol = 0.0;
  s.max_iter = 60;
  GaussianMixture g(s);
  const auto& r = g.fit(X);
  ASSERT_GE(r.history.size(), 2u);
  for (size_t i = 1; i < r.history.size(); ++i) EXPECT_GE(r.history[i], r.history[i - 1] - 1e-9) << i;
}

TEST(Gmm, RecoversTwoWellSeparatedClusters) {
  const RowMatrixXd X = two_blobs(3000, 5);
  GmmSettings s;
  s.n_components = 2;
  GaussianMixture g(s);
  EXPECT_TRUE(g.fit(X).converged);
  const int big = g.weights()[0] > g.weights()[1] ? 0 : 1;
  EXPECT_NEAR(g.weights()[big], 2.0 / 3.0, 0.03);
  EXPECT_NEAR(g.means()(big, 0), 0.0, 0.1);
  EXPECT_NEAR(g.means()(1 - big, 0), 5.0, 0.1);
  EXPECT_NEAR(g.covariances()[big](1, 1), 0.25, 0.03);
}

TEST(Gmm, IntegerWeightsEqualRepeatedSamples) {
  const RowMatrixXd X = two_blobs(200, 6);
  Eigen::VectorXd w(X.rows());
  std::vector<int> rows;
  for (int i = 0; i < X.rows(); ++i) {
    w[i] = 1 + i % 3;
    for (int r = 0; r < w[i]; ++r) rows.push_back(i);
  }
  RowMatrixXd Xr(rows.size(), X.cols());
  for (size_t i = 0; i < rows.size(); ++i) Xr.row(i) = X.row(rows[i]);
  GmmSettings s;
  s.n_components = 2;
  RowMatrixXd init(2, 3);
  init << 0, 1, 0, 5, -2, 1.5;
  GaussianMixture a(s), b(s);
  a.fit(X, w, init);
  b.fit(Xr, {}, init);
  EXPECT_EQ(a.result().n_iter, b.result().n_iter);
  EXPECT_NEAR(a.result().lower_bound, b.result().lower_bound, 1e-10);
  EXPECT_TRUE(a.means().isApprox(b.means(), 1e-9));
  EXPECT_TRUE(a.covariances()[1].isApprox(b.covariances()[1], 1e-9));
}

TEST(Gmm, ConditionMatchesJointGaussianAlgebra) {
  const GaussianMixture g = random_mixture(3, 5, 7);
  const std::vector<int> given{1, 4};
  Eigen::VectorXd r(2);
  r << 0.3, -1.2;
  const GaussianMixture c = g.condition(given, r);
  // p(u | r) = p(u, r) / p(r): check pointwise against the joint and the marginal.
  const GaussianMixture m = g.marginal(given);
  std::mt19937_64 rng(8);
  std::normal_distribution<double> z;
  RowMatrixXd U(20, 3), X(20, 5);
  for (int i = 0; i < 20; ++i) {
    for (int j = 0; j < 3; ++j) U(i, j) = 2.0 * z(rng);
    X.row(i) << U(i, 0), r[0], U(i, 1), U(i, 2), r[1];
  }
  const Eigen::VectorXd lc = c.score_samples(U), lj = g.score_samples(X);
  const double lm = m.score_samples(r.transpose())[0];
  for (int i = 0; i < 20; ++i) EXPECT_NEAR(lc[i], lj[i] - lm, 1e-9);
}

TEST(Gmm, MarginalMatchesDirectIntegrationOfOneGaussian) {
  const GaussianMixture g = random_mixture(1, 4, 9);
  const GaussianMixture m = g.marginal({2, 0});
  Eigen::VectorXd x(2);
  x << 0.4, -0.3;
  Eigen::VectorXd mu(2);
  mu << g.means()(0, 2), g.means()(0, 0);
  Eigen::MatrixXd S(2, 2);
  const auto& C = g.covariances()[0];
  S << C(2, 2), C(2, 0), C(0, 2), C(0, 0);
  EXPECT_NEAR(m.score_samples(x.transpose())[0], gaussian_log_pdf(x, mu, S), 1e-12);
}

TEST(Gmm, ConditionalBatchAgreesWithConditionPerRow) {
  const GaussianMixture g = random_mixture(3, 6, 10);
  const ConditionalGaussianMixture cg(g, 4);
  std::mt19937_64 rng(11);
  std::normal_distribution<double> z;
  RowMatrixXd U(10, 4), R(10, 2);
  for (int i = 0; i < 10; ++i) {
    for (int j = 0; j < 4; ++j) U(i, j) = z(rng);
    for (int j = 0; j < 2; ++j) R(i, j) = z(rng);
  }
  const Eigen::VectorXd batch = cg.log_density(U, R);
  const Eigen::VectorXd feat = cg.log_feature_density(R);
  const GaussianMixture mr = g.marginal({4, 5});
  for (int i = 0; i < 10; ++i) {
    const GaussianMixture c = g.condition({4, 5}, R.row(i).transpose());
    EXPECT_NEAR(batch[i], c.score_samples(U.row(i))[0], 1e-9);
    EXPECT_NEAR(feat[i], mr.score_samples(R.row(i))[0], 1e-9);
  }
}

TEST(Gmm, SampleMomentsMatchTheMixture) {
  const GaussianMixture g = random_mixture(2, 3, 12);
  const RowMatrixXd S = g.sample(200000, std::uint64_t{13});
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(3);
  for (int k = 0; k < 2; ++k) mean += g.weights()[k] * g.means().row(k).transpose();
  const Eigen::VectorXd smean = S.colwise().mean().transpose();
  EXPECT_LT((smean - mean).cwiseAbs().maxCoeff(), 0.03);
  // Same seed, same draws.
  EXPECT_TRUE(g.sample(5, std::uint64_t{13}).isApprox(S.topRows(5)));
}

TEST(Gmm, DegenerateDataFailsClearly) {
  GmmSettings s;
  s.n_components = 3;
  GaussianMixture g(s);
  RowMatrixXd two(2, 2);
  two << 0, 0, 1, 1;
  EXPECT_THROW(g.fit(two), std::invalid_argument);  // fewer samples than components
  RowMatrixXd dup(10, 2);
  dup.setZero();
  dup.bottomRows(5).setOnes();
  try {
    g.fit(dup);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("distinct"), std::string::npos) << e.what();
  }
  RowMatrixXd nan = RowMatrixXd::Zero(5, 2);
  nan(3, 1) = std::nan("");
  EXPECT_THROW(g.fit(nan), std::invalid_argument);
  Eigen::VectorXd w = Eigen::VectorXd::Ones(10);
  w[2] = -1;
  EXPECT_THROW(g.fit(dup, w), std::invalid_argument);
  // With no regularisation, a component on a single repeated point has a singular covariance.
  s.n_components = 2;
  s.reg_covar = 0.0;
  GaussianMixture h(s);
  EXPECT_THROW(h.fit(dup), std::invalid_argument);
}

TEST(Gmm, UnfittedMixtureAndFeaturesOfZeroDensityFailClearly) {
  const GaussianMixture g(GmmSettings{});
  const RowMatrixXd X = RowMatrixXd::Zero(3, 2);
  EXPECT_THROW(g.score_samples(X), std::invalid_argument);
  EXPECT_THROW(g.sample(3, std::uint64_t{0}), std::invalid_argument);
  EXPECT_THROW(g.marginal({0}), std::invalid_argument);
  try {
    g.predict_proba(X);
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("GaussianMixture.predict_proba: the mixture is not fitted"), std::string::npos)
        << e.what();
  }
  // Features so far away that every component's weight underflows: an error, not a draw from the last component.
  RowMatrixXd mu(2, 2);
  mu << 0, 0, 1, 1;
  const GaussianMixture joint = GaussianMixture::from_parameters(
      Eigen::Vector2d(0.5, 0.5), mu, {Eigen::Matrix2d::Identity(), Eigen::Matrix2d::Identity()});
  const ConditionalGaussianMixture c(joint, 1);
  std::mt19937_64 rng(0);
  EXPECT_NO_THROW(c.sample(RowMatrixXd::Constant(1, 1, 0.5), rng));
  EXPECT_THROW(c.sample(RowMatrixXd::Constant(1, 1, 1e200), rng), std::invalid_argument);
}
