#include "graspmix/grasp/approach.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "graspmix/core/se3.hpp"

namespace graspmix {

ClearApproachExpert::ClearApproachExpert(std::shared_ptr<const CollisionExpert> collision, ConfigModel config,
                                         ClearApproachSettings settings)
    : collision_(std::move(collision)), config_(std::move(config)), settings_(std::move(settings)) {
  if (!collision_) throw std::invalid_argument("ClearApproachExpert: no collision expert");
  require_config_of(config_, collision_->hand(), "ClearApproachExpert");
  const ClearApproachSettings& s = settings_;
  if (!std::isfinite(s.clearance) || s.clearance < 0.0) {
    throw std::invalid_argument("ClearApproachExpert: clearance must be a finite distance >= 0 (m), got " +
                                std::to_string(s.clearance));
  }
  if (!std::isfinite(s.stand_off) || s.stand_off < 0.0) {
    throw std::invalid_argument("ClearApproachExpert: stand_off must be a finite distance >= 0 (m), got " +
                                std::to_string(s.stand_off));
  }
  if (!std::isfinite(s.step) || s.step <= 0.0) {
    throw std::invalid_argument("ClearApproachExpert: step must be a finite distance > 0 (m), got " +
                                std::to_string(s.step));
  }
  if (!s.hand_axis) settings_.hand_axis = collision_->hand().approach_axis();
  if (!settings_.hand_axis->allFinite() || !(settings_.hand_axis->norm() > 1e-12)) {
    throw std::invalid_argument("ClearApproachExpert: hand_axis must be a finite non-zero vector");
  }
  settings_.hand_axis->normalize();
  const auto n_steps = static_cast<int>(std::ceil(s.stand_off / s.step - 1e-9));
  for (int k = 0; k < n_steps; ++k) offsets_.push_back(k * s.step);
  offsets_.push_back(s.stand_off);
}

Eigen::VectorXd ClearApproachExpert::log_value(const GraspBatch& b) const {
  const Eigen::Index n = b.wrists.rows();
  const int dofs = collision_->hand().n_dofs();
  require_joints_shape(n, b.joints, dofs, settings_.name + " expert");
  const RowMatrixXd open = config_.pregrasps_for(b.joints);
  // The approach direction of every grasp in the world frame.
  Vec3Array axis(n, 3);
  for (Eigen::Index i = 0; i < n; ++i)
    axis.row(i) = (pose_from_vector(b.wrists.row(i).transpose()).linear() * *settings_.hand_axis).transpose();
  Eigen::VectorXd out = Eigen::VectorXd::Zero(n);
  std::vector<Eigen::Index> alive(static_cast<size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) alive[static_cast<size_t>(i)] = i;
  // Pose by pose from the pre-grasp outwards: a grasp rejected near the object is not checked further out.
  for (const double s : offsets_) {
    if (alive.empty()) break;
    const auto m = static_cast<Eigen::Index>(alive.size());
    PoseArray w(m, 7);
    RowMatrixXd q(m, dofs);
    for (Eigen::Index k = 0; k < m; ++k) {
      const Eigen::Index i = alive[static_cast<size_t>(k)];
      w.row(k) = b.wrists.row(i);
      w.row(k).head<3>() -= s * axis.row(i);
      q.row(k) = open.row(i);
    }
    const Eigen::Matrix<bool, Eigen::Dynamic, 1> free = collision_->collision_free_batch(w, q);
    std::vector<Eigen::Index> still;
    for (Eigen::Index k = 0; k < m; ++k) {
      const Eigen::Index i = alive[static_cast<size_t>(k)];
      if (free[k]) {
        still.push_back(i);
      } else {
        out[i] = -std::numeric_limits<double>::infinity();
      }
    }
    alive.swap(still);
  }
  return out;
}

}  // namespace graspmix
