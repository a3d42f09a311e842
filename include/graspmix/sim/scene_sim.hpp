#pragma once
// Several objects in one Bullet world (sim.hpp's execution, generalised): a grasp executed in a scene of
// objects on the plane z = 0, and a scene settled without a hand until its objects rest.
//
// execute_scene runs execute()'s protocol (sim.hpp) with every object in the world: the start is in
// collision when the hand penetrates any object or the support; "no contact" when, after closing, the
// hand touches no object; after the lift and the hold an object is *lifted* when it rose by at least
// success_fraction * lift_height and touches the hand. Exactly one lifted object is a success, more than
// one "two objects lifted", none "not held". With one object it is execute() step for step (the world is
// built and stepped in the same order), so its results are the same bit for bit.
//
// settle_scene builds the same world (support and objects, no hand) and steps it until every object is
// at rest or the time is up, optionally inside walls (a pile is dropped into a box that is then removed):
// a scene settled by it is at rest when execute_scene starts.
#include <vector>

#include <Eigen/Geometry>

#include "graspmix/sim/sim.hpp"

namespace graspmix {

/// The outcome of one grasp in a scene.
struct SceneSimResult {
  /// outcome, reason, success (exactly one object lifted), contact_count (hand contacts with every
  /// object), start_penetration, steps, times; lift_height and T_world_object_final are those of the
  /// object that rose most (the lifted one when there is one).
  SimResult result;
  std::vector<int> lifted;                         ///< indices of the objects that rose and are held
  std::vector<Eigen::Isometry3d> T_world_objects;  ///< every object's link frame at the end
  std::vector<double> rise;                        ///< m: how far each object's centre of mass rose
  std::vector<double> moved;                       ///< m: how far each object's link origin moved
};

/// Executes one grasp among `objects` (link frames at `T_world_objects`, same length, at least one);
/// the other arguments as execute(). Throws std::invalid_argument for mismatched sizes, non-finite poses,
/// wrong-sized or non-finite joints, settings out of range.
SceneSimResult execute_scene(const Hand& hand, const std::vector<const SimObject*>& objects,
                             const std::vector<Eigen::Isometry3d>& T_world_objects,
                             const Eigen::Isometry3d& T_world_wrist, const Eigen::Ref<const Eigen::VectorXd>& pregrasp,
                             const Eigen::Ref<const Eigen::VectorXd>& grasp, const SimSettings& settings = {});

/// Walls of a settling: four static boxes standing on the plane around an axis-aligned rectangle.
struct SettleWalls {
  Eigen::Vector2d min = Eigen::Vector2d::Zero();  ///< m: x, y of the inner rectangle's corner
  Eigen::Vector2d max = Eigen::Vector2d::Zero();  ///< m: x, y of the opposite corner (> min)
  double height = 0.0;                            ///< m (> 0)
};

/// Bounds of settle_scene: at most kMaxSettleTime simulated seconds (and kMaxPhaseSteps steps).
inline constexpr double kMaxSettleTime = 60.0;  ///< s
/// An object is at rest when its speed is below kRestSpeed and its angular speed below kRestSpin
/// during kRestTime.
inline constexpr double kRestSpeed = 1e-3;  ///< m/s
inline constexpr double kRestSpin = 1e-2;   ///< rad/s
inline constexpr double kRestTime = 0.1;    ///< s

struct SettleResult {
  std::vector<Eigen::Isometry3d> T_world_objects;  ///< every object's link frame at the end
  bool at_rest = false;                            ///< every object at rest before the time was up
  int steps = 0;
  double simulated_time = 0.0;  ///< s
};

/// Simulates `objects` from `T_world_objects` with gravity and no hand (settings: time step, solver,
/// frictions, masses) for at most `seconds`, stopping once every object is at rest; `walls` (if given)
/// stand around them the whole time. Throws std::invalid_argument for mismatched sizes, non-finite
/// poses, seconds outside [0, kMaxSettleTime], bad walls or settings.
SettleResult settle_scene(const std::vector<const SimObject*>& objects,
                          const std::vector<Eigen::Isometry3d>& T_world_objects, const SimSettings& settings = {},
                          double seconds = 2.0, const SettleWalls* walls = nullptr);

}  // namespace graspmix
