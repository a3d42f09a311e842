// The collision expert's link shapes: bounds, FCL geometry, interior samples, and their plane and occupancy terms.
#include "grasp/collision_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_request.h>
#include <fcl/narrowphase/collision_result.h>

#include "grasp/collision_geometry.hpp"

namespace graspmix {

using detail::box_halfspace_depth;
using detail::signed_distance;

namespace {

std::shared_ptr<fcl::CollisionGeometryd> make_fcl_geometry(const CollisionShape& s) {
  switch (s.type) {
    case ShapeType::Box:
      return std::make_shared<fcl::Boxd>(s.size.x(), s.size.y(), s.size.z());
    case ShapeType::Cylinder:
      return std::make_shared<fcl::Cylinderd>(s.size.x(), s.size.y());
    case ShapeType::Sphere:
      return std::make_shared<fcl::Sphered>(s.size.x());
    case ShapeType::Mesh: {
      if (!s.hull) return nullptr;
      auto verts = std::make_shared<std::vector<Eigen::Vector3d>>();
      for (Eigen::Index i = 0; i < s.hull->vertices.rows(); ++i) verts->push_back(s.hull->vertices.row(i).transpose());
      auto faces = std::make_shared<std::vector<int>>();
      for (Eigen::Index i = 0; i < s.hull->triangles.rows(); ++i) {
        faces->push_back(3);
        for (int k = 0; k < 3; ++k) faces->push_back(s.hull->triangles(i, k));
      }
      return std::make_shared<fcl::Convexd>(verts, static_cast<int>(s.hull->triangles.rows()), faces);
    }
  }
  return nullptr;
}

}  // namespace

CollisionExpert::Shapes::Shapes(const Hand& hand, const std::optional<Eigen::Vector4d>& plane, double plane_margin) {
  for (int l = 0; l < hand.n_links(); ++l) {
    for (const CollisionShape& s : hand.links()[static_cast<size_t>(l)].collisions) {
      if (s.type == ShapeType::Mesh && !s.hull_planes) {
        throw std::invalid_argument("hand: link '" + hand.link_names()[static_cast<size_t>(l)] +
                                    "' has a mesh without geometry (the hand was read with load_meshes = false)");
      }
      Shape sh;
      sh.link = l;
      sh.src = &s;
      switch (s.type) {
        case ShapeType::Box:
          sh.half = 0.5 * s.size;
          break;
        case ShapeType::Cylinder:
          sh.half = Eigen::Vector3d(s.size.x(), s.size.x(), 0.5 * s.size.y());
          break;
        case ShapeType::Sphere:
          sh.half = Eigen::Vector3d::Constant(s.size.x());
          break;
        case ShapeType::Mesh: {
          const Eigen::Vector3d lo = s.hull->vertices.colwise().minCoeff().transpose();
          const Eigen::Vector3d hi = s.hull->vertices.colwise().maxCoeff().transpose();
          sh.centre = 0.5 * (lo + hi);
          sh.half = 0.5 * (hi - lo);
          break;
        }
      }
      if (plane) sh.fcl_geometry = make_fcl_geometry(s);
      shapes.push_back(std::move(sh));
    }
  }
  if (plane) {
    // FCL's half-space is {x : n . x <= d}: the table below the (raised) plane n . x + d0 = margin.
    halfspace = std::make_shared<fcl::Halfspaced>(Eigen::Vector3d(plane->head<3>()), plane_margin - (*plane)[3]);
  }
}

namespace {

/// Appends to sh the interior samples of the grid cells [lo, hi) (indices of the grid first + spacing * (i, j, k))
/// as one block with their bounding box, when any lies inside the shape.
void add_block(CollisionExpert::Shapes::Shape& sh, const Eigen::Vector3d& first, double spacing,
               const Eigen::Vector3i& lo, const Eigen::Vector3i& hi) {
  CollisionExpert::Shapes::Shape::Block b;
  b.begin = sh.samples.size();
  Eigen::Vector3d box_lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), box_hi = -box_lo;
  for (int k = lo.z(); k < hi.z(); ++k)
    for (int j = lo.y(); j < hi.y(); ++j)
      for (int i = lo.x(); i < hi.x(); ++i) {
        const Eigen::Vector3d p = first + spacing * Eigen::Vector3d(i, j, k);
        if (signed_distance(*sh.src, p) >= 0) continue;
        sh.samples.push_back(p);
        box_lo = box_lo.cwiseMin(p);
        box_hi = box_hi.cwiseMax(p);
      }
  b.end = sh.samples.size();
  if (b.end == b.begin) return;
  b.centre = 0.5 * (box_lo + box_hi);
  b.half = 0.5 * (box_hi - box_lo);
  sh.blocks.push_back(b);
}

}  // namespace

