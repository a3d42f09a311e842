#include "graspmix/grasp/config_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "graspmix/density/gmm.hpp"

namespace graspmix {

namespace {
constexpr double kLog2Pi = 1.8378770664093454836;
}

ConfigModel::ConfigModel(const Eigen::VectorXd& pregrasp, const Eigen::VectorXd& grasp, const RowMatrixXd& limits,
                         ConfigModelSettings s)
    : settings_(s), pregrasp_(pregrasp), grasp_(grasp), limits_(limits) {
  const Eigen::Index D = grasp.size();
  if (pregrasp.size() != D) {
    throw std::invalid_argument("ConfigModel: pregrasp has " + std::to_string(pregrasp.size()) + " joints, grasp has " +
                                std::to_string(D));
  }
  if (limits.rows() != D || limits.cols() != 2) {
    throw std::invalid_argument("ConfigModel: limits must be (" + std::to_string(D) + ", 2)");
  }
  if (!pregrasp.allFinite() || !grasp.allFinite())
    throw std::invalid_argument("ConfigModel: joints contain NaN or inf");
  for (Eigen::Index j = 0; j < D; ++j) {
    if (std::isnan(limits(j, 0)) || std::isnan(limits(j, 1)) || limits(j, 0) > limits(j, 1)) {
      throw std::invalid_argument("ConfigModel: joint " + std::to_string(j) + " has limits [" +
                                  std::to_string(limits(j, 0)) + ", " + std::to_string(limits(j, 1)) +
                                  "]: lower must not exceed upper");
    }
  }
  if (s.n_kernels < 1) throw std::invalid_argument("ConfigModel: n_kernels must be >= 1");
  if (!(s.beta >= 0.0) || !(s.alpha >= 0.0) || !(s.bandwidth > 0.0) || !(s.min_bandwidth > 0.0)) {
    throw std::invalid_argument("ConfigModel: beta and alpha must be >= 0, bandwidth and min_bandwidth > 0");
  }
  const Eigen::VectorXd delta = pregrasp - grasp;
  const double length = delta.norm();
  sigma_ = std::max(s.min_bandwidth, s.bandwidth * length);
  kernels_.resize(s.n_kernels, D);
  log_weights_.resize(s.n_kernels);
  for (int k = 0; k < s.n_kernels; ++k) {
    const double gamma = s.n_kernels == 1 ? 0.0 : -s.beta + 2.0 * s.beta * k / (s.n_kernels - 1);
    kernels_.row(k) = (grasp + gamma * delta).transpose();
    // |h(gamma) - h_g| / |h_e - h_g| = |gamma|.
    log_weights_[k] = -s.alpha * std::abs(gamma);
  }
  log_weights_.array() -= logsumexp_rows(log_weights_.transpose())[0];
}

Eigen::VectorXd ConfigModel::log_density(const Eigen::Ref<const RowMatrixXd>& q) const {
  if (q.cols() != dim()) {
    throw std::invalid_argument("ConfigModel.log_density: configurations have " + std::to_string(q.cols()) +
                                " joints, the model " + std::to_string(dim()));
  }
  const double norm = -0.5 * dim() * (kLog2Pi + 2.0 * std::log(sigma_));
  RowMatrixXd terms(q.rows(), kernels_.rows());
  for (Eigen::Index k = 0; k < kernels_.rows(); ++k) {
    terms.col(k) = (q.rowwise() - kernels_.row(k)).rowwise().squaredNorm() * (-0.5 / (sigma_ * sigma_));
    terms.col(k).array() += log_weights_[k] + norm;
  }
  return logsumexp_rows(terms);
}

RowMatrixXd ConfigModel::sample(int n, std::mt19937_64& rng) const {
  if (n < 0) throw std::invalid_argument("ConfigModel.sample: n must be >= 0");
  const Eigen::VectorXd w = log_weights_.array().exp();
  std::discrete_distribution<int> pick(w.data(), w.data() + w.size());
  std::normal_distribution<double> normal;
  RowMatrixXd out(n, dim());
  for (int i = 0; i < n; ++i) {
    const int k = pick(rng);
    for (int j = 0; j < dim(); ++j) {
      out(i, j) = std::clamp(kernels_(k, j) + sigma_ * normal(rng), limits_(j, 0), limits_(j, 1));
    }
  }
  return out;
}

Eigen::VectorXd ConfigModel::pregrasp_for(const Eigen::Ref<const Eigen::VectorXd>& q) const {
  if (q.size() != dim()) {
    throw std::invalid_argument("ConfigModel.pregrasp_for: " + std::to_string(q.size()) + " joints, the model " +
                                std::to_string(dim()));
  }
  Eigen::VectorXd out = q + (pregrasp_ - grasp_);
  for (int j = 0; j < dim(); ++j) out[j] = std::clamp(out[j], limits_(j, 0), limits_(j, 1));
  return out;
}

RowMatrixXd ConfigModel::pregrasps_for(const Eigen::Ref<const RowMatrixXd>& q) const {
  RowMatrixXd out(q.rows(), q.cols());
  for (Eigen::Index i = 0; i < q.rows(); ++i) out.row(i) = pregrasp_for(q.row(i).transpose()).transpose();
  return out;
}

}  // namespace graspmix
