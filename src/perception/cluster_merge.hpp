#pragma once
// Steps on the clusters of segment_scene, private to perception: their principal axes and the merge rule
// (segmentation.hpp states it).
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "graspmix/core/types.hpp"

namespace graspmix::detail {

/// Centroid and principal axes of `rows` of P: columns by decreasing variance, each axis' largest component
/// positive (a deterministic sign) for the first two, right-handed.
void principal_axes(const Vec3Array& P, const std::vector<int>& rows, Eigen::Vector3d& centroid, Eigen::Matrix3d& axes);

/// Fraction of the lines of sight to `a` (rows of P, each from its camera to the point) that cross the
/// 26-DOP of `b` (rows of P) inset by `inset`. `cameras`: one row for all points, or one per row of P.
double seen_through(const Vec3Array& P, const Vec3Array& cameras, const std::vector<int>& b, const std::vector<int>& a,
                    double inset);

/// The merge rule: while some group is seen through a larger one (fraction >= `fraction`; the smallest
/// such group first, into the largest such larger group), join them. Each group stays sorted; returns the
/// number of joins.
std::size_t merge_seen_through(const Vec3Array& P, const Vec3Array& cameras, std::vector<std::vector<int>>& groups,
                               double fraction, double inset);

}  // namespace graspmix::detail
