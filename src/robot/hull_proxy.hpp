#pragma once
// The cheap proxy of a mesh's convex hull (CollisionShape::T_shape_box, box_half, box_growth), private to the
// library (robot/urdf_loader.cpp makes it once per shape when a hand is read).
#include <vector>

#include "graspmix/robot/hand.hpp"

namespace graspmix::detail {

/// Orders the hull's unique planes (rows [nx, ny, nz, offset]) largest facet first and fits the shape's proxy
/// box: the smaller of the box along the shape's axes and the box along the hull vertices' principal axes, and
/// the growth bound of hand.hpp. tri_plane: the row of `planes` that each triangle of `hull` lies in.
void fit_hull_proxy(RowMatrixXd& planes, const TriangleMesh& hull, const std::vector<int>& tri_plane,
                    CollisionShape& s);

}  // namespace graspmix::detail
