// Both PoseDensity implementations (PoseMixture, PoseKDE) against the same properties: normalisation
// on R^3 x SO(3), q/-q invariance, conditioning on features, reproducible sampling.
#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <random>

#include <gtest/gtest.h>

#include "graspmix/density/kde.hpp"
#include "graspmix/density/pose_mixture.hpp"

using namespace graspmix;

namespace {

/// Two groups of poses: feature 0 near position (0,0,0) rotated about z by ~0.3 rad; feature 1 near
/// (0.05, 0, 0) rotated about x by ~-0.5 rad.
void make_data(int n, PoseArray& poses, RowMatrixXd& features, std::uint64_t seed, double spread = 1.0) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> z;
  poses.resize(n, 7);
  features.resize(n, 1);
  for (int i = 0; i < n; ++i) {
    const bool b = i % 2;
    const Eigen::Vector3d p = (b ? Eigen::Vector3d(0.05, 0, 0) : Eigen::Vector3d::Zero()) +
                              0.004 * spread * Eigen::Vector3d(z(rng), z(rng), z(rng));
    const double a = 0.05 * spread;
    const Eigen::Quaterniond centre = b ? Eigen::Quaterniond(Eigen::AngleAxisd(-0.5, Eigen::Vector3d::UnitX()))
                                        : Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
    // Isotropic rotation noise of about `a` rad about every axis.
    const Eigen::Vector3d noise(a * z(rng), a * z(rng), a * z(rng));
    const Eigen::Quaterniond q = centre * Eigen::Quaterniond(Eigen::AngleAxisd(noise.norm(), noise.normalized()));
    poses.row(i) << p.transpose(), q.x(), q.y(), q.z(), q.w();
    features(i, 0) = (b ? 1.0 : 0.0) + 0.05 * z(rng);
  }
}

Eigen::Vector4d uniform_hemisphere_quaternion(std::mt19937_64& rng) {
  std::normal_distribution<double> z;
  Eigen::Vector4d q(z(rng), z(rng), z(rng), z(rng));
  q.normalize();
  return q[3] < 0 ? Eigen::Vector4d(-q) : q;
}

template <typename D>
std::unique_ptr<PoseDensity> make_density(double spread = 1.0);
template <>
std::unique_ptr<PoseDensity> make_density<PoseMixture>(double) {
  GmmSettings s;
  s.n_components = 2;
  return std::make_unique<PoseMixture>(s);
}
template <>
std::unique_ptr<PoseDensity> make_density<PoseKDE>(double spread) {
  KdeSettings s;
  s.position_bandwidth = 0.004 * spread;
  s.orientation_bandwidth = 0.1 * spread;
  s.feature_bandwidth = Eigen::VectorXd::Constant(1, 0.05);
  return std::make_unique<PoseKDE>(s);
}

template <typename D>
class PoseDensityTest : public ::testing::Test {};
using Densities = ::testing::Types<PoseMixture, PoseKDE>;
TYPED_TEST_SUITE(PoseDensityTest, Densities);

}  // namespace

TYPED_TEST(PoseDensityTest, ConditionalIntegratesToOne) {
  PoseArray poses;
  RowMatrixXd feats;
  // Broad data and kernels, so that plain Monte Carlo (uniform positions in a box around the data,
  // uniform rotations) has a small variance; normalisation does not depend on the widths.
  const double spread = 10.0;
  make_data(200, poses, feats, 1, spread);
  auto d = make_density<TypeParam>(spread);
  d->fit(poses, feats, {});
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> ux(-0.16, 0.21), uy(-0.16, 0.16);
  const int n = 600000;
  PoseArray q(n, 7);
  for (int i = 0; i < n; ++i) q.row(i) << ux(rng), uy(rng), uy(rng), uniform_hemisphere_quaternion(rng).transpose();
  const double volume = 0.37 * 0.32 * 0.32 * M_PI * M_PI;  // box x hemisphere of S^3 (area pi^2)
  for (double r : {0.0, 1.0}) {
    const Eigen::VectorXd lp = d->log_density(q, RowMatrixXd::Constant(n, 1, r));
    const Eigen::ArrayXd v = volume * lp.array().exp();
    const double integral = v.mean();
    const double std_error = std::sqrt((v - integral).square().mean() / n);
    // Within four standard errors of the Monte Carlo estimate (and the estimate itself precise).
    EXPECT_LT(std_error, 0.03) << d->kind();
    EXPECT_NEAR(integral, 1.0, 4.0 * std_error + 0.01) << d->kind() << " r=" << r << " se=" << std_error;
  }
}

