#pragma once
// Which objects of a segmented scene a synthesis grasps: every one, one by index, the largest, the one nearest a
// point or nearest the camera (graspmix_cli's --target, GraspModel.synthesize's target=).
#include <optional>
#include <vector>

#include "graspmix/core/types.hpp"
#include "graspmix/perception/segmentation.hpp"

namespace graspmix {

/// m: a "point" target names the object with a point within this distance of it, or none.
inline constexpr double kPointTargetMaxDistance = 0.05;

/// Which objects grasps are sampled on.
struct Target {
  enum class Kind { All, Index, Point, Largest, Nearest };
  Kind kind = Kind::All;
  int index = 0;                                    ///< Index: the object's index
  Eigen::Vector3d point = Eigen::Vector3d::Zero();  ///< Point: the object with a point nearest to it
  /// Nearest: the object with the point nearest to this camera position; unset: to the camera that saw each
  /// point, or the origin without viewpoints.
  std::optional<Eigen::Vector3d> camera;
};

/// The object indices of `target` in a segmented scene whose kept points were seen from `viewpoints` (one row
/// per point of scene.points, one row for all, or 0 rows): All every object, Index that one, Largest the one with
/// the most points (ties: the lower index), Point the one with a point nearest to it (within
/// kPointTargetMaxDistance), Nearest as Target says (ties: the lower index). Throws std::invalid_argument for an
/// index out of range, a point that names no object, a scene without objects (but for All), viewpoints of another
/// count and a camera that is not finite.
std::vector<int> select_targets(const Segmentation& scene, const Vec3Array& viewpoints, const Target& target);

}  // namespace graspmix
