#pragma once
// The non-parametric baseline of Kopicki et al. 2015: one weighted kernel per data point, each a
// product of an isotropic Gaussian on position, an antipodally symmetric von Mises-Fisher kernel on
// the unit quaternion (q and -q alike), and a diagonal Gaussian on the features.
#include "graspmix/density/pose_density.hpp"

namespace graspmix {

/// The smallest orientation bandwidth a PoseKDE accepts (rad). Its concentration kappa = 4 / bw^2 is then
/// 4e12: rounding of a quaternion's dot product (~1e-16) already moves kappa (1 - t) by ~4e-4, and narrower
/// kernels would score and sample rounding noise rather than rotations.
inline constexpr double kMinOrientationBandwidth = 1e-6;

struct KdeSettings {
  double position_bandwidth = 0.005;    ///< std of the position kernel (m)
  double orientation_bandwidth = 0.15;  ///< approximate std of the rotation angle of the kernel (rad),
                                        ///< at least kMinOrientationBandwidth
  /// std per feature (same units as the features); one value = all features. 0.005 suits PCL's
  /// curvatures k1, k2 at the paper's 1 cm radius (they range over about 0-0.1).
  Eigen::VectorXd feature_bandwidth = Eigen::VectorXd::Constant(1, 0.005);
};

class PoseKDE : public PoseDensity {
 public:
  explicit PoseKDE(KdeSettings settings = {});

  void fit(const Eigen::Ref<const PoseArray>& poses, const Eigen::Ref<const RowMatrixXd>& features,
           const Eigen::VectorXd& weights) override;
  bool fitted() const override { return positions_.rows() > 0; }
  int n_features() const override { return static_cast<int>(features_.cols()); }
  int n_kernels() const override { return static_cast<int>(positions_.rows()); }
  std::string kind() const override { return "kde"; }
  void accept(PoseDensityVisitor& visitor) const override { visitor(*this); }

  Eigen::VectorXd log_density(const Eigen::Ref<const PoseArray>& poses,
                              const Eigen::Ref<const RowMatrixXd>& features) const override;
  Eigen::VectorXd feature_log_density(const Eigen::Ref<const RowMatrixXd>& features) const override;
  PoseArray sample(const Eigen::Ref<const RowMatrixXd>& features, std::mt19937_64& rng) const override;
  std::unique_ptr<PoseDensity> clone() const override { return std::make_unique<PoseKDE>(*this); }

  const KdeSettings& settings() const { return settings_; }
  /// The von Mises-Fisher concentration kappa = 4 / orientation_bandwidth^2 (for small angles the kernel is
  /// then a Gaussian in the rotation angle with that std).
  double concentration() const { return kappa_; }
  const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>& positions() const { return positions_; }
  const QuatArray& orientations() const { return orientations_; }
  const RowMatrixXd& features() const { return features_; }
  const Eigen::VectorXd& weights() const { return weights_; }
  const Eigen::VectorXd& feature_bandwidth() const { return feature_bw_; }

 private:
  void require_fitted(const char* what) const;
  /// log w_k + log K_r(r | r_k) for one feature row, every kernel.
  Eigen::VectorXd log_feature_kernels(const Eigen::Ref<const Eigen::RowVectorXd>& r) const;

  KdeSettings settings_;
  double kappa_ = 0.0, log_norm_q_ = 0.0, log_norm_p_ = 0.0, log_norm_r_ = 0.0;
  Eigen::VectorXd feature_bw_;
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> positions_;
  QuatArray orientations_;
  RowMatrixXd features_;
  Eigen::VectorXd weights_, log_weights_;  ///< normalised to sum 1
};

/// log of the normaliser of the hemisphere-restricted antipodal vMF kernel on S^3,
/// log(kappa / (4 pi^2 I_1(kappa))), stable for large kappa. Exposed for tests.
double log_vmf_s3_normaliser(double kappa);

}  // namespace graspmix