TYPED_TEST(PoseDensityTest, QAndMinusQHaveTheSameDensity) {
  PoseArray poses;
  RowMatrixXd feats;
  make_data(100, poses, feats, 3);
  auto d = make_density<TypeParam>();
  d->fit(poses, feats, {});
  PoseArray flipped = poses;
  flipped.rightCols<4>() *= -1.0;
  EXPECT_TRUE(d->log_density(poses, feats).isApprox(d->log_density(flipped, feats), 1e-10));
}

TYPED_TEST(PoseDensityTest, FeaturesSelectThePoseCluster) {
  PoseArray poses;
  RowMatrixXd feats;
  make_data(300, poses, feats, 4);
  auto d = make_density<TypeParam>();
  d->fit(poses, feats, {});
  std::mt19937_64 rng(5);
  for (double r : {0.0, 1.0}) {
    const PoseArray s = d->sample(RowMatrixXd::Constant(500, 1, r), rng);
    const double mean_x = s.col(0).mean();
    EXPECT_NEAR(mean_x, r * 0.05, 0.004) << d->kind();
    // Rotation: about z for r = 0 (qz ~ sin(0.15)), about x for r = 1 (qx ~ sin(-0.25)).
    if (r == 0.0) EXPECT_NEAR(s.col(5).mean(), std::sin(0.15), 0.02) << d->kind();
    if (r == 1.0) EXPECT_NEAR(s.col(3).mean(), std::sin(-0.25), 0.02) << d->kind();
  }
  // The pose of cluster 0 is likelier given feature 0 than given feature 1, and the other way round.
  PoseArray p0(1, 7), p1(1, 7);
  p0 << 0, 0, 0, 0, 0, std::sin(0.15), std::cos(0.15);
  p1 << 0.05, 0, 0, std::sin(-0.25), 0, 0, std::cos(0.25);
  const RowMatrixXd f0 = RowMatrixXd::Zero(1, 1), f1 = RowMatrixXd::Ones(1, 1);
  EXPECT_GT(d->log_density(p0, f0)[0], d->log_density(p0, f1)[0] + 5.0);
  EXPECT_GT(d->log_density(p1, f1)[0], d->log_density(p1, f0)[0] + 5.0);
  // p(r) is high at both observed features and low between them... and far away.
  RowMatrixXd fr(3, 1);
  fr << 0.0, 1.0, 3.0;
  const Eigen::VectorXd lf = d->feature_log_density(fr);
  EXPECT_GT(lf[0], lf[2] + 10.0);
  EXPECT_GT(lf[1], lf[2] + 10.0);
}

TYPED_TEST(PoseDensityTest, SameSeedSameSamples) {
  PoseArray poses;
  RowMatrixXd feats;
  make_data(60, poses, feats, 6);
  auto d = make_density<TypeParam>();
  d->fit(poses, feats, {});
  std::mt19937_64 a(7), b(7);
  EXPECT_TRUE(d->sample(feats, a).isApprox(d->sample(feats, b)));
  auto c = d->clone();
  std::mt19937_64 e(7), f(7);
  const PoseArray from_clone = c->sample(feats, e), from_original = d->sample(feats, f);
  EXPECT_TRUE(from_clone.isApprox(from_original));
}

