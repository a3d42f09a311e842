#pragma once
// The target-first check of scene synthesis (ContactQualitySettings::target_first), private to the library: the
// closing test itself, and what it closes on besides the segmented objects (the points the segmentation's clean-up
// dropped that are not the target's). target_side, the target's own side, is public (scene_synthesis.hpp).
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "graspmix/core/types.hpp"
#include "graspmix/grasp/contact_quality.hpp"
#include "graspmix/grasp/synthesis.hpp"
#include "graspmix/perception/segmentation.hpp"

namespace graspmix::detail {

/// m: a point the segmentation dropped is the object's whose kept point comes nearest it within this (an outlier
/// lies by its object's edge, a few voxels off); farther from every kept point it is no object's.
inline constexpr double kDroppedOwnerRadius = 0.01;

/// 0 where each finger, closing from the pre-grasp, meets the target's points (`target`'s cloud) no later than the
/// other objects' (`others`), -inf where a finger meets another object first (or only another object). The closing
/// parameters are the contact quality's own (ContactQualityResult::t), so the test is exact for its closing motion.
Eigen::VectorXd target_first(const ContactQualityExpert& target, const ContactQualityExpert& others,
                             const std::vector<Grasp>& grasps);

/// Per row of scene.dropped, the object (Segmentation::objects index) whose kept point comes nearest it within
/// kDroppedOwnerRadius; -1 where none comes within it.
Eigen::VectorXi dropped_owners(const Segmentation& scene);

/// scene.dropped's points that are not object `target`'s (`owners`: dropped_owners(scene)): another object's, or
/// no object's.
Vec3Array dropped_not_of(const Segmentation& scene, const Eigen::VectorXi& owners, int target);

/// P in cells one radius wide: the nearest row of P within the radius of a point.
class RadiusGrid {
 public:
  /// Throws std::invalid_argument for a radius that is not finite and > 0.
  RadiusGrid(const Vec3Array& P, double radius);
  /// The row of P nearest p within the radius (ties: the first in the grid's canonical order), -1 for none.
  Eigen::Index nearest(const Eigen::Vector3d& p) const;

 private:
  struct Impl;
  std::shared_ptr<const Impl> impl_;
};

}  // namespace graspmix::detail
