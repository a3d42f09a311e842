#include "graspmix/density/kde.hpp"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "graspmix/core/se3.hpp"
#include "graspmix/density/gmm.hpp"

namespace graspmix {

namespace {

constexpr double kLog2Pi = 1.8378770664093454836;
constexpr double kPi = 3.14159265358979323846;

double log_bessel_i1(double x) {
  if (x < 50.0) return std::log(std::cyl_bessel_i(1.0, x));
  // Hankel's asymptotic series for I_1, accurate to ~1e-10 here.
  const double t = 1.0 / (8.0 * x);
  return x - 0.5 * std::log(2.0 * kPi * x) + std::log(1.0 - 3.0 * t - 7.5 * t * t - 52.5 * t * t * t);
}

/// log of the antipodal kernel at cosine t: kappa |t| + log(1 + exp(-2 kappa |t|)) + log normaliser.
inline double log_q_kernel(double t, double kappa, double log_norm) {
  const double a = kappa * std::abs(t);
  return log_norm + a + std::log1p(std::exp(-2.0 * a));
}

std::string format_double(double v) {
  std::ostringstream out;
  out << v;  // 1e-06, not to_string's 0.000001 (or 0.000000 for 1e-9)
  return out.str();
}

/// Proposals of one draw before the samplers give up; Wood's sampler accepts more than half of its
/// proposals at every concentration, so this is never reached by valid parameters.
constexpr int kMaxProposals = 1000;

/// Wood (1994) rejection sampler for the cosine W = <q, mu> of the vMF on S^3 (p = 4), written with
/// 1 - x0 and 1 - W instead of x0 and W so that large concentrations keep their precision (the direct
/// form loses b = 3 / (2 kappa + sqrt(4 kappa^2 + 9)) to cancellation at kappa ~ 1e8 and then compares NaNs).
class WoodSampler {
 public:
  explicit WoodSampler(double kappa) : kappa_(kappa) {
    b_ = kP1 / (2.0 * kappa + std::sqrt(4.0 * kappa * kappa + kP1 * kP1));
    one_minus_x0_ = 2.0 * b_ / (1.0 + b_);
    x0_ = 1.0 - one_minus_x0_;
    log_1_minus_x0sq_ = std::log(one_minus_x0_ * (1.0 + x0_));
  }

  /// One W; throws when the acceptance test is not a number or nothing is accepted. The caller keeps the
  /// distributions (they carry state between draws, and the random stream stays that of earlier versions).
  double operator()(std::mt19937_64& rng, std::gamma_distribution<double>& gamma,
                    std::uniform_real_distribution<double>& uni) const {
    for (int i = 0; i < kMaxProposals; ++i) {
      const double g1 = gamma(rng), g2 = gamma(rng);
      const double z = g1 / (g1 + g2);
      const double one_minus_w = 2.0 * b_ * z / (1.0 - (1.0 - b_) * z);
      // kappa W + 3 log(1 - x0 W) - c with c = kappa x0 + 3 log(1 - x0^2).
      const double test = kappa_ * (one_minus_x0_ - one_minus_w) +
                          kP1 * (std::log(one_minus_x0_ + x0_ * one_minus_w) - log_1_minus_x0sq_);
      if (std::isnan(test)) {
        throw std::invalid_argument("PoseKDE.sample: the rotation sampler's acceptance test is NaN at concentration " +
                                    format_double(kappa_) + " (degenerate orientation_bandwidth)");
      }
      if (test >= std::log(uni(rng))) return 1.0 - one_minus_w;
    }
    throw std::invalid_argument("PoseKDE.sample: the rotation sampler rejected " + std::to_string(kMaxProposals) +
                                " proposals in a row at concentration " + format_double(kappa_) +
                                " (degenerate orientation_bandwidth)");
  }

