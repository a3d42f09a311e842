#pragma once
// The parts of an object a hand can close across from above, private to the library (grasp/topdown_seeds.cpp's part
// seeds; the rule and its constants: include/graspmix/grasp/topdown_seeds.hpp).
#include <vector>

#include <Eigen/Core>

#include "graspmix/core/types.hpp"

namespace graspmix {

/// A part: its middle on the table (world frame), the horizontal unit direction to close along, its width along it
/// (the extent of the points under the fingers) and the highest of those points above the table.
struct ObjectPart {
  Eigen::Vector3d middle;
  Eigen::Vector3d direction;
  double width = 0.0;
  double top = 0.0;
};

/// Up to kPartSeedCentres parts of the object whose points are given (finite; world frame) on the table whose unit
/// normal is `up` and offset `offset` (up . x + offset = height above it), for fingers 2 * half_width wide whose
/// widest gap is `widest`: none when any of `others` (the other objects' observed points) comes within
/// kPartSeedIsolation of the object's footprint, or when the footprint exceeds kPartSeedMaxCells.
std::vector<ObjectPart> graspable_parts(const Vec3Array& points, const Vec3Array& others, const Eigen::Vector3d& up,
                                        double offset, double half_width, double widest);

}  // namespace graspmix
