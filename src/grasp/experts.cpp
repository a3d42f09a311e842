#include "graspmix/grasp/experts.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "graspmix/core/se3.hpp"

namespace graspmix {

namespace {
constexpr double kRejected = -std::numeric_limits<double>::infinity();
}

KinematicFeasibilityExpert::KinematicFeasibilityExpert(std::shared_ptr<const Hand> hand,
                                                       const std::optional<Eigen::Vector4d>& plane,
                                                       const KinematicFeasibilitySettings& settings,
                                                       Reachability reachable)
    : hand_(std::move(hand)), reachable_(std::move(reachable)), limit_tolerance_(settings.limit_tolerance) {
  if (!hand_) throw std::invalid_argument("KinematicFeasibilityExpert: no hand");
  if (plane) {
    CollisionSettings s;
    s.plane_margin = settings.plane_margin;
    s.contact_tolerance = settings.plane_tolerance;
    s.orient_plane = false;  // the caller's orientation: the object is on the positive side
    plane_check_.emplace(hand_, Vec3Array(0, 3), plane, s);
  }
}

KinematicFeasibilityExpert::KinematicFeasibilityExpert(std::shared_ptr<const Hand> hand,
                                                       const std::optional<Eigen::Vector4d>& plane, double plane_margin,
                                                       Reachability reachable, double limit_tolerance)
    : KinematicFeasibilityExpert(
          std::move(hand), plane,
          [&] {
            KinematicFeasibilitySettings s;
            s.plane_margin = plane_margin;
            s.limit_tolerance = limit_tolerance;
            return s;
          }(),
          std::move(reachable)) {}

CollisionFreeExpert::CollisionFreeExpert(std::shared_ptr<const CollisionExpert> collision,
                                         std::optional<ConfigModel> pregrasp_config, std::string name)
    : collision_(std::move(collision)), config_(std::move(pregrasp_config)), name_(std::move(name)) {
  if (!collision_) throw std::invalid_argument("CollisionFreeExpert: no collision expert");
  if (config_ && config_->dim() != collision_->hand().n_dofs()) {
    throw std::invalid_argument("CollisionFreeExpert: the configuration model has " + std::to_string(config_->dim()) +
                                " joints, the hand " + std::to_string(collision_->hand().n_dofs()));
  }
}

Eigen::VectorXd CollisionFreeExpert::log_value(const GraspBatch& b) const {
  const Eigen::Index n = b.wrists.rows();
  if (b.joints.rows() != n || b.joints.cols() != collision_->hand().n_dofs()) {
    throw std::invalid_argument(name_ + " expert: joints must be (" + std::to_string(n) + ", " +
                                std::to_string(collision_->hand().n_dofs()) + ")");
  }
  Eigen::VectorXd out = Eigen::VectorXd::Zero(n);
  if (config_) {
    const auto [grasp, pregrasp] = collision_->total_depth_pair(b.wrists, b.joints, config_->pregrasps_for(b.joints));
    for (Eigen::Index i = 0; i < n; ++i)
      if (!(grasp[i] <= 0.0 && pregrasp[i] <= 0.0)) out[i] = kRejected;
  } else {
    const CollisionBatchResult r = collision_->evaluate_batch(b.wrists, b.joints);
    for (Eigen::Index i = 0; i < n; ++i)
      if (!r.collision_free[i]) out[i] = kRejected;
  }
  return out;
}

Eigen::VectorXd KinematicFeasibilityExpert::log_value(const GraspBatch& b) const {
  const Eigen::Index n = b.wrists.rows();
  if (b.joints.rows() != n || b.joints.cols() != hand_->n_dofs()) {
    throw std::invalid_argument("kinematic expert: joints must be (" + std::to_string(n) + ", " +
                                std::to_string(hand_->n_dofs()) + ")");
  }
  Eigen::VectorXd out = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!hand_->within_limits(b.joints.row(i).transpose(), limit_tolerance_)) out[i] = kRejected;
  }
  if (plane_check_) {
    const CollisionBatchResult r = plane_check_->evaluate_batch(b.wrists, b.joints);
    for (Eigen::Index i = 0; i < n; ++i)
      if (!r.collision_free[i]) out[i] = kRejected;
  }
  if (reachable_) {
    const Eigen::Matrix<bool, Eigen::Dynamic, 1> ok = reachable_(b.wrists, b.joints);
    if (ok.size() != n) {
      throw std::invalid_argument("kinematic expert: the reachability test returned " + std::to_string(ok.size()) +
                                  " values for " + std::to_string(n) + " grasps");
    }
    for (Eigen::Index i = 0; i < n; ++i)
      if (!ok[i]) out[i] = kRejected;
  }
  return out;
}

AxisAlignmentExpert::AxisAlignmentExpert(const Eigen::Vector3d& world_axis, const Eigen::Vector3d& hand_axis,
                                         double concentration, std::string name)
    : concentration_(concentration), name_(std::move(name)) {
  if (!(world_axis.norm() > 1e-12) || !world_axis.allFinite()) {
    throw std::invalid_argument("approach axis must be a non-zero finite vector");
  }
  if (!(hand_axis.norm() > 1e-12) || !hand_axis.allFinite()) {
    throw std::invalid_argument("hand axis must be a non-zero finite vector");
  }
  if (!(concentration >= 0.0) || !std::isfinite(concentration)) {
    throw std::invalid_argument("axis concentration must be finite and >= 0");
  }
  world_axis_ = world_axis.normalized();
  hand_axis_ = hand_axis.normalized();
}

Eigen::VectorXd AxisAlignmentExpert::log_value(const GraspBatch& b) const {
  Eigen::VectorXd out(b.wrists.rows());
  for (Eigen::Index i = 0; i < b.wrists.rows(); ++i) {
    const Eigen::Quaterniond q(b.wrists(i, 6), b.wrists(i, 3), b.wrists(i, 4), b.wrists(i, 5));
    const double c = (q.normalized() * hand_axis_).dot(world_axis_);
    out[i] = concentration_ * (c - 1.0);
  }
  return out;
}

FunctionExpert::FunctionExpert(std::string name, Function fn) : name_(std::move(name)), fn_(std::move(fn)) {
  if (!fn_) throw std::invalid_argument("expert '" + name_ + "': no function given");
}

Eigen::VectorXd FunctionExpert::log_value(const GraspBatch& b) const {
  Eigen::VectorXd v = fn_(b.wrists, b.joints);
  if (v.size() != b.wrists.rows()) {
    throw std::invalid_argument("expert '" + name_ + "' returned " + std::to_string(v.size()) + " values for " +
                                std::to_string(b.wrists.rows()) + " grasps");
  }
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (std::isnan(v[i]) || v[i] == std::numeric_limits<double>::infinity()) {
      throw std::invalid_argument("expert '" + name_ + "' returned " + std::to_string(v[i]) + " for grasp " +
                                  std::to_string(i) + "; log values must be finite or -inf");
    }
  }
  return v;
}

}  // namespace graspmix
