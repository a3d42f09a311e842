#pragma once
// The hand configuration model C(h_c) of eq:manipulator_model (after Kopicki et al. 2015): a KDE over
// the line through the demonstrated pre-grasp h_e and grasp h_g configurations,
//   h(gamma) = (1 - gamma) h_g + gamma h_e,  gamma in [-beta, beta],
//   C(h_c) = sum_gamma w(gamma) N(h_c | h(gamma), sigma^2 I),  w(gamma) ∝ exp(-alpha |h(gamma) - h_g| / |h_e - h_g|).
// The distance in w is measured in units of the demonstrated closing |h_e - h_g| so alpha is unitless
// whatever the joints' units; sigma likewise is a fraction of it (with a floor).
#include <random>

#include <Eigen/Core>

#include "graspmix/core/types.hpp"

namespace graspmix {

struct ConfigModelSettings {
  double beta = 1.0;            ///< gamma range: configurations up to beta * (h_e - h_g) either side of h_g
  int n_kernels = 21;           ///< kernels along the line (odd keeps one on h_g)
  double alpha = 2.0;           ///< decay of the kernel weights away from h_g (unitless, see above)
  double bandwidth = 0.1;       ///< kernel std as a fraction of |h_e - h_g|
  double min_bandwidth = 1e-3;  ///< floor of the kernel std (joint units: m or rad)
};

class ConfigModel {
 public:
  ConfigModel() = default;
  /// pregrasp h_e and grasp h_g (D each); limits (D, 2) bound sampling (rows of -inf, inf allowed).
  ConfigModel(const Eigen::VectorXd& pregrasp, const Eigen::VectorXd& grasp, const RowMatrixXd& limits,
              ConfigModelSettings settings = {});

  int dim() const { return static_cast<int>(grasp_.size()); }
  /// log C(h_c) for every row of q (N, D).
  Eigen::VectorXd log_density(const Eigen::Ref<const RowMatrixXd>& q) const;
  /// n configurations drawn from C and clamped to the joint limits.
  RowMatrixXd sample(int n, std::mt19937_64& rng) const;
  /// The pre-grasp that goes with grasp q: q opened by the demonstrated h_e - h_g, clamped to limits.
  Eigen::VectorXd pregrasp_for(const Eigen::Ref<const Eigen::VectorXd>& q) const;
  /// pregrasp_for of every row of q (N, D).
  RowMatrixXd pregrasps_for(const Eigen::Ref<const RowMatrixXd>& q) const;

  const Eigen::VectorXd& pregrasp() const { return pregrasp_; }
  const Eigen::VectorXd& grasp() const { return grasp_; }
  const RowMatrixXd& limits() const { return limits_; }
  const RowMatrixXd& kernels() const { return kernels_; }
  const Eigen::VectorXd& log_weights() const { return log_weights_; }
  double sigma() const { return sigma_; }
  const ConfigModelSettings& settings() const { return settings_; }

 private:
  ConfigModelSettings settings_;
  Eigen::VectorXd pregrasp_, grasp_, log_weights_;
  RowMatrixXd limits_, kernels_;
  double sigma_ = 0.0;
};

}  // namespace graspmix
