#pragma once
// The density interface every downstream part (contact models, query densities, ranking) uses, so
// that the paper's mixtures (PoseMixture) and the KDE baseline of Kopicki et al. 2015 (PoseKDE) are
// interchangeable.
//
// A density is over x = (u, r): u = (p, q) a pose, r an n-vector of features (n may be 0).
// Log densities are with respect to Lebesgue measure on p (m^-3) times the area measure of the unit
// 3-sphere restricted to the hemisphere w >= 0 (one point per rotation, total area pi^2), and
// Lebesgue measure on r. Both implementations use that same measure, so their values compare.
#include <memory>
#include <random>
#include <string>

#include <Eigen/Core>

#include "graspmix/core/types.hpp"

namespace graspmix {

class PoseMixture;
class PoseKDE;

/// One action per kind of pose density (double dispatch through PoseDensity::accept): what differs
/// between the kinds is written as a visitor, never as a comparison of kind() strings, and a new kind
/// makes every visitor that does not handle it fail to compile.
class PoseDensityVisitor {
 public:
  virtual ~PoseDensityVisitor() = default;
  virtual void operator()(const PoseMixture& density) = 0;
  virtual void operator()(const PoseKDE& density) = 0;
};

class PoseDensity {
 public:
  virtual ~PoseDensity() = default;

  /// Fits to poses (N, 7) with features (N, n) (n = 0 allowed: a (N, 0) array) and positive
  /// weights (N; empty = all ones). Throws std::invalid_argument on bad input.
  virtual void fit(const Eigen::Ref<const PoseArray>& poses, const Eigen::Ref<const RowMatrixXd>& features,
                   const Eigen::VectorXd& weights) = 0;
  virtual bool fitted() const = 0;
  virtual int n_features() const = 0;
  /// Kernels (KDE) or components (mixture): what every evaluation costs.
  virtual int n_kernels() const = 0;
  /// "gmm" or "kde".
  virtual std::string kind() const = 0;
  /// Calls the visitor's operator() for this density's kind.
  virtual void accept(PoseDensityVisitor& visitor) const = 0;

  /// log p(u_i | r_i) for every row (eq:density_mixture_rigid_body); with no features, log p(u_i).
  virtual Eigen::VectorXd log_density(const Eigen::Ref<const PoseArray>& poses,
                                      const Eigen::Ref<const RowMatrixXd>& features) const = 0;
  /// log p(r_i) for every row (eq:density_mixture_features).
  virtual Eigen::VectorXd feature_log_density(const Eigen::Ref<const RowMatrixXd>& features) const = 0;
  /// One pose drawn from p(u | r_i) for every row of features (N, 7), quaternions with w >= 0.
  virtual PoseArray sample(const Eigen::Ref<const RowMatrixXd>& features, std::mt19937_64& rng) const = 0;

  virtual std::unique_ptr<PoseDensity> clone() const = 0;
};

/// Shared input checks of PoseDensity::fit: shapes, finiteness, weights. Returns the weights (ones if empty).
Eigen::VectorXd check_pose_data(const Eigen::Ref<const PoseArray>& poses, const Eigen::Ref<const RowMatrixXd>& features,
                                const Eigen::VectorXd& weights, const char* what);
/// Shared checks of evaluation input against a fitted density of n_features features.
void check_pose_query(const Eigen::Ref<const PoseArray>& poses, const Eigen::Ref<const RowMatrixXd>& features,
                      int n_features, const char* what);
void check_feature_query(const Eigen::Ref<const RowMatrixXd>& features, int n_features, const char* what);

}  // namespace graspmix
