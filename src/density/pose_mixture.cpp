#include "graspmix/density/pose_mixture.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>

#include "graspmix/core/se3.hpp"

namespace graspmix {

namespace {
std::string str(Eigen::Index v) { return std::to_string(v); }
}  // namespace

// ---- shared checks of the PoseDensity interface ----------------------------------------------

Eigen::VectorXd check_pose_data(const Eigen::Ref<const PoseArray>& poses, const Eigen::Ref<const RowMatrixXd>& features,
                                const Eigen::VectorXd& weights, const char* what) {
  const std::string w(what);
  if (poses.rows() == 0) throw std::invalid_argument(w + ": no poses given");
  if (features.rows() != poses.rows()) {
    throw std::invalid_argument(w + ": " + str(poses.rows()) + " poses but " + str(features.rows()) + " feature rows");
  }
  require_finite(poses, (w + ": poses").c_str());
  require_finite(features, (w + ": features").c_str());
  for (Eigen::Index i = 0; i < poses.rows(); ++i) {
    if (poses.row(i).tail<4>().norm() < 1e-12) {
      throw std::invalid_argument(w + ": pose " + str(i) + " has a zero quaternion");
    }
  }
  if (weights.size() == 0) return Eigen::VectorXd::Ones(poses.rows());
  if (weights.size() != poses.rows()) {
    throw std::invalid_argument(w + ": " + str(weights.size()) + " weights for " + str(poses.rows()) + " poses");
  }
  for (Eigen::Index i = 0; i < weights.size(); ++i) {
    if (!std::isfinite(weights[i]) || weights[i] <= 0.0) {
      throw std::invalid_argument(w + ": weight " + str(i) + " is " + std::to_string(weights[i]) +
                                  "; weights must be positive and finite");
    }
  }
  return weights;
}

void check_feature_query(const Eigen::Ref<const RowMatrixXd>& features, int n_features, const char* what) {
  if (features.cols() != n_features) {
    throw std::invalid_argument(std::string(what) + ": features have " + str(features.cols()) +
                                " columns, the density was fitted with " + str(n_features));
  }
  require_finite(features, (std::string(what) + ": features").c_str());
}

void check_pose_query(const Eigen::Ref<const PoseArray>& poses, const Eigen::Ref<const RowMatrixXd>& features,
                      int n_features, const char* what) {
  if (features.rows() != poses.rows()) {
    throw std::invalid_argument(std::string(what) + ": " + str(poses.rows()) + " poses but " + str(features.rows()) +
                                " feature rows");
  }
  check_feature_query(features, n_features, what);
  require_finite(poses, (std::string(what) + ": poses").c_str());
}

// ---- PoseMixture -----------------------------------------------------------------------------

Eigen::Quaterniond mean_quaternion(const Eigen::Ref<const QuatArray>& q, const Eigen::VectorXd& weights) {
  Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
  for (Eigen::Index i = 0; i < q.rows(); ++i) {
    const Eigen::Vector4d v = q.row(i).transpose().normalized();
    M += weights[i] * v * v.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> es(M);
  const Eigen::Vector4d v = es.eigenvectors().col(3);  // eigenvalues ascend
  return canonical(Eigen::Quaterniond(v[3], v[0], v[1], v[2]).normalized());
}

PoseMixture::PoseMixture(GmmSettings settings) : settings_(settings), joint_(settings) {}

PoseMixture PoseMixture::from_parameters(const Eigen::Quaterniond& reference, const GaussianMixture& joint) {
  if (!joint.fitted()) throw std::invalid_argument("PoseMixture.from_parameters: the joint mixture has no parameters");
  if (joint.dim() < 6) {
    throw std::invalid_argument("PoseMixture.from_parameters: the joint mixture has " + str(joint.dim()) +
                                " dimensions, at least 6 (position, log-rotation) are needed");
  }
  if (!reference.coeffs().allFinite() || reference.norm() < 1e-12) {
    throw std::invalid_argument("PoseMixture.from_parameters: the reference quaternion is not valid");
  }
  GmmSettings s = joint.settings();
  s.n_components = joint.n_components();
  PoseMixture m(s);
  m.joint_ = joint;
  m.reference_ = canonical(reference.normalized());
  m.n_features_ = joint.dim() - 6;
  m.conditional_ = ConditionalGaussianMixture(joint, 6);
  return m;
}

RowMatrixXd PoseMixture::to_coordinates(const Eigen::Ref<const PoseArray>& poses, Eigen::VectorXd* log_jacobian) const {
  RowMatrixXd X(poses.rows(), 6);
  if (log_jacobian) log_jacobian->resize(poses.rows());
  const Eigen::Quaterniond ref_inv = reference_.conjugate();
  for (Eigen::Index i = 0; i < poses.rows(); ++i) {
    Eigen::Quaterniond q = row_quaternion(poses, i);
    const double n = q.norm();
    if (!(n > 1e-12)) throw std::invalid_argument("PoseMixture: pose " + str(i) + " has a zero quaternion");
    q.coeffs() /= n;
    const Eigen::Vector3d w = quat_log(ref_inv * q);
    X.row(i) << poses(i, 0), poses(i, 1), poses(i, 2), w.x(), w.y(), w.z();
    if (log_jacobian) {
      // The area element of S^3 in exponential coordinates is (sin|w| / |w|)^2 d^3w.
      const double a = w.norm();
      (*log_jacobian)[i] = a < 1e-8 ? 0.0 : 2.0 * std::log(std::sin(a) / a);
    }
  }
  return X;
}

PoseArray PoseMixture::from_coordinates(const Eigen::Ref<const RowMatrixXd>& coords) const {
  PoseArray out(coords.rows(), 7);
  for (Eigen::Index i = 0; i < coords.rows(); ++i) {
    const Eigen::Quaterniond q =
        canonical((reference_ * quat_exp(Eigen::Vector3d(coords.row(i).segment<3>(3)))).normalized());
    out.row(i) << coords(i, 0), coords(i, 1), coords(i, 2), q.x(), q.y(), q.z(), q.w();
  }
  return out;
}

void PoseMixture::fit(const Eigen::Ref<const PoseArray>& poses, const Eigen::Ref<const RowMatrixXd>& features,
                      const Eigen::VectorXd& weights) {
  const Eigen::VectorXd w = check_pose_data(poses, features, weights, "PoseMixture.fit");
  reference_ = mean_quaternion(poses.rightCols<4>(), w);
  const Eigen::Index n_f = features.cols();
  RowMatrixXd X(poses.rows(), 6 + n_f);
  X.leftCols(6) = to_coordinates(poses);
  X.rightCols(n_f) = features;
  joint_ = GaussianMixture(settings_);
  joint_.fit(X, w);
  n_features_ = static_cast<int>(n_f);
  conditional_ = ConditionalGaussianMixture(joint_, 6);
}

void PoseMixture::require_fitted(const char* what) const {
  if (!fitted()) {
    throw std::invalid_argument(std::string("PoseMixture.") + what +
                                ": the mixture is not fitted yet (call fit, or make it with from_parameters)");
  }
}

Eigen::VectorXd PoseMixture::log_density(const Eigen::Ref<const PoseArray>& poses,
                                         const Eigen::Ref<const RowMatrixXd>& features) const {
  require_fitted("log_density");
  check_pose_query(poses, features, n_features_, "PoseMixture.log_density");
  Eigen::VectorXd log_jac;
  const RowMatrixXd U = to_coordinates(poses, &log_jac);
  return conditional_.log_density(U, features) - log_jac;
}

Eigen::VectorXd PoseMixture::feature_log_density(const Eigen::Ref<const RowMatrixXd>& features) const {
  require_fitted("feature_log_density");
  check_feature_query(features, n_features_, "PoseMixture.feature_log_density");
  return conditional_.log_feature_density(features);
}

PoseArray PoseMixture::sample(const Eigen::Ref<const RowMatrixXd>& features, std::mt19937_64& rng) const {
  require_fitted("sample");
  check_feature_query(features, n_features_, "PoseMixture.sample");
  return from_coordinates(conditional_.sample(features, rng));
}

}  // namespace graspmix
