#pragma once
// Grasp execution in Bullet physics (the paper's "Experiments": the best grasp is executed and counts
// as a success if the object is held after a lift).
//
// The world: a support plane at z = 0 (the box of pybullet_data's plane.urdf), one object from a
// one-link URDF (its collision meshes as convex hulls, as pybullet treats a dynamic body's meshes), and
// the hand from its URDF as a Featherstone multibody. The hand hangs from a fixed base at the wrist
// pose by one extra prismatic "lift" joint along world +z, so the wrist moves only by that joint.
//
// One execution (fresh world every time, so the object always starts from the same pose):
//   1. the hand is placed at T_world_wrist with the pre-grasp joints; if it penetrates the object or
//      the support deeper than `start_penetration`, the result is "start in collision";
//   2. close: every movable joint (mimic joints too, to their mimicked targets) is driven by a velocity
//      motor towards a target past the grasp joints (grasp + close_overshoot * (grasp - pregrasp)),
//      speed-limited (close_speed, or faster for long travels) and force-limited by grip_force; no hand-object contact
//      at the end of this phase is "no contact";
//   3. lift: the lift joint raises the wrist by lift_height; 4. hold for hold_time, fingers still pressing;
//   5. success: the object rose by at least success_fraction * lift_height and still touches the hand;
//      otherwise "not held".
// Everything is deterministic: the same inputs give the same result bit for bit (no time-based input;
// wall time is only measured).
#include <memory>
#include <string>

#include <Eigen/Geometry>

#include "graspmix/robot/hand.hpp"

namespace graspmix {

/// Bounds of SimSettings (execute refuses settings beyond them, naming the setting): each phase (close,
/// lift, hold) simulates at most kMaxPhaseTime and kMaxPhaseSteps steps, so a run ends in bounded time.
inline constexpr double kMaxPhaseTime = 60.0;       ///< s simulated per phase
inline constexpr int kMaxPhaseSteps = 100000;       ///< physics steps per phase
inline constexpr double kMaxTimeStep = 0.1;         ///< s: coarser steps are not a simulation of a grasp
inline constexpr int kMaxSolverIterations = 10000;  ///< per step
inline constexpr double kMaxForce = 1e6;            ///< N (N m): grip_force and lift_force
inline constexpr double kMaxLiftHeight = 100.0;     ///< m

/// Every time, speed and force is finite; times are >= 0, speeds, forces and gains > 0,
/// success_fraction in [0, 1]; see the bounds above.
struct SimSettings {
  Eigen::Vector3d gravity{0.0, 0.0, -9.81};  ///< m/s^2
  double time_step = 1.0 / 240.0;            ///< s (pybullet's default)
  int solver_iterations = 50;                ///< constraint solver iterations per step (pybullet's default)
  double hand_friction = 1.0;                ///< lateral friction coefficient of every hand link
  double object_friction =
      -1.0;  ///< < 0: the URDF's <contact><lateral_friction>, or 0.5 (pybullet's default) if absent
  double support_friction = 1.0;  ///< the plane (pybullet_data's plane.urdf uses 1)
  double object_mass = -1.0;      ///< kg; < 0: the URDF's <inertial><mass>
  double grip_force = 40.0;       ///< N (N m for revolute joints): force limit of every finger joint motor
  /// m/s: speed limit of the fingertips while closing (see closing_speeds: a revolute finger turns at
  /// close_speed / its fingertips' distance from the axis); a joint whose travel from pregrasp to grasp
  /// needs more to get there within close_time / 2 moves at that faster speed.
  double close_speed = 0.2;
  double close_overshoot = 0.5;      ///< the motors aim this fraction of (grasp - pregrasp) past the grasp joints
  double close_time = 0.5;           ///< s spent closing before the lift
  double position_gain = 20.0;       ///< 1/s: joint velocity command = gain * position error (then clamped)
  double lift_height = 0.20;         ///< m
  double lift_speed = 0.5;           ///< m/s
  double lift_force = 1000.0;        ///< N: force limit of the lift joint
  double hold_time = 0.5;            ///< s held at the top
  double start_penetration = 0.002;  ///< m: a start penetrating deeper than this is "start in collision"
  double contact_distance = 0.001;   ///< m: contact points closer than this count as touching
  double success_fraction = 0.5;     ///< the object must rise by this fraction of lift_height
};

/// An object to grasp: a one-link URDF (as in pybullet_data), its collision geometry read by
/// Hand::from_urdf (meshes scaled by the URDF, convex hulls), mass and <contact> lateral friction.
class SimObject {
 public:
  /// Throws std::invalid_argument naming the file if it is missing, not a URDF, has more than one
  /// link or no collision geometry.
  static SimObject from_urdf(const std::string& path, const HandLoadSettings& settings = {});

