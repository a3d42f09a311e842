#include "graspmix/grasp/experts.hpp"

#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "graspmix/core/se3.hpp"

namespace graspmix {

namespace {
constexpr double kRejected = -std::numeric_limits<double>::infinity();
}

void require_joints_shape(Eigen::Index n_wrists, const RowMatrixXd& joints, int n_dofs, const std::string& who) {
  if (joints.rows() != n_wrists || joints.cols() != n_dofs) {
    throw std::invalid_argument(who + ": joints must be (" + std::to_string(n_wrists) + ", " + std::to_string(n_dofs) +
                                "), got (" + std::to_string(joints.rows()) + ", " + std::to_string(joints.cols()) +
                                ")");
  }
}

void require_config_of(const ConfigModel& config, const Hand& hand, const std::string& who) {
  if (config.dim() != hand.n_dofs()) {
    throw std::invalid_argument(who + ": the configuration model has " + std::to_string(config.dim()) +
                                " joints, the hand '" + hand.name() + "' has " + std::to_string(hand.n_dofs()));
  }
}

std::pair<PoseArray, RowMatrixXd> batch_rows(const PoseArray& wrists, const RowMatrixXd& joints,
                                             const std::vector<Eigen::Index>& rows) {
  const auto m = static_cast<Eigen::Index>(rows.size());
  PoseArray w(m, 7);
  RowMatrixXd q(m, joints.cols());
  for (Eigen::Index k = 0; k < m; ++k) {
    w.row(k) = wrists.row(rows[static_cast<size_t>(k)]);
    q.row(k) = joints.row(rows[static_cast<size_t>(k)]);
  }
  return {std::move(w), std::move(q)};
}

ExpertTerms evaluate_experts(const std::vector<std::shared_ptr<const Expert>>& experts, const PoseArray& wrists,
                             const RowMatrixXd& joints) {
  const Eigen::Index n = wrists.rows();
  ExpertTerms e;
  e.log_values =
      RowMatrixXd::Constant(n, static_cast<Eigen::Index>(experts.size()), std::numeric_limits<double>::quiet_NaN());
  e.total = Eigen::VectorXd::Zero(n);
  e.passed.resize(static_cast<size_t>(n));
  std::iota(e.passed.begin(), e.passed.end(), Eigen::Index{0});
  for (size_t k = 0; k < experts.size() && !e.passed.empty(); ++k) {
    const auto m = static_cast<Eigen::Index>(e.passed.size());
    Eigen::VectorXd v;
    if (m == n) {
      v = experts[k]->log_value(GraspBatch{wrists, joints});
    } else {
      const auto [w, q] = batch_rows(wrists, joints, e.passed);
      v = experts[k]->log_value(GraspBatch{w, q});
    }
    if (v.size() != m || v.array().isNaN().any() || (v.array() == std::numeric_limits<double>::infinity()).any()) {
      throw std::invalid_argument("expert '" + experts[k]->name() +
                                  "' returned NaN, +inf or the wrong number of values");
    }
    std::vector<Eigen::Index> still;
    for (Eigen::Index j = 0; j < m; ++j) {
      const Eigen::Index i = e.passed[static_cast<size_t>(j)];
      e.log_values(i, static_cast<Eigen::Index>(k)) = v[j];
      e.total[i] += v[j];
      if (e.total[i] > kRejected) still.push_back(i);
    }
    e.passed.swap(still);
  }
  return e;
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
  if (config_) require_config_of(*config_, collision_->hand(), "CollisionFreeExpert");
}

Eigen::VectorXd CollisionFreeExpert::log_value(const GraspBatch& b) const {
  const Eigen::Index n = b.wrists.rows();
  require_joints_shape(n, b.joints, collision_->hand().n_dofs(), name_ + " expert");
  Eigen::VectorXd out = Eigen::VectorXd::Zero(n);
  const Eigen::Matrix<bool, Eigen::Dynamic, 1> free = collision_->collision_free_batch(b.wrists, b.joints);
  std::vector<Eigen::Index> kept;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!free[i]) {
      out[i] = kRejected;
    } else {
      kept.push_back(i);
    }
  }
  if (!config_ || kept.empty()) return out;
  // The pre-grasps of the grasps that are free.
  const auto [w, q] = batch_rows(b.wrists, b.joints, kept);
  const Eigen::Matrix<bool, Eigen::Dynamic, 1> pre_free =
      collision_->collision_free_batch(w, config_->pregrasps_for(q));
  for (std::size_t k = 0; k < kept.size(); ++k)
    if (!pre_free[static_cast<Eigen::Index>(k)]) out[kept[k]] = kRejected;
  return out;
}

Eigen::VectorXd KinematicFeasibilityExpert::log_value(const GraspBatch& b) const {
  const Eigen::Index n = b.wrists.rows();
  require_joints_shape(n, b.joints, hand_->n_dofs(), "kinematic expert");
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

namespace {
Eigen::Vector3d hand_axis_of(const AxisAlignmentSettings& s, const Hand* hand) {
  if (s.hand_axis) return *s.hand_axis;
  // Without a hand: the wrist's +z, the axis this expert aligned before hands had one (and a hand's without
  // fingertips).
  return hand ? hand->approach_axis() : Eigen::Vector3d::UnitZ();
}
}  // namespace

AxisAlignmentExpert::AxisAlignmentExpert(const Eigen::Vector3d& world_axis, const AxisAlignmentSettings& settings,
                                         const Hand* hand)
    : AxisAlignmentExpert(world_axis, hand_axis_of(settings, hand), settings.concentration, settings.name) {}

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
    const Eigen::Quaterniond q = row_quaternion(b.wrists, i);
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