 private:
  static constexpr double kP1 = 3.0;  // p - 1
  double kappa_, b_, one_minus_x0_, x0_, log_1_minus_x0sq_;
};

/// A unit vector orthogonal to the unit vector mu.
Eigen::Vector4d orthogonal_direction(const Eigen::Vector4d& mu, std::mt19937_64& rng,
                                     std::normal_distribution<double>& normal) {
  for (int i = 0; i < kMaxProposals; ++i) {
    Eigen::Vector4d v;
    for (int j = 0; j < 4; ++j) v[j] = normal(rng);
    v -= v.dot(mu) * mu;
    if (v.norm() >= 1e-9) return v.normalized();  // fails only for a non-unit or NaN mu
  }
  throw std::invalid_argument("PoseKDE.sample: no direction orthogonal to a kernel's quaternion (is it NaN?)");
}

}  // namespace

double log_vmf_s3_normaliser(double kappa) {
  if (!(kappa > 0.0) || !std::isfinite(kappa)) {
    throw std::invalid_argument("vMF concentration must be positive and finite, got " + std::to_string(kappa));
  }
  // Hemisphere density C_4(kappa) (e^{kappa t} + e^{-kappa t}) with C_4 = kappa / ((2 pi)^2 I_1(kappa)).
  return std::log(kappa) - 2.0 * std::log(2.0 * kPi) - log_bessel_i1(kappa);
}

PoseKDE::PoseKDE(KdeSettings s) : settings_(std::move(s)) {
  if (!(settings_.position_bandwidth > 0.0) || !std::isfinite(settings_.position_bandwidth)) {
    throw std::invalid_argument("PoseKDE: position_bandwidth must be positive, got " +
                                std::to_string(settings_.position_bandwidth));
  }
  if (!(settings_.orientation_bandwidth >= kMinOrientationBandwidth) ||
      !std::isfinite(settings_.orientation_bandwidth)) {
    throw std::invalid_argument("PoseKDE: orientation_bandwidth must be finite and at least " +
                                format_double(kMinOrientationBandwidth) + " rad, got " +
                                format_double(settings_.orientation_bandwidth));
  }
  for (Eigen::Index i = 0; i < settings_.feature_bandwidth.size(); ++i) {
    if (!(settings_.feature_bandwidth[i] > 0.0) || !std::isfinite(settings_.feature_bandwidth[i])) {
      throw std::invalid_argument("PoseKDE: feature_bandwidth[" + std::to_string(i) + "] must be positive, got " +
                                  std::to_string(settings_.feature_bandwidth[i]));
    }
  }
  kappa_ = 4.0 / (settings_.orientation_bandwidth * settings_.orientation_bandwidth);
  log_norm_q_ = log_vmf_s3_normaliser(kappa_);
  log_norm_p_ = -1.5 * (kLog2Pi + 2.0 * std::log(settings_.position_bandwidth));
}

void PoseKDE::fit(const Eigen::Ref<const PoseArray>& poses, const Eigen::Ref<const RowMatrixXd>& features,
                  const Eigen::VectorXd& weights) {
  const Eigen::VectorXd w = check_pose_data(poses, features, weights, "PoseKDE.fit");
  const Eigen::Index n = poses.rows(), nf = features.cols();
  const Eigen::VectorXd& bw = settings_.feature_bandwidth;
  if (bw.size() > 1 && bw.size() != nf) {
    throw std::invalid_argument("PoseKDE.fit: feature_bandwidth has " + std::to_string(bw.size()) + " entries for " +
                                std::to_string(nf) + " features");
  }
  if (bw.size() == 0 && nf > 0) {
    throw std::invalid_argument("PoseKDE.fit: feature_bandwidth is empty but the data has " + std::to_string(nf) +
                                " features");
  }
  feature_bw_ = bw.size() == 1 ? Eigen::VectorXd(Eigen::VectorXd::Constant(nf, bw[0])) : bw;
  log_norm_r_ = -0.5 * nf * kLog2Pi - feature_bw_.array().log().sum();
  positions_ = poses.leftCols<3>();
  orientations_.resize(n, 4);
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Vector4d q = poses.row(i).tail<4>().transpose().normalized();
    if (q[3] < 0) q = -q;
    orientations_.row(i) = q.transpose();
  }
  features_ = features;
  weights_ = w / w.sum();
  log_weights_ = weights_.array().log();
}

void PoseKDE::require_fitted(const char* what) const {
  if (!fitted())
    throw std::invalid_argument(std::string("PoseKDE.") + what + ": the density is not fitted yet (call fit)");
}

Eigen::VectorXd PoseKDE::log_feature_kernels(const Eigen::Ref<const Eigen::RowVectorXd>& r) const {
  if (features_.cols() == 0) return log_weights_;
  const Eigen::RowVectorXd inv = feature_bw_.cwiseInverse().transpose();
  const Eigen::VectorXd m =
      ((features_.rowwise() - r).array().rowwise() * inv.array()).matrix().rowwise().squaredNorm();
  return log_weights_.array() - 0.5 * m.array() + log_norm_r_;
}

