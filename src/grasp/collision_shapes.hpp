#pragma once
// The collision expert's view of a hand's link shapes (private to src/): each shape's local bounding box, its
// FCL geometry against the support plane, and its interior samples for the occupancy model; the plane's and the
// occupancy's per-shape terms.
#include <memory>
#include <optional>
#include <vector>

#include <fcl/geometry/collision_geometry.h>
#include <fcl/geometry/shape/halfspace.h>
#include <Eigen/Geometry>

#include "graspmix/grasp/collision.hpp"

namespace graspmix {

struct CollisionExpert::Shapes {
  /// The FCL geometry and the interior samples depend on the hand alone: they are made once per hand (and grid
  /// spacing) and shared by every expert of that hand while it lives (a synthesis builds several: the scene's, the
  /// clear approach's, each target's neighbours').
  Shapes(const std::shared_ptr<const Hand>& hand, const std::optional<Eigen::Vector4d>& plane, double plane_margin);
  /// A shape's interior samples (shape frame), for the occupancy model.
  struct Interior {
    std::vector<Eigen::Vector3d> samples;
    double sample_volume = 0.0;  ///< m^3 each stands for
    /// The samples in blocks of up to kBlock^3 grid neighbours: [begin, end) of samples and the block's box
    /// (shape frame), so that a block wholly in free cells is skipped at once (OccupancyMap::any_blocked).
    struct Block {
      std::size_t begin = 0, end = 0;
      Eigen::Vector3d centre = Eigen::Vector3d::Zero(), half = Eigen::Vector3d::Zero();
    };
    std::vector<Block> blocks;
  };
  struct Shape {
    int link = -1;
    const CollisionShape* src = nullptr;
    Eigen::Vector3d half = Eigen::Vector3d::Zero();    ///< half extents of the local bounding box
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< centre of the local bounding box
    std::shared_ptr<const fcl::CollisionGeometryd> fcl_geometry;
    std::shared_ptr<const Interior> interior;  ///< null until sample_interiors
  };
  /// Fills every shape's interior samples: a grid of spacing min(h, half its thinnest side).
  void sample_interiors(double h);
  std::shared_ptr<const Hand> hand;
  std::vector<Shape> shapes;
  std::shared_ptr<fcl::Halfspaced> halfspace;
};

/// A shape's local bounding box posed at T, as an axis-aligned world box: its centre and half extents. Computed once
/// per shape and pose, for every term that culls by it.
struct WorldBox {
  Eigen::Vector3d centre, half;
};
inline WorldBox world_box(const CollisionExpert::Shapes::Shape& sh, const Eigen::Isometry3d& T) {
  return {T * sh.centre, T.linear().cwiseAbs() * sh.half};
}

/// The plane's P_l term of one shape posed at T (its world box: box_w; 0 when clear): boxes by FCL's own formula,
/// other shapes by FCL when their bounding box reaches below the raised plane.
double plane_term(const CollisionExpert::Shapes& shapes, const CollisionExpert::Shapes::Shape& sh,
                  const Eigen::Isometry3d& T, const WorldBox& box_w, const Eigen::Vector4d& plane, double plane_margin);

/// The volume (m^3) of the shape posed at T inside blocked cells of the map, over its interior samples
/// whose cell's centre lies deeper than tol + h/2 inside it; `count` gets the samples charged. A block of
/// samples whose world box touches no blocked cell is skipped whole.
double blocked_volume(const OccupancyMap& map, const CollisionExpert::Shapes::Shape& sh, const Eigen::Isometry3d& T,
                      double tol, int& count);

/// Whether blocked_volume would charge any sample (it stops at the first).
bool any_blocked_sample(const OccupancyMap& map, const CollisionExpert::Shapes::Shape& sh, const Eigen::Isometry3d& T,
                        double tol);

/// The same volume over the map's unknown cells whose sample lies outside the solid volume (`solid`'s occupied
/// cells; none when null) and, with margin > 0, farther than `margin` from it along every axis (no occupied cell in
/// the cube of half-side margin around it): the unseen space a soft charge weighs (CollisionSettings::unseen_weight).
double unseen_volume(const OccupancyMap& map, const OccupancyMap* solid, double margin,
                     const CollisionExpert::Shapes::Shape& sh, const Eigen::Isometry3d& T, double tol);

}  // namespace graspmix
