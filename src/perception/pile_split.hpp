#pragma once
// The split rule of segment_scene (segmentation.hpp states it): a cluster that holds several objects touching in
// a pile cut along its concave creases, private to perception.
#include <cstddef>
#include <vector>

#include "graspmix/core/types.hpp"

namespace graspmix::detail {

struct SplitRule {
  double voxel_resolution = 0;     ///< m: the supervoxels' voxel
  double seed_resolution = 0;      ///< m: the supervoxels' seed spacing
  double concavity_tolerance = 0;  ///< rad: a crease less concave than this is no cut (LCCP)
  int min_piece_points = 0;        ///< a piece with fewer points goes back to the neighbour it touches most
  double max_size = 0;             ///< m: one object's largest principal-box side (larger clusters are cut)
};

/// The split rule on each group (rows of P) seen from `seen_from` (one row per point of P, or one for all): the
/// group's points in a frame centred on its camera (supervoxel normals face the origin), supervoxels
/// (pcl::SupervoxelClustering) grouped by PCL's LCCP; small pieces go back. Groups that split are replaced by
/// their pieces (rows kept sorted). Returns the number of pieces added.
std::size_t split_touching(const Vec3Array& P, const Vec3Array& seen_from, std::vector<std::vector<int>>& groups,
                           const SplitRule& rule);

}  // namespace graspmix::detail
