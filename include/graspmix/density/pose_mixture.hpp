#pragma once
// The paper's parametric density over x = (p, q, r) (section "Representations"): a Gaussian mixture
// fitted in (p, log(q), r) coordinates, with p(u | r) by closed-form conditioning and p(r) by
// marginalisation.
//
// Orientations are mapped through the log map relative to a reference rotation q_ref (the data's
// weighted mean, computed at fit time): omega = log(q_ref^-1 q), canonicalised to w >= 0. This puts the
// log map's cut (rotations of pi away) as far from the data as it can be, rather than pi away from the
// identity, where contact data often lies. The density carries the Jacobian of the exp map so that it is
// a density on rotations, not on omega.
#include <Eigen/Geometry>

#include "graspmix/density/gmm.hpp"
#include "graspmix/density/pose_density.hpp"

namespace graspmix {

class PoseMixture : public PoseDensity {
 public:
  /// GmmSettings{} with the paper's K = 2 components per contact model (what PoseMixture() fits with).
  static GmmSettings default_settings() {
    GmmSettings s;
    s.n_components = 2;
    return s;
  }
  explicit PoseMixture(GmmSettings settings = default_settings());
  /// A fitted mixture from saved parameters: the reference rotation and the joint mixture over
  /// (p, omega, r) whose dimension is 6 + n_features.
  static PoseMixture from_parameters(const Eigen::Quaterniond& reference, const GaussianMixture& joint);

  void fit(const Eigen::Ref<const PoseArray>& poses, const Eigen::Ref<const RowMatrixXd>& features,
           const Eigen::VectorXd& weights) override;
  bool fitted() const override { return joint_.fitted(); }
  int n_features() const override { return n_features_; }
  int n_kernels() const override { return joint_.n_components(); }
  std::string kind() const override { return "gmm"; }
  void accept(PoseDensityVisitor& visitor) const override { visitor(*this); }

  Eigen::VectorXd log_density(const Eigen::Ref<const PoseArray>& poses,
                              const Eigen::Ref<const RowMatrixXd>& features) const override;
  Eigen::VectorXd feature_log_density(const Eigen::Ref<const RowMatrixXd>& features) const override;
  PoseArray sample(const Eigen::Ref<const RowMatrixXd>& features, std::mt19937_64& rng) const override;
  std::unique_ptr<PoseDensity> clone() const override { return std::make_unique<PoseMixture>(*this); }

  /// (p, omega) coordinates of poses in this mixture's chart (N, 6), and log |d q / d omega|.
  RowMatrixXd to_coordinates(const Eigen::Ref<const PoseArray>& poses, Eigen::VectorXd* log_jacobian = nullptr) const;
  PoseArray from_coordinates(const Eigen::Ref<const RowMatrixXd>& coords) const;

  const GaussianMixture& joint() const { return joint_; }
  const Eigen::Quaterniond& reference() const { return reference_; }
  const GmmSettings& settings() const { return settings_; }

 private:
  void require_fitted(const char* what) const;

  GmmSettings settings_;
  GaussianMixture joint_;
  ConditionalGaussianMixture conditional_;
  Eigen::Quaterniond reference_ = Eigen::Quaterniond::Identity();
  int n_features_ = 0;
};

/// The weighted mean rotation of unit quaternions (N, 4) [x, y, z, w] (Markley et al. 2007: the principal
/// eigenvector of sum w_i q_i q_i^T), which treats q and -q alike. Canonicalised to w >= 0.
Eigen::Quaterniond mean_quaternion(const Eigen::Ref<const QuatArray>& q, const Eigen::VectorXd& weights);

}  // namespace graspmix
