#pragma once
// The solid volume of objects standing on a support plane, from their points (observed and completed): what a
// hand must stay out of even where no point is near it. A cloud, even a completed one, samples surfaces only: a
// finger wholly inside an object touches none of its points, and the surface collision model cannot see it.
//
// The rule (columns): the points are projected onto the plane into a footprint grid of cells resolution / 2 wide;
// a footprint cell holding a point is solid from the plane up to the highest point above it (an object stands on
// the table, so everything under its top surface is object: exact for prisms, cylinders, boxes and anything without
// overhangs; an overhang, a mug's handle, is filled down to the table). An empty footprint cell with solid cells
// within `gap` on both sides along its row or its column is filled, up to the lower of those two tops: it closes the
// holes of a sparsely sampled top face (and bridges gaps between objects narrower than about `gap`, where no finger
// fits).
// The columns are baked into an OccupancyMap (cells of `resolution`): a cell is Occupied when its centre lies in a
// solid column, at least one cell above the plane (the plane has an exact term of its own in the collision
// expert); every other cell is Free. The footprint is half a cell fine so that an occupied cell's centre lies at
// most half a cell outside the points: the collision expert's erosion (contact tolerance + half a cell) then never
// charges a link that only touches the points.
#include <cstdint>

#include <Eigen/Core>

#include "graspmix/core/types.hpp"
#include "graspmix/grasp/occupancy.hpp"

namespace graspmix {

struct SolidVolumeSettings {
  double resolution = 0.005;            ///< m: the cell of the baked map (the footprint's is half of it), > 0
  double gap = 0.005;                   ///< m: empty footprint cells are filled between solid ones this close (>= 0)
  std::int64_t max_cells = 50'000'000;  ///< the baked map's largest size (cells)
};

/// The solid columns of `points` (N, 3, world) standing on `plane` ([n, d], n . x + d = 0; oriented so that the
/// points' mean lies on its positive side). Points less than one cell above the plane (the table's own) make no
/// column. Throws std::invalid_argument for non-finite points, a degenerate plane, bad settings or a region of more
/// than max_cells. No point above the plane gives a map with no occupied cell.
OccupancyMap solid_volume(const Eigen::Ref<const Vec3Array>& points, const Eigen::Vector4d& plane,
                          const SolidVolumeSettings& settings = {});

}  // namespace graspmix
