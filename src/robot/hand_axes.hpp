#pragma once
// A hand's grasp axes (Hand::approach_axis, Hand::fingertips): read from the URDF's <graspmix> element or
// inferred from the hand's geometry when the URDF is read (the rules are stated in hand.hpp).
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "graspmix/robot/hand.hpp"

namespace graspmix::detail {

/// What a URDF's <graspmix approach_axis="x y z" fingertips="a b"/> element gives (nothing without one).
struct UrdfGraspAxes {
  std::optional<Eigen::Vector3d> approach;  ///< unit
  std::vector<std::string> fingertips;
};

/// The element's attributes; throws std::invalid_argument starting with `what` for an axis that is not three
/// finite numbers, not all zero, or an attribute other than the two.
UrdfGraspAxes read_urdf_grasp_axes(const std::string& xml, const std::string& what);

struct GraspAxes {
  Eigen::Vector3d approach = Eigen::Vector3d::UnitZ();
  std::vector<int> fingertips;  ///< link indices, ascending
  bool given = false;           ///< the URDF's element gave the approach or the fingertips
};

/// The axes of `hand` by hand.hpp's rules; a given approach (unit) or given fingertips (link indices) are kept
/// and the other inferred from them. Fingertips empty when no moving link has collision geometry (the approach
/// then stays +z).
GraspAxes infer_grasp_axes(const Hand& hand, const std::optional<Eigen::Vector3d>& approach,
                           const std::vector<int>& fingertips, const HandLoadSettings& settings);

/// The axes of a hand read from `xml`: its <graspmix> element's (fingertips checked by Hand::checked_fingertip),
/// the rest inferred.
GraspAxes grasp_axes_of(const Hand& hand, const std::string& xml, const std::string& what,
                        const HandLoadSettings& settings);

}  // namespace graspmix::detail
