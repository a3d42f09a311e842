#pragma once
// The clear-approach expert: the hand reaches each grasp's pre-grasp along its approach axis from a stand-off,
// open, without touching anything. A grasp whose open hand (the pre-grasp configuration) meets the scene or the
// support plane anywhere on that straight path is rejected (hard: log E = -inf), a grasp with a clear path
// scores 0.
//
// "Touching" is the collision expert's: CollisionBatchResult::collision_free of the open hand at each pose, so
// the scene is whatever that expert knows (the cloud's points; with the occupancy model, also the space no
// camera saw free, which keeps a hand from approaching through an object's unseen back). The path is checked
// at the pre-grasp itself and at poses every `step` back along the approach axis up to the stand-off
// (the last at the stand-off exactly). A point of the scene is missed only if it crosses a link between two
// checked poses, i.e. if the link is shorter than `step` along the axis: the WSG 50's shortest link along
// its approach is its 24 mm jaw, above the 2 cm default. The support plane is exact whatever the step: a
// link's depth below a plane is linear along a straight path, so it is greatest at one of its ends.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "graspmix/grasp/collision.hpp"
#include "graspmix/grasp/config_model.hpp"
#include "graspmix/grasp/experts.hpp"

namespace graspmix {

struct ClearApproachSettings {
  /// m: the hand starts this far back along its approach axis from the pre-grasp (>= 0; 0 checks the pre-grasp
  /// alone). 10 cm: the distance an arm's planner typically leaves between its pre-grasp approach pose and the
  /// object.
  double stand_off = 0.10;
  /// m: the path is checked at poses this far apart (> 0); keep it below every link's length along the axis.
  double step = 0.02;
  /// m: whoever builds the `collision` expert the path is checked against (scene synthesis does) makes the points
  /// balls of this radius, which the open hand may enter by that expert's contact tolerance: with the default 1 mm
  /// it keeps 1 mm from every point (kept so: without the tolerance, the whole 2 mm, it lost grasps on the
  /// development scenes, docs/one-view.md). A cleaned cloud's points are the centres of 3 mm voxels: a hand clear of
  /// them by the collision's 1 mm contact tolerance can still sit 1-2 mm inside the surface they sample, which
  /// Bullet calls a start in collision (over 2 mm).
  double clearance = 0.002;
  /// The approach axis in the wrist frame, normalised; unset: the hand's approach_axis() (robot/hand.hpp: read from
  /// its URDF or inferred from its fingertips; the WSG 50's palm z).
  std::optional<Eigen::Vector3d> hand_axis;
  std::string name = "clear_approach";  ///< the key of its term in a grasp's experts table
};

class ClearApproachExpert : public Expert {
 public:
  /// collision: what the path must keep clear of (the whole scene and its plane); config: the configuration
  /// model whose pregrasps_for(q) gives each grasp's open hand. Throws std::invalid_argument for a null expert,
  /// a configuration model of another hand's size, stand_off < 0, step <= 0, a zero axis, or non-finite values.
  ClearApproachExpert(std::shared_ptr<const CollisionExpert> collision, ConfigModel config,
                      ClearApproachSettings settings = {});
  std::string name() const override { return settings_.name; }
  Eigen::VectorXd log_value(const GraspBatch& batch) const override;
  bool scores_in_parts() const override { return true; }

  /// The distances (m) back along the axis at which the open hand is checked: 0, step, 2 step, ..., stand_off.
  const std::vector<double>& offsets() const { return offsets_; }
  const ClearApproachSettings& settings() const { return settings_; }

 private:
  std::shared_ptr<const CollisionExpert> collision_;
  ConfigModel config_;
  ClearApproachSettings settings_;
  std::vector<double> offsets_;
};

}  // namespace graspmix
