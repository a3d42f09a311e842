#pragma once
// The join rule of segment_scene (segmentation.hpp states it): clusters that are pieces of one object cut
// apart by a shadow in the view, private to perception.
#include <cstddef>
#include <vector>

#include "graspmix/core/types.hpp"
#include "graspmix/perception/visibility.hpp"

namespace graspmix::detail {

struct JoinRule {
  double max_gap = 0;      ///< m: clusters farther apart are never joined
  double seen_margin = 0;  ///< m: how far beyond the gap the views must have seen for it to be seen empty
  double max_size = 0;     ///< m: the joined cluster's largest principal-box side may not exceed this
};

/// The largest side (m) of the principal box of `rows` of P (its points' covariance axes).
double largest_side(const Vec3Array& P, const std::vector<int>& rows);

/// How far the views saw beyond the gap between groups a and b (rows of P): over the facing segments (each
/// point of one within kFacingBand of the least gap joined to its nearest point of the other, at most
/// kMaxSegments of them, nearest first), the median of each segment's largest signed distance at its
/// interior samples (unseen or outside every view counts as -inf). NaN when the gap exceeds max_gap; `gap`
/// gets the least distance (m).
double seen_beyond_gap(const Vec3Array& P, const VisibilityModel& vis, const std::vector<int>& a,
                       const std::vector<int>& b, double max_gap, double& gap);

/// The join rule: while some pair of groups passes it, the pair with the least gap is joined (rows kept
/// sorted). Returns the number of joins.
std::size_t join_occluded(const Vec3Array& P, const VisibilityModel& vis, std::vector<std::vector<int>>& groups,
                          const JoinRule& rule);

}  // namespace graspmix::detail
