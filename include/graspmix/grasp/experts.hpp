#pragma once
// Task-constraint experts E_k of eq:opt_criterion_extended. Each maps a batch of grasps to log E_k:
// 0 where the constraint holds, -inf where a hard constraint rejects the grasp (rejection sampling),
// and in between for soft constraints. Working in log space keeps a product of experts free of
// underflow and NaN.
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "graspmix/core/types.hpp"
#include "graspmix/grasp/collision.hpp"
#include "graspmix/grasp/config_model.hpp"
#include "graspmix/robot/hand.hpp"

namespace graspmix {

/// Grasps to score: wrist poses (N, 7) and configurations (N, D) in Hand::joint_names() order.
struct GraspBatch {
  const PoseArray& wrists;
  const RowMatrixXd& joints;
};

/// Throws std::invalid_argument "<who>: joints must be (N, n_dofs), got (r, c)" unless joints has a row per wrist
/// and a column per degree of freedom.
void require_joints_shape(Eigen::Index n_wrists, const RowMatrixXd& joints, int n_dofs, const std::string& who);
/// Throws std::invalid_argument "<who>: the configuration model has D joints, the hand H" unless they agree.
void require_config_of(const ConfigModel& config, const Hand& hand, const std::string& who);
/// The rows `rows` of wrists (N, 7) and joints (N, D).
std::pair<PoseArray, RowMatrixXd> batch_rows(const PoseArray& wrists, const RowMatrixXd& joints,
                                             const std::vector<Eigen::Index>& rows);

class Expert {
 public:
  virtual ~Expert() = default;
  /// The key of this expert's term in a grasp's "experts" table.
  virtual std::string name() const = 0;
  /// log E_k for every grasp of the batch (N).
  virtual Eigen::VectorXd log_value(const GraspBatch& batch) const = 0;
  /// A bound log E_k never exceeds (+inf: none known). Annealing skips the last expert of a product on a proposal
  /// that this bound already shows will be refused (GraspSynthesizer::anneal): the result is the same, sooner.
  virtual double max_log_value() const { return std::numeric_limits<double>::infinity(); }
  /// Whether log_value may score a batch in parts, from several threads at once: each grasp's value depends on
  /// that grasp alone, and scoring changes no state. Annealing runs its chains in parallel only when every expert
  /// allows it (GraspSynthesizer::anneal). Off unless an expert says so (the library's own do); a caller's
  /// function (FunctionExpert, a reachability test) is called with the whole batch on the calling thread.
  virtual bool scores_in_parts() const { return false; }
};

struct KinematicFeasibilitySettings {
  double plane_margin = 0.0;  ///< m: links must stay this far above the support plane
  /// m: a link this little below the (raised) plane still counts as clear (rounding, not penetration)
  double plane_tolerance = 1e-9;
  double limit_tolerance = 1e-9;  ///< joint units (m or rad): slack allowed past the joint limits
};

/// The hard kinematic-feasibility expert: joint limits, no link touching the support plane, and an
/// optional user test of reachability (e.g. an arm's inverse kinematics) called once per batch with
/// the wrist poses and configurations and returning true for reachable grasps.
class KinematicFeasibilityExpert : public Expert {
 public:
  using Reachability = std::function<Eigen::Matrix<bool, Eigen::Dynamic, 1>(const PoseArray&, const RowMatrixXd&)>;
  /// plane: [a, b, c, d] (oriented so the object is on its positive side); plane_margin (m): links
  /// must stay this far above it; limit_tolerance: joint slack allowed past the limits.
  KinematicFeasibilityExpert(std::shared_ptr<const Hand> hand, const std::optional<Eigen::Vector4d>& plane,
                             const KinematicFeasibilitySettings& settings, Reachability reachable = nullptr);
  KinematicFeasibilityExpert(std::shared_ptr<const Hand> hand,
                             const std::optional<Eigen::Vector4d>& plane = std::nullopt,
                             double plane_margin = KinematicFeasibilitySettings{}.plane_margin,
                             Reachability reachable = nullptr,
                             double limit_tolerance = KinematicFeasibilitySettings{}.limit_tolerance);
  std::string name() const override { return "kinematic"; }
  Eigen::VectorXd log_value(const GraspBatch& batch) const override;
  bool scores_in_parts() const override { return !reachable_; }