void CollisionExpert::Shapes::sample_interiors(double h) {
  constexpr int kBlock = 4;
  for (Shape& sh : shapes) {
    const double spacing = std::min(h, sh.half.minCoeff());  // at least two samples across
    if (!(spacing > 0)) continue;
    const Eigen::Vector3i n = (2.0 * sh.half / spacing).array().ceil().cast<int>().max(1);
    // The grid centred on the shape's box, so that a symmetric shape gets symmetric samples.
    const Eigen::Vector3d first = sh.centre - 0.5 * spacing * (n.cast<double>() - Eigen::Vector3d::Ones());
    for (int kb = 0; kb < n.z(); kb += kBlock)
      for (int jb = 0; jb < n.y(); jb += kBlock)
        for (int ib = 0; ib < n.x(); ib += kBlock) {
          const Eigen::Vector3i lo(ib, jb, kb);
          add_block(sh, first, spacing, lo, (lo + Eigen::Vector3i::Constant(kBlock)).cwiseMin(n));
        }
    sh.sample_volume = spacing * spacing * spacing;
  }
}

double plane_term(const CollisionExpert::Shapes& shapes, const CollisionExpert::Shapes::Shape& sh,
                  const Eigen::Isometry3d& T, const Eigen::Vector4d& plane, double plane_margin) {
  const fcl::Halfspaced& hs = *shapes.halfspace;
  if (sh.src->type == ShapeType::Box) {
    const double depth = box_halfspace_depth(sh.src->size, T, hs.n, hs.d);
    return depth >= 0 ? depth : 0.0;
  }
  const Eigen::Vector3d n = plane.head<3>();
  // Skip FCL when even the shape's bounding box clears the raised plane.
  const Eigen::Vector3d centre = T * sh.centre;
  const Eigen::Vector3d half = T.linear().cwiseAbs() * sh.half;
  const double lowest = n.dot(centre) + plane[3] - half.dot(n.cwiseAbs());
  if (!(lowest < plane_margin && sh.fcl_geometry)) return 0.0;
  fcl::CollisionRequestd request(1, true);
  fcl::CollisionResultd result;
  fcl::collide(sh.fcl_geometry.get(), fcl::Transform3d(T.matrix()), &hs, fcl::Transform3d::Identity(), request, result);
  // FCL's sign convention for half-space contacts differs between shape pairs; the depth is its magnitude.
  return result.isCollision() ? std::abs(result.getContact(0).penetration_depth) : 0.0;
}

namespace {

/// The volume of the shape's samples charged: those for which `charged(sample, its cell's state)` holds and whose
/// cell's centre lies deeper than tol + h/2 inside the shape. `any(lo, hi)`: whether a box may hold a charged cell.
template <class Any, class Charged>
double charged_volume(const OccupancyMap& map, const CollisionExpert::Shapes::Shape& sh, const Eigen::Isometry3d& T,
                      double tol, int& count, Any any, Charged charged) {
  const double erosion = tol + 0.5 * map.resolution();
  const Eigen::Matrix3d& R = T.linear();
  const Eigen::Matrix3d absR = R.cwiseAbs();
  const Eigen::Vector3d t = T.translation();
  int n = 0;
  for (const auto& b : sh.blocks) {
    const Eigen::Vector3d c = T * b.centre, half = absR * b.half;
    if (!any(c - half, c + half)) continue;
    for (std::size_t s = b.begin; s < b.end; ++s) {
      Eigen::Vector3d centre;
      const Eigen::Vector3d x = R * sh.samples[s] + t;
      if (!charged(x, map.cell(x, centre))) continue;
      if (-signed_distance(*sh.src, R.transpose() * (centre - t)) > erosion) ++n;
    }
  }
  count += n;
  return n * sh.sample_volume;
}

}  // namespace

double blocked_volume(const OccupancyMap& map, const CollisionExpert::Shapes::Shape& sh, const Eigen::Isometry3d& T,
                      double tol, int& count) {
  return charged_volume(
      map, sh, T, tol, count,
      [&](const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) { return map.any_blocked(lo, hi); },
      [&](const Eigen::Vector3d&, CellState st) { return map.blocked(st); });
}

double unseen_volume(const OccupancyMap& map, const OccupancyMap* solid, double margin,
                     const CollisionExpert::Shapes::Shape& sh, const Eigen::Isometry3d& T, double tol) {
  int count = 0;
  const Eigen::Vector3d m = Eigen::Vector3d::Constant(margin);
  return charged_volume(
      map, sh, T, tol, count,
      [&](const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) { return map.any_unknown(lo, hi); },
      [&](const Eigen::Vector3d& x, CellState st) {
        if (st != CellState::Unknown) return false;
        if (!solid) return true;
        return margin > 0 ? !solid->any_blocked(x - m, x + m) : solid->state(x) != CellState::Occupied;
      });
}

}  // namespace graspmix