  const std::string& source() const { return model_->source(); }
  const Hand& model() const { return *model_; }
  double mass() const { return mass_; }
  /// The URDF's <contact><lateral_friction>, or -1 if it has none.
  double lateral_friction() const { return friction_; }
  /// The URDF's <contact><inertia_scaling> (1 if absent): pybullet multiplies the inertia by it.
  double inertia_scaling() const { return inertia_scaling_; }
  /// The link frame pose that rests the object on the plane z = 0 (lowest collision vertex at z = 0)
  /// at (x, y) with orientation q.
  Eigen::Isometry3d rest_pose(double x, double y, const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity()) const;

 private:
  std::shared_ptr<const Hand> model_;
  double mass_ = 0.0;
  double friction_ = -1.0;
  double inertia_scaling_ = 1.0;
};

/// TwoObjectsLifted happens only in a scene (scene_sim.hpp): more than one object rose in the hand.
enum class SimOutcome { Success, StartInCollision, NoContact, NotHeld, TwoObjectsLifted };

/// "success", "start in collision", "no contact", "not held", "two objects lifted".
const char* to_string(SimOutcome outcome);

struct SimResult {
  bool success = false;
  SimOutcome outcome = SimOutcome::NotHeld;
  std::string reason;              ///< to_string(outcome)
  double lift_height = 0.0;        ///< m: how far the object's centre of mass rose by the end
  int contact_count = 0;           ///< hand-object contact points at the end (after closing if it stopped there)
  double start_penetration = 0.0;  ///< m: deepest hand penetration (object or support) at the start (>= 0)
  Eigen::Isometry3d T_world_object_final = Eigen::Isometry3d::Identity();  ///< object link frame at the end
  int steps = 0;                                                           ///< physics steps taken
  double simulated_time = 0.0;                                             ///< s
  double wall_time = 0.0;  ///< s (measured only; never affects the outcome)
};

/// The speed limit of every URDF joint (joints() order; m/s or rad/s, 0 for fixed joints) while the hand
/// closes from `pregrasp` to `grasp`: each independent joint moves its fastest fingertip point (the centre of
/// a fingertip link's collision box, Hand::fingertips) at settings.close_speed m/s at the pre-grasp, or
/// faster if its travel needs more to end within close_time / 2; a mimic joint moves at |multiplier| times
/// its master's speed, so a linkage keeps its proportions. A joint that moves no fingertip gets close_speed
/// in its own units. (Without this a revolute finger turned at close_speed rad/s: the PR2 gripper's
/// fingertips, 0.1 m from their axes, closed ten times slower than a prismatic finger.)
Eigen::VectorXd closing_speeds(const Hand& hand, const Eigen::Ref<const Eigen::VectorXd>& pregrasp,
                               const Eigen::Ref<const Eigen::VectorXd>& grasp, const SimSettings& settings = {});

/// Executes one grasp: hand at T_world_wrist, pre-grasp configuration `pregrasp`, grasp configuration
/// `grasp` (both in hand.joint_names() order), object's link frame at T_world_object. Throws
/// std::invalid_argument for wrong-sized or non-finite joints or settings out of range.
SimResult execute(const Hand& hand, const SimObject& object, const Eigen::Isometry3d& T_world_object,
                  const Eigen::Isometry3d& T_world_wrist, const Eigen::Ref<const Eigen::VectorXd>& pregrasp,
                  const Eigen::Ref<const Eigen::VectorXd>& grasp, const SimSettings& settings = {});

}  // namespace graspmix
