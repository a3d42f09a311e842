// The hand configuration model C(h_c) against numerical integration and its definition.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "graspmix/grasp/config_model.hpp"

using namespace graspmix;

namespace {
RowMatrixXd limits1(double lo, double hi) {
  RowMatrixXd l(1, 2);
  l << lo, hi;
  return l;
}
}  // namespace

TEST(ConfigModel, OneJointDensityIntegratesToOneAndPeaksAtTheGrasp) {
  Eigen::VectorXd pre(1), grasp(1);
  pre << 0.05;
  grasp << 0.03;
  const ConfigModel c(pre, grasp, limits1(0.0, 0.055));
  const int n = 20001;
  RowMatrixXd q(n, 1);
  for (int i = 0; i < n; ++i) q(i, 0) = -0.05 + 0.15 * i / (n - 1);
  const Eigen::VectorXd lp = c.log_density(q);
  double integral = 0.0;
  for (int i = 1; i < n; ++i) integral += 0.5 * (std::exp(lp[i]) + std::exp(lp[i - 1])) * (q(i, 0) - q(i - 1, 0));
  EXPECT_NEAR(integral, 1.0, 1e-6);
  Eigen::Index best;
  lp.maxCoeff(&best);
  EXPECT_NEAR(q(best, 0), 0.03, 0.002);
  // Symmetric about h_g: h(gamma) and h(-gamma) have the same weight.
  RowMatrixXd sym(2, 1);
  sym << 0.03 - 0.012, 0.03 + 0.012;
  const Eigen::VectorXd ls = c.log_density(sym);
  EXPECT_NEAR(ls[0], ls[1], 1e-9);
  EXPECT_NEAR(c.sigma(), 0.1 * 0.02, 1e-15);
}

TEST(ConfigModel, KernelsLieOnTheDemonstratedLine) {
  Eigen::VectorXd pre(2), grasp(2);
  pre << 0.4, 1.0;
  grasp << 0.1, 0.2;
  RowMatrixXd lim(2, 2);
  lim << -1, 2, -1, 2;
  ConfigModelSettings s;
  s.n_kernels = 5;
  s.beta = 1.0;
  const ConfigModel c(pre, grasp, lim, s);
  ASSERT_EQ(c.kernels().rows(), 5);
  EXPECT_TRUE(c.kernels().row(2).isApprox(grasp.transpose()));
  EXPECT_TRUE(c.kernels().row(4).isApprox(pre.transpose()));
  EXPECT_TRUE(c.kernels().row(0).isApprox((2 * grasp - pre).transpose()));
  // w(gamma) ∝ exp(-alpha |gamma|): the middle kernel weighs e^alpha more than the ends.
  EXPECT_NEAR(c.log_weights()[2] - c.log_weights()[4], s.alpha, 1e-12);
}

TEST(ConfigModel, SamplesStayWithinLimitsAndPregraspOpensByTheDemonstratedAmount) {
  Eigen::VectorXd pre(1), grasp(1);
  pre << 0.05;
  grasp << 0.01;
  const ConfigModel c(pre, grasp, limits1(0.0, 0.055));
  std::mt19937_64 rng(3);
  const RowMatrixXd s = c.sample(5000, rng);
  EXPECT_GE(s.minCoeff(), 0.0);
  EXPECT_LE(s.maxCoeff(), 0.055);
  Eigen::VectorXd q(1);
  q << 0.02;
  EXPECT_NEAR(c.pregrasp_for(q)[0], 0.055, 1e-15);  // 0.06 clamped to the upper limit
  q << 0.005;
  EXPECT_NEAR(c.pregrasp_for(q)[0], 0.045, 1e-15);
}

TEST(ConfigModel, BadInputThrows) {
  Eigen::VectorXd a(1), b(2);
  a << 0.0;
  b << 0.0, 0.0;
  EXPECT_THROW(ConfigModel(a, b, limits1(0, 1)), std::invalid_argument);
  EXPECT_THROW(ConfigModel(a, a, RowMatrixXd(2, 2)), std::invalid_argument);
  ConfigModelSettings s;
  s.bandwidth = -1.0;
  EXPECT_THROW(ConfigModel(a, a, limits1(0, 1), s), std::invalid_argument);
  const ConfigModel c(a, a, limits1(0, 1));
  EXPECT_THROW(c.log_density(RowMatrixXd::Zero(3, 2)), std::invalid_argument);
}