 private:
  std::shared_ptr<const Hand> hand_;
  std::optional<CollisionExpert> plane_check_;
  Reachability reachable_;
  double limit_tolerance_;
};

struct AxisAlignmentSettings {
  /// The hand's axis in the wrist frame; unset: the hand's approach_axis() (the WSG 50's palm z), the expert given
  /// the hand (else the wrist's +z).
  std::optional<Eigen::Vector3d> hand_axis;
  /// nats: log E = concentration (cos theta - 1), so a 90-degree deviation costs this much. 20, the value
  /// grasp synthesis has always run with from Python (it was 5 here): comparable to the contact terms, so
  /// the preference decides between otherwise similar grasps.
  double concentration = 20.0;
  std::string name = "approach_axis";  ///< the key of its term in a grasp's experts table
};

/// The soft principal-axis alignment expert: log E = concentration * (cos theta - 1), theta the angle
/// between the hand's axis (in the wrist frame; the WSG 50's approach axis is its palm z) and the
/// desired world axis. E = 1 when aligned, exp(-2 concentration) when opposite.
class AxisAlignmentExpert : public Expert {
 public:
  /// hand: whose approach_axis() is the hand's axis where settings.hand_axis is unset (without a hand: the wrist's
  /// +z, the axis before hands had one).
  AxisAlignmentExpert(const Eigen::Vector3d& world_axis, const AxisAlignmentSettings& settings,
                      const Hand* hand = nullptr);
  AxisAlignmentExpert(const Eigen::Vector3d& world_axis, const Eigen::Vector3d& hand_axis,
                      double concentration = AxisAlignmentSettings{}.concentration,
                      std::string name = AxisAlignmentSettings{}.name);
  std::string name() const override { return name_; }
  Eigen::VectorXd log_value(const GraspBatch& batch) const override;
  bool scores_in_parts() const override { return true; }

 private:
  Eigen::Vector3d world_axis_, hand_axis_;
  double concentration_;
  std::string name_;
};

/// The hard expert that keeps the hand out of a collision expert's cloud and plane (e.g. a scene's other
/// objects): log E = 0 where the hand touches none of them at the grasp and, given a configuration model, at
/// the grasp's pre-grasp (ConfigModel::pregrasp_for; checked for the grasps free at the grasp), -inf elsewhere.
/// Collision-free is CollisionExpert::collision_free_batch's (CollisionBatchResult::collision_free: no hard term;
/// the unseen charge never refuses).
class CollisionFreeExpert : public Expert {
 public:
  CollisionFreeExpert(std::shared_ptr<const CollisionExpert> collision, std::optional<ConfigModel> pregrasp_config,
                      std::string name = "collision_free");
  std::string name() const override { return name_; }
  Eigen::VectorXd log_value(const GraspBatch& batch) const override;
  bool scores_in_parts() const override { return true; }

 private:
  std::shared_ptr<const CollisionExpert> collision_;
  std::optional<ConfigModel> config_;
  std::string name_;
};

/// The constraint experts' terms of N grasps (GraspSynthesizer::evaluate's first step).
struct ExpertTerms {
  RowMatrixXd log_values;            ///< (N, K) log E_k; NaN where not evaluated (rejected by an earlier expert)
  Eigen::VectorXd total;             ///< (N) sum of the evaluated terms; -inf where an expert rejected the grasp
  std::vector<Eigen::Index> passed;  ///< the rows no expert rejected, in order
};

/// The experts in order, each on the grasps none before it rejected: a grasp a hard expert rejects costs nothing
/// more, and an expensive soft expert placed last sees only the survivors. Throws std::invalid_argument for an
/// expert returning NaN, +inf or the wrong number of values.
ExpertTerms evaluate_experts(const std::vector<std::shared_ptr<const Expert>>& experts, const PoseArray& wrists,
                             const RowMatrixXd& joints);

/// A user-defined expert: a function of the whole batch returning log E_k (N). graspmix.expert() in
/// Python turns a callable returning probabilities in [0, 1] or booleans into one.
class FunctionExpert : public Expert {
 public:
  using Function = std::function<Eigen::VectorXd(const PoseArray&, const RowMatrixXd&)>;
  FunctionExpert(std::string name, Function fn);
  std::string name() const override { return name_; }
  Eigen::VectorXd log_value(const GraspBatch& batch) const override;

 private:
  std::string name_;
  Function fn_;
};

}  // namespace graspmix