Eigen::VectorXd PoseKDE::log_density(const Eigen::Ref<const PoseArray>& poses,
                                     const Eigen::Ref<const RowMatrixXd>& features) const {
  require_fitted("log_density");
  check_pose_query(poses, features, n_features(), "PoseKDE.log_density");
  const Eigen::Index n = poses.rows(), K = n_kernels();
  const double inv_var = 1.0 / (settings_.position_bandwidth * settings_.position_bandwidth);
  Eigen::VectorXd out(n);
#pragma omp parallel for schedule(static) if (n * K >= 200000)
  for (Eigen::Index i = 0; i < n; ++i) {
    Eigen::Vector4d q = poses.row(i).tail<4>().transpose();
    const double qn = q.norm();
    if (!(qn > 1e-12)) {
      out[i] = std::numeric_limits<double>::quiet_NaN();  // reported below, outside the parallel region
      continue;
    }
    q /= qn;
    const Eigen::VectorXd lr = log_feature_kernels(features.row(i));
    Eigen::VectorXd terms(K);
    for (Eigen::Index k = 0; k < K; ++k) {
      const double d2 = (positions_.row(k) - poses.row(i).head<3>()).squaredNorm();
      terms[k] =
          lr[k] - 0.5 * d2 * inv_var + log_norm_p_ + log_q_kernel(orientations_.row(k).dot(q), kappa_, log_norm_q_);
    }
    const double mt = terms.maxCoeff(), mr = lr.maxCoeff();
    const double num = mt + std::log((terms.array() - mt).exp().sum());
    const double den = mr + std::log((lr.array() - mr).exp().sum());
    out[i] = num - den;
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    if (std::isnan(out[i])) {
      throw std::invalid_argument("PoseKDE.log_density: pose " + std::to_string(i) + " has a zero quaternion");
    }
  }
  return out;
}

Eigen::VectorXd PoseKDE::feature_log_density(const Eigen::Ref<const RowMatrixXd>& features) const {
  require_fitted("feature_log_density");
  check_feature_query(features, n_features(), "PoseKDE.feature_log_density");
  Eigen::VectorXd out(features.rows());
  for (Eigen::Index i = 0; i < features.rows(); ++i) {
    const Eigen::VectorXd lr = log_feature_kernels(features.row(i));
    const double m = lr.maxCoeff();
    out[i] = m + std::log((lr.array() - m).exp().sum());
  }
  return out;
}

PoseArray PoseKDE::sample(const Eigen::Ref<const RowMatrixXd>& features, std::mt19937_64& rng) const {
  require_fitted("sample");
  check_feature_query(features, n_features(), "PoseKDE.sample");
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  std::normal_distribution<double> normal;
  std::gamma_distribution<double> gamma(1.5, 1.0);
  const WoodSampler wood(kappa_);
  PoseArray out(features.rows(), 7);
  for (Eigen::Index i = 0; i < features.rows(); ++i) {
    Eigen::VectorXd lw = log_feature_kernels(features.row(i));
    const double top = lw.maxCoeff();
    if (!std::isfinite(top)) {
      throw std::invalid_argument("PoseKDE.sample: feature row " + std::to_string(i) +
                                  " has zero density under every kernel");
    }
    lw.array() -= top;
    const Eigen::VectorXd p = lw.array().exp();
    double u = uni(rng) * p.sum();
    Eigen::Index k = 0;
    for (; k + 1 < p.size(); ++k) {
      u -= p[k];
      if (u <= 0.0) break;
    }
    const double W = wood(rng, gamma, uni);
    const Eigen::Vector4d mu = orientations_.row(k).transpose();
    const Eigen::Vector4d v = orthogonal_direction(mu, rng, normal);
    Eigen::Vector4d q = W * mu + std::sqrt(std::max(0.0, (1.0 - W) * (1.0 + W))) * v;
    q.normalize();
    if (q[3] < 0) q = -q;
    const double s = settings_.position_bandwidth;
    out.row(i) << positions_(k, 0) + s * normal(rng), positions_(k, 1) + s * normal(rng),
        positions_(k, 2) + s * normal(rng), q[0], q[1], q[2], q[3];
  }
  return out;
}

}  // namespace graspmix
