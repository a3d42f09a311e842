// The collision expert's link shapes: bounds, FCL geometry, interior samples, and their plane and occupancy terms.
#include "grasp/collision_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <mutex>
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

std::shared_ptr<const fcl::CollisionGeometryd> make_fcl_geometry(const CollisionShape& s) {
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

/// What of a hand's shapes outlives one expert, per shape in Shapes' order: its FCL geometry and its interior
/// samples per grid spacing, each made when first asked for. Kept while the hand lives (a weak reference: an entry
/// whose hand is gone is dropped at the next look-up).
struct HandShapes {
  std::vector<std::shared_ptr<const fcl::CollisionGeometryd>> geometry;
  std::map<double, std::vector<std::shared_ptr<const CollisionExpert::Shapes::Interior>>> interiors;
};

std::mutex cache_mutex;
std::map<std::weak_ptr<const Hand>, HandShapes, std::owner_less<std::weak_ptr<const Hand>>> cache;

/// The hand's entry (empty at first); call with cache_mutex held.
HandShapes& hand_entry(const std::shared_ptr<const Hand>& hand) {
  for (auto it = cache.begin(); it != cache.end();) it = it->first.expired() ? cache.erase(it) : std::next(it);
  return cache[hand];
}

}  // namespace

CollisionExpert::Shapes::Shapes(const std::shared_ptr<const Hand>& hand_ptr,
                                const std::optional<Eigen::Vector4d>& plane, double plane_margin)
    : hand(hand_ptr) {
  for (int l = 0; l < hand->n_links(); ++l) {
    for (const CollisionShape& s : hand->links()[static_cast<size_t>(l)].collisions) {
      if (s.type == ShapeType::Mesh && !s.hull_planes) {
        throw std::invalid_argument("hand: link '" + hand->link_names()[static_cast<size_t>(l)] +
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
      shapes.push_back(std::move(sh));
    }
  }
  if (plane) {
    // FCL's geometry of a mesh is its hull (FCL checks the hull's topology when it is made: made once per hand).
    const std::lock_guard<std::mutex> lock(cache_mutex);
    HandShapes& entry = hand_entry(hand);
    if (entry.geometry.empty()) {
      for (const Shape& sh : shapes) entry.geometry.push_back(make_fcl_geometry(*sh.src));
    }
    for (std::size_t i = 0; i < shapes.size(); ++i) shapes[i].fcl_geometry = entry.geometry[i];
    // FCL's half-space is {x : n . x <= d}: the table below the (raised) plane n . x + d0 = margin.
    halfspace = std::make_shared<fcl::Halfspaced>(Eigen::Vector3d(plane->head<3>()), plane_margin - (*plane)[3]);
  }
}

namespace {

/// Appends to `in` the interior samples of the grid cells [lo, hi) (indices of the grid first + spacing * (i, j, k))
/// as one block with their bounding box, when any lies inside the shape.
void add_block(CollisionExpert::Shapes::Interior& in, const CollisionShape& src, const Eigen::Vector3d& first,
               double spacing, const Eigen::Vector3i& lo, const Eigen::Vector3i& hi) {
  CollisionExpert::Shapes::Interior::Block b;
  b.begin = in.samples.size();
  Eigen::Vector3d box_lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), box_hi = -box_lo;
  for (int k = lo.z(); k < hi.z(); ++k)
    for (int j = lo.y(); j < hi.y(); ++j)
      for (int i = lo.x(); i < hi.x(); ++i) {
        const Eigen::Vector3d p = first + spacing * Eigen::Vector3d(i, j, k);
        if (signed_distance(src, p) >= 0) continue;
        in.samples.push_back(p);
        box_lo = box_lo.cwiseMin(p);
        box_hi = box_hi.cwiseMax(p);
      }
  b.end = in.samples.size();
  if (b.end == b.begin) return;
  b.centre = 0.5 * (box_lo + box_hi);
  b.half = 0.5 * (box_hi - box_lo);
  in.blocks.push_back(b);
}

/// One shape's interior samples: a grid of spacing min(h, half its thinnest side) centred on its box.
std::shared_ptr<const CollisionExpert::Shapes::Interior> make_interior(const CollisionExpert::Shapes::Shape& sh,
                                                                       double h) {
  constexpr int kBlock = 4;
  auto in = std::make_shared<CollisionExpert::Shapes::Interior>();
  const double spacing = std::min(h, sh.half.minCoeff());  // at least two samples across
  if (!(spacing > 0)) return in;
  const Eigen::Vector3i n = (2.0 * sh.half / spacing).array().ceil().cast<int>().max(1);
  // The grid centred on the shape's box, so that a symmetric shape gets symmetric samples.
  const Eigen::Vector3d first = sh.centre - 0.5 * spacing * (n.cast<double>() - Eigen::Vector3d::Ones());
  for (int kb = 0; kb < n.z(); kb += kBlock)
    for (int jb = 0; jb < n.y(); jb += kBlock)
      for (int ib = 0; ib < n.x(); ib += kBlock) {
        const Eigen::Vector3i lo(ib, jb, kb);
        add_block(*in, *sh.src, first, spacing, lo, (lo + Eigen::Vector3i::Constant(kBlock)).cwiseMin(n));
      }
  in->sample_volume = spacing * spacing * spacing;
  return in;
}

}  // namespace

void CollisionExpert::Shapes::sample_interiors(double h) {
  // A mesh link's samples cost a signed distance through its hull's planes per grid point (some 20 ms for the xArm
  // gripper's base link): made once per hand and spacing.
  const std::lock_guard<std::mutex> lock(cache_mutex);
  auto& made = hand_entry(hand).interiors[h];
  if (made.empty()) {
    for (const Shape& sh : shapes) made.push_back(make_interior(sh, h));
  }
  for (std::size_t i = 0; i < shapes.size(); ++i) shapes[i].interior = made[i];
}

double plane_term(const CollisionExpert::Shapes& shapes, const CollisionExpert::Shapes::Shape& sh,
                  const Eigen::Isometry3d& T, const WorldBox& box_w, const Eigen::Vector4d& plane,
                  double plane_margin) {
  const fcl::Halfspaced& hs = *shapes.halfspace;
  if (sh.src->type == ShapeType::Box) {
    const double depth = box_halfspace_depth(sh.src->size, T, hs.n, hs.d);
    return depth >= 0 ? depth : 0.0;
  }
  const Eigen::Vector3d n = plane.head<3>();
  // Skip FCL when even the shape's bounding box clears the raised plane.
  const double lowest = n.dot(box_w.centre) + plane[3] - box_w.half.dot(n.cwiseAbs());
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
/// kFirst: stop at the first sample charged (its volume alone: whether there is any).
template <bool kFirst = false, class Any, class Charged>
double charged_volume(const OccupancyMap& map, const CollisionExpert::Shapes::Shape& sh, const Eigen::Isometry3d& T,
                      double tol, int& count, Any any, Charged charged) {
  const double erosion = tol + 0.5 * map.resolution();
  const Eigen::Matrix3d& R = T.linear();
  const Eigen::Matrix3d absR = R.cwiseAbs();
  const Eigen::Vector3d t = T.translation();
  int n = 0;
  if (!sh.interior) return 0.0;
  const CollisionExpert::Shapes::Interior& in = *sh.interior;
  for (const auto& b : in.blocks) {
    const Eigen::Vector3d c = T * b.centre, half = absR * b.half;
    if (!any(c - half, c + half)) continue;
    for (std::size_t s = b.begin; s < b.end; ++s) {
      Eigen::Vector3d centre;
      const Eigen::Vector3d x = R * in.samples[s] + t;
      if (!charged(x, map.cell(x, centre))) continue;
      if (-signed_distance(*sh.src, R.transpose() * (centre - t)) > erosion) {
        ++n;
        if (kFirst) break;
      }
    }
    if (kFirst && n > 0) break;
  }
  count += n;
  return n * in.sample_volume;
}

/// charged_volume over the map's blocked cells (kFirst: stop at the first).
template <bool kFirst>
double blocked(const OccupancyMap& map, const CollisionExpert::Shapes::Shape& sh, const Eigen::Isometry3d& T,
               double tol, int& count) {
  return charged_volume<kFirst>(
      map, sh, T, tol, count,
      [&](const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) { return map.any_blocked(lo, hi); },
      [&](const Eigen::Vector3d&, CellState st) { return map.blocked(st); });
}

}  // namespace

double blocked_volume(const OccupancyMap& map, const CollisionExpert::Shapes::Shape& sh, const Eigen::Isometry3d& T,
                      double tol, int& count) {
  return blocked<false>(map, sh, T, tol, count);
}

bool any_blocked_sample(const OccupancyMap& map, const CollisionExpert::Shapes::Shape& sh, const Eigen::Isometry3d& T,
                        double tol) {
  int count = 0;
  return blocked<true>(map, sh, T, tol, count) > 0.0;
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
