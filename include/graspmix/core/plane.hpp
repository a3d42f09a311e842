#pragma once
// Which side of a plane a set of points is on: the one rule every part that orients a support plane
// uses (perception's prepare_cloud, grasp's CollisionExpert).
#include <Eigen/Core>

#include "graspmix/core/types.hpp"

namespace graspmix {

/// m: what lies at most this far above a support plane is the table, not an object: the segmentation drops
/// observed points there and the completion adds none (the plane has its own term in the collision expert).
inline constexpr double kTableClearance = 0.005;

/// How orient_plane decides the side of the points, with h_i = a x_i + b y_i + c z_i + d their signed
/// heights over the plane [a, b, c, d]. Each rule keeps the plane as given on a tie.
enum class PlaneSide {
  /// More points strictly above (h_i > 0) than not (h_i <= 0): robust to a few far outliers. Used by
  /// prepare_cloud on the points off the plane.
  Majority,
  /// mean(h_i) >= 0. Used by CollisionExpert (CollisionSettings::orient_plane) on the whole cloud.
  Mean,
  /// median(h_i) >= 0 (numpy's median: the mean of the two middle heights for an even count).
  Median,
};

/// The plane [a, b, c, d] or its negation, whichever has the points on its positive side
/// (a x + b y + c z + d > 0) by `rule`. The plane is not normalised; with no points it is returned
/// as given.
Eigen::Vector4d orient_plane(const Eigen::Vector4d& plane, const Eigen::Ref<const Vec3Array>& points, PlaneSide rule);

}  // namespace graspmix