TYPED_TEST(PoseDensityTest, BadInputThrows) {
  PoseArray poses;
  RowMatrixXd feats;
  make_data(20, poses, feats, 8);
  auto d = make_density<TypeParam>();
  // Not fitted: a clear invalid_argument (ValueError in Python) from every evaluation and from sampling.
  for (const auto& call :
       std::vector<std::function<void()>>{[&] { d->log_density(poses, feats); }, [&] { d->feature_log_density(feats); },
                                          [&] {
                                            std::mt19937_64 rng(0);
                                            d->sample(feats, rng);
                                          }}) {
    try {
      call();
      ADD_FAILURE() << d->kind() << ": no error from an unfitted density";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("not fitted"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(d->fit(poses, RowMatrixXd::Zero(19, 1), {}), std::invalid_argument);
  Eigen::VectorXd w = Eigen::VectorXd::Ones(20);
  w[4] = 0.0;
  EXPECT_THROW(d->fit(poses, feats, w), std::invalid_argument);
  PoseArray bad = poses;
  bad(3, 2) = std::nan("");
  EXPECT_THROW(d->fit(bad, feats, {}), std::invalid_argument);
  d->fit(poses, feats, {});
  EXPECT_THROW(d->log_density(poses, RowMatrixXd::Zero(20, 2)), std::invalid_argument);
}

TEST(PoseKde, NormaliserMatchesNumericalIntegrationAndIsContinuous) {
  // Integrate the hemisphere kernel C(k) (e^{k t} + e^{-k t}) over the hemisphere by Monte Carlo.
  std::mt19937_64 rng(9);
  for (double kappa : {0.5, 4.0, 20.0}) {
    const double ln = log_vmf_s3_normaliser(kappa);
    const Eigen::Vector4d mu = Eigen::Vector4d(0.3, -0.1, 0.2, 0.927).normalized();
    double sum = 0.0;
    const int n = 400000;
    for (int i = 0; i < n; ++i) {
      const double t = mu.dot(uniform_hemisphere_quaternion(rng));
      sum += std::exp(ln + kappa * t) + std::exp(ln - kappa * t);
    }
    EXPECT_NEAR(sum / n * M_PI * M_PI, 1.0, 0.02) << kappa;
  }
  // The asymptotic branch takes over at kappa = 50 without a jump.
  EXPECT_NEAR(log_vmf_s3_normaliser(49.999999), log_vmf_s3_normaliser(50.0), 1e-6);
  EXPECT_THROW(log_vmf_s3_normaliser(-1.0), std::invalid_argument);
  KdeSettings s;
  s.position_bandwidth = -0.1;
  EXPECT_THROW(PoseKDE{s}, std::invalid_argument);
}

TEST(PoseMixture, ChartIsCentredOnTheDataSoRotationsNearPiStayTogether) {
  // Rotations of ~pi about z would straddle the log map's cut at the identity chart.
  std::mt19937_64 rng(10);
  std::normal_distribution<double> z;
  PoseArray poses(200, 7);
  for (int i = 0; i < 200; ++i) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(M_PI + 0.1 * z(rng), Eigen::Vector3d::UnitZ()));
    poses.row(i) << 0.001 * z(rng), 0.001 * z(rng), 0.001 * z(rng), q.x(), q.y(), q.z(), q.w();
  }
  GmmSettings s;
  s.n_components = 1;
  PoseMixture m(s);
  m.fit(poses, RowMatrixXd(200, 0), {});
  // One component suffices: the fitted rotation spread is the data's (0.1 rad -> 0.05 in half-angle).
  EXPECT_NEAR(std::sqrt(m.joint().covariances()[0](5, 5)), 0.05, 0.01);
  EXPECT_NEAR(std::abs(m.reference().z()), 1.0, 1e-2);
}

TEST(PoseKde, DegenerateOrientationBandwidthIsRefusedAndSmallOnesSampleTheRightSpread) {
  for (double bw :
       {0.0, -0.1, std::nan(""), std::numeric_limits<double>::infinity(), 1e-7, 0.99 * kMinOrientationBandwidth}) {
    KdeSettings s;
    s.orientation_bandwidth = bw;
    EXPECT_THROW(PoseKDE{s}, std::invalid_argument) << bw;
  }
  // Down to the bound the sampler terminates (1e-4 used to loop forever on a NaN acceptance test) and
  // draws rotation vectors with std bw per axis: for kappa = 4 / bw^2 the kernel is exp(-|w|^2 / (2 bw^2))
  // to second order, so the rms rotation angle is sqrt(3) bw.
  PoseArray one(1, 7);
  one << 0, 0, 0, 0, 0, 0, 1;
  for (double bw : {kMinOrientationBandwidth, 1e-4, 1e-2}) {
    KdeSettings s;
    s.orientation_bandwidth = bw;
    PoseKDE d(s);
    d.fit(one, RowMatrixXd(1, 0), {});
    std::mt19937_64 rng(3);
    const PoseArray draws = d.sample(RowMatrixXd(4000, 0), rng);
    double sq = 0;
    for (Eigen::Index i = 0; i < draws.rows(); ++i) {
      const double angle = 2.0 * std::acos(std::min(1.0, std::abs(draws(i, 6))));
      sq += angle * angle;
    }
    EXPECT_NEAR(std::sqrt(sq / draws.rows()) / (std::sqrt(3.0) * bw), 1.0, 0.05) << bw;
  }
}
