#pragma once
// The closing motion of the contact-quality expert, private to the library (grasp/contact_quality.cpp): the
// cloud's grid, and each finger's first contact as the hand closes (include/graspmix/grasp/contact_quality.hpp
// states the rule).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "core/uniform_grid.hpp"
#include "grasp/collision_geometry.hpp"
#include "graspmix/grasp/contact_quality.hpp"

namespace graspmix {

namespace closing {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
using Index = ContactQualityExpert::Index;

/// The grid over the cloud's box: cells 1.5 times the side of one point's share of the box (a surface cloud
/// then has several per cell; finer grids were slower on the bench's 2k-point mug, the columns' overhead
/// outweighing the points they skip), at most 4 million cells.
inline detail::UniformGrid cloud_grid(const Eigen::Ref<const Vec3Array>& P, const Eigen::Vector3d& lo,
                                      const Eigen::Vector3d& hi) {
  using Grid = detail::UniformGrid;
  if (P.rows() == 0) return Grid(P, Eigen::Vector3d::Zero(), 1.0, {1, 1, 1}, Grid::Layout::Dense);
  const Eigen::Vector3d ext = (hi - lo).cwiseMax(1e-6);
  const Eigen::Vector3d thick = ext.cwiseMax(0.05 * ext.maxCoeff());
  double h = std::max(std::cbrt(thick.prod() / static_cast<double>(P.rows())) * 1.5, 1e-4 * ext.maxCoeff());
  auto dims_for = [&](double hh) { return ((ext / hh).array().floor().cast<int>() + 1).matrix().eval(); };
  Eigen::Vector3i dims = dims_for(h);
  while (static_cast<double>(dims[0]) * dims[1] * dims[2] > 4e6) dims = dims_for(h *= 1.5);
  return Grid(P, lo, h, {dims[0], dims[1], dims[2]}, Grid::Layout::Dense);
}

}  // namespace closing

struct ContactQualityExpert::Index {
  Index(const Eigen::Ref<const Vec3Array>& points, const Eigen::Ref<const Vec3Array>& normals)
      : lo(points.rows() > 0 ? Eigen::Vector3d(points.colwise().minCoeff().transpose()) : Eigen::Vector3d::Zero()),
        hi(points.rows() > 0 ? Eigen::Vector3d(points.colwise().maxCoeff().transpose()) : Eigen::Vector3d::Zero()),
        grid(closing::cloud_grid(points, lo, hi)),
        normals(static_cast<size_t>(points.rows())) {
    for (int i = 0; i < grid.size(); ++i) this->normals[static_cast<size_t>(i)] = normals.row(grid.row(i)).normalized();
  }
  Eigen::Vector3d lo, hi;  ///< the cloud's bounding box
  detail::UniformGrid grid;
  std::vector<Eigen::Vector3d> normals;  ///< unit, in the grid's canonical order
};

namespace closing {

/// One finger's first contact.
struct Contact {
  double t = kNaN;
  int patch = 0;  ///< points in the patch (0: no contact)
  Eigen::Vector3d point = Eigen::Vector3d::Constant(kNaN), normal = Eigen::Vector3d::Constant(kNaN);
  Eigen::Vector3d motion = Eigen::Vector3d::Zero();  ///< the contact point's displacement from t = 0 to t = 1
};

/// Per-thread storage reused across grasps.
struct Scratch {
  std::vector<Eigen::Isometry3d> poses0, poses1, poses;
  Eigen::VectorXd q;
  std::vector<int> cand, chain;
  struct Entry {
    int i;
    double lo, hi;
  };
  std::vector<Entry> entries;
};

/// A box of a translating link: a point x of the link frame at t = 0 is at Rt x + b - t e in the box's frame.
/// A mesh's slab is its proxy box grown by box_growth * g for g (g1, g2 below: tol, 2 tol), and its hull decides
/// the points the slab keeps: x is at Rs x + bs - t es in the mesh's frame.
struct Slab {
  Eigen::Matrix3d Rt;
  Eigen::Vector3d b, inv, half;  ///< inv = 1 / e per axis, 0 where the box does not move along it
  bool aligned = false;          ///< Rt is the identity
  /// The one axis the box moves along (-1: none or several), and (half + g) |inv| there for g = g1, g2.
  int axis = -1;
  double reach1 = 0.0, reach2 = 0.0;
  double g1 = 0.0, g2 = 0.0;  ///< the growths of the box for the tolerances tol and 2 tol
  const CollisionShape* mesh = nullptr;
  Eigen::Matrix3d Rs = Eigen::Matrix3d::Identity();
  Eigen::Vector3d bs = Eigen::Vector3d::Zero(), es = Eigen::Vector3d::Zero();
};

/// The times in [0, 1] at which the point x0 - t es (mesh frame) lies within g2 of the hull (every plane's
/// n . x - offset <= g2): [lo2, hi2] (false when none), and the first within g1 <= g2 (in1; inf when never).
inline bool hull_times(const RowMatrixXd& P, const Eigen::Vector3d& x0, const Eigen::Vector3d& es, double g1, double g2,
                       double& lo2, double& hi2, double& in1) {
  lo2 = 0.0;
  hi2 = 1.0;
  double lo1 = 0.0, hi1 = 1.0;
  for (Eigen::Index f = 0; f < P.rows(); ++f) {
    const double c = P(f, 0) * x0.x() + P(f, 1) * x0.y() + P(f, 2) * x0.z() - P(f, 3);
    const double v = P(f, 0) * es.x() + P(f, 1) * es.y() + P(f, 2) * es.z();  // c - t v <= g
    if (v == 0.0) {
      if (c > g2) return false;
      if (c > g1) hi1 = -1.0;
    } else if (v > 0.0) {
      lo2 = std::max(lo2, (c - g2) / v);
      lo1 = std::max(lo1, (c - g1) / v);
    } else {
      hi2 = std::min(hi2, (c - g2) / v);
      hi1 = std::min(hi1, (c - g1) / v);
    }
    if (lo2 > hi2) return false;
  }
  in1 = lo1 <= hi1 ? lo1 : kInf;
  return true;
}

/// The times in [0, 1] at which the point `a` (box frame, t = 0) lies within the box grown by g2: [lo2, hi2]
/// (false when none), and the first time it lies within the box grown by g1 <= g2 (in1; inf when never).
inline bool slab_times(const Slab& sl, const Eigen::Vector3d& a, double g1, double g2, double& lo2, double& hi2,
                       double& in1) {
  if (sl.axis >= 0) {  // the usual case (a finger moving along one of its box's axes), without branches per axis
    const int m = sl.axis, u = (m + 1) % 3, v = (m + 2) % 3;
    const double d = std::max(std::abs(a[u]) - sl.half[u], std::abs(a[v]) - sl.half[v]);
    if (d > g2) return false;
    const double c = a[m] * sl.inv[m];
    lo2 = std::max(0.0, c - sl.reach2);
    hi2 = std::min(1.0, c + sl.reach2);
    if (lo2 > hi2) return false;
    const double lo1 = std::max(0.0, c - sl.reach1);
    in1 = d <= g1 && lo1 <= std::min(1.0, c + sl.reach1) ? lo1 : kInf;
    return true;
  }
  lo2 = 0.0;
  hi2 = 1.0;
  double lo1 = 0.0, hi1 = 1.0;
  for (int k = 0; k < 3; ++k) {
    if (sl.inv[k] == 0.0) {
      const double d = std::abs(a[k]) - sl.half[k];
      if (d > g2) return false;
      if (d > g1) hi1 = -1.0;
      continue;
    }
    const double c = a[k] * sl.inv[k], w = std::abs(sl.half[k] * sl.inv[k]), g = std::abs(sl.inv[k]);
    lo2 = std::max(lo2, c - w - g2 * g);
    hi2 = std::min(hi2, c + w + g2 * g);
    lo1 = std::max(lo1, c - w - g1 * g);
    hi1 = std::min(hi1, c + w + g1 * g);
  }
  in1 = lo1 <= hi1 ? lo1 : kInf;
  return lo2 <= hi2;
}

/// The cells of the grid under the box [lo, hi]; false when it misses the cloud's box.
inline bool cells_under(const Index& ix, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                        detail::UniformGrid::Cell& c0, detail::UniformGrid::Cell& c1) {
  if (ix.grid.size() == 0 || (lo.array() > ix.hi.array()).any() || (hi.array() < ix.lo.array()).any()) return false;
  c0 = ix.grid.cell_of(lo);
  c1 = ix.grid.cell_of(hi);
  return true;
}

/// The contact point (the patch's mean) and normal axis (the principal axis of its normals, pointed against
/// the motion) of the patch of canonical positions `patch`.
inline void patch_contact(const Index& ix, const std::vector<int>& patch, Contact& c) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  for (const int i : patch) {
    sum += ix.grid.point(i);
    M.noalias() += ix.normals[static_cast<size_t>(i)] * ix.normals[static_cast<size_t>(i)].transpose();
  }
  c.patch = static_cast<int>(patch.size());
  c.point = sum / static_cast<double>(patch.size());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(M);
  c.normal = eig.eigenvectors().col(2).normalized();  // eigenvalues ascending
  if (c.normal.dot(c.motion) > 0.0) c.normal = -c.normal;
}

/// The slab of a shape (frame T_link_shape) of a link displaced by e (link frame) over the closing, for the
/// tolerance tol; returns the frame of its box in the link frame.
inline Eigen::Isometry3d make_slab(const CollisionShape& sh, const Eigen::Vector3d& e, double tol, Slab& sl) {
  const bool mesh = sh.type == ShapeType::Mesh;
  const Eigen::Isometry3d T = mesh ? sh.T_link_shape * sh.T_shape_box : sh.T_link_shape;
  sl.Rt = T.linear().transpose();
  sl.b = -sl.Rt * T.translation();
  const Eigen::Vector3d es = sl.Rt * e;
  for (int a = 0; a < 3; ++a) sl.inv[a] = std::abs(es[a]) > 1e-12 * e.norm() ? 1.0 / es[a] : 0.0;
  sl.half = mesh ? sh.box_half : Eigen::Vector3d(0.5 * sh.size);
  sl.g1 = mesh ? sh.box_growth * tol : tol;
  sl.g2 = 2.0 * sl.g1;
  if (mesh) {
    sl.mesh = &sh;
    sl.Rs = sh.T_link_shape.linear().transpose();
    sl.bs = -sl.Rs * sh.T_link_shape.translation();
    sl.es = sl.Rs * e;
  }
  sl.aligned = sl.Rt.isIdentity(0.0);
  if ((sl.inv.array() != 0.0).count() == 1) {
    sl.inv.cwiseAbs().maxCoeff(&sl.axis);
    sl.reach1 = (sl.half[sl.axis] + sl.g1) * std::abs(sl.inv[sl.axis]);
    sl.reach2 = (sl.half[sl.axis] + sl.g2) * std::abs(sl.inv[sl.axis]);
  }
  return T;
}

/// The first contact of a link moved by prismatic joints alone, whose shapes are boxes or meshes: it translates
/// by D = A1 - A0 over t in [0, 1], so each point's entry time into a grown box is one slab test (into a mesh's
/// hull grown by the tolerance, a slab test of its proxy box and, for the points that pass, one of its planes). The
/// sweep is cut into chunks half as long as the link is thick along it, visited in order until one holds a contact;
/// only the grid's cells that can meet a chunk's swept box (in the link's frame) are visited.
inline Contact translating_contact(const Index& ix, const LinkInfo& link, const Eigen::Isometry3d& A0,
                                   const Eigen::Isometry3d& A1, double tol, Scratch& s) {
  Contact c;
  c.motion = A1.translation() - A0.translation();
  const Eigen::Matrix3d Rt = A0.linear().transpose();
  const Eigen::Vector3d o = A0.translation(), e = Rt * c.motion;  // the displacement in the link frame
  // The boxes in their frames; lo, hi bound them grown by 2 tol in the link frame.
  Slab slabs[8];
  const int n_shapes = static_cast<int>(std::min<size_t>(link.collisions.size(), 8));
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInf), hi = -lo;
  for (int k = 0; k < n_shapes; ++k) {
    const CollisionShape& sh = link.collisions[static_cast<size_t>(k)];
    Slab& sl = slabs[k];
    const Eigen::Isometry3d T = make_slab(sh, e, tol, sl);
    const Eigen::Vector3d ext = T.linear().cwiseAbs() * (sl.half.array() + sl.g2).matrix();
    lo = lo.cwiseMin(T.translation() - ext);
    hi = hi.cwiseMax(T.translation() + ext);
  }
  const double thick = (hi - lo).dot(e.cwiseAbs()) / std::max(e.norm(), 1e-300);
  const int chunks = std::clamp(static_cast<int>(std::ceil(e.norm() / (0.5 * thick))), 1, 32);
  double first = kInf;
  for (int j = 0; j < chunks && !(first <= 1.0); ++j) {
    const double ta = static_cast<double>(j) / chunks, tb = static_cast<double>(j + 1) / chunks;
    const Eigen::Vector3d slo = (lo + ta * e).cwiseMin(lo + tb * e), shi = (hi + ta * e).cwiseMax(hi + tb * e);
    const Eigen::Vector3d mid = 0.5 * (slo + shi), half = 0.5 * (shi - slo), centre = A0 * mid;
    const Eigen::Vector3d ext = A0.linear().cwiseAbs() * half;
    detail::UniformGrid::Cell c0, c1;
    if (!cells_under(ix, centre - ext, centre + ext, c0, c1)) continue;
    const detail::BoxColumns columns(ix.lo, ix.grid.cell_size(), centre, A0.linear(), half, 0.0);
    s.entries.clear();
    for (std::int64_t x = c0[0]; x <= c1[0]; ++x) {
      for (std::int64_t y = c0[1]; y <= c1[1]; ++y) {
        std::int64_t z0, z1;
        if (!columns.column(x, y, c0[2], c1[2], z0, z1)) continue;
        const auto [b, end] = ix.grid.z_run(x, y, z0, z1);
        for (Eigen::Index i = b; i < end; ++i) {
          const Eigen::Vector3d a = Rt * (ix.grid.point(static_cast<int>(i)) - o);
          if (((a - mid).cwiseAbs() - half).maxCoeff() > 0.0) continue;
          for (int k = 0; k < n_shapes; ++k) {
            double lo2, hi2, in1;
            const Slab& sl = slabs[k];
            const Eigen::Vector3d as = sl.aligned ? Eigen::Vector3d(a + sl.b) : Eigen::Vector3d(sl.Rt * a + sl.b);
            if (!slab_times(sl, as, sl.g1, sl.g2, lo2, hi2, in1)) continue;
            if (sl.mesh && !hull_times(*sl.mesh->hull_planes, sl.Rs * a + sl.bs, sl.es, tol, 2.0 * tol, lo2, hi2, in1))
              continue;
            first = std::min(first, in1);
            if (lo2 <= std::min(first, tb)) s.entries.push_back({static_cast<int>(i), lo2, hi2});
          }
        }
      }
    }
    if (first > tb) first = kInf;  // entries after this chunk are found again, in order, by a later one
  }
  if (!(first <= 1.0)) return c;
  c.t = first;
  s.cand.clear();
  for (const Scratch::Entry& en : s.entries) {
    if (en.lo <= first && first <= en.hi && (s.cand.empty() || s.cand.back() != en.i)) s.cand.push_back(en.i);
  }
  patch_contact(ix, s.cand, c);
  return c;
}

/// Whether any candidate lies within tol of the link posed at A (its shapes' signed distance <= tol; meshes
/// through their proxies, detail::signed_distance_within).
inline bool any_within(const Index& ix, const LinkInfo& link, const Eigen::Isometry3d& A, const std::vector<int>& cand,
                       double tol) {
  for (const CollisionShape& sh : link.collisions) {
    const Eigen::Isometry3d inv = (A * sh.T_link_shape).inverse();
    for (const int i : cand)
      if (detail::within(sh, inv * ix.grid.point(i), tol)) return true;
  }
  return false;
}

/// The world box of the points within g >= 0 of the link posed at A: each shape's box grown by g (a mesh's proxy
/// box by box_growth * g, hand.hpp), into [lo, hi].
inline void reach_box(const LinkInfo& link, const Eigen::Isometry3d& A, double g, Eigen::Vector3d& lo,
                      Eigen::Vector3d& hi) {
  for (const CollisionShape& sh : link.collisions) {
    Eigen::Isometry3d T = A * sh.T_link_shape;
    Eigen::Vector3d half;
    switch (sh.type) {
      case ShapeType::Box:
        half = (0.5 * sh.size).array() + g;
        break;
      case ShapeType::Cylinder:
        half = Eigen::Vector3d(sh.size.x(), sh.size.x(), 0.5 * sh.size.y()).array() + g;
        break;
      case ShapeType::Sphere:
        half = Eigen::Vector3d::Constant(sh.size.x() + g);
        break;
      case ShapeType::Mesh:
        if (g > 0.0 && !std::isfinite(sh.box_growth)) {  // no bound: everywhere
          lo.setConstant(-kInf);
          hi.setConstant(kInf);
          return;
        }
        T = T * sh.T_shape_box;
        half = sh.box_half.array() + (g > 0.0 ? sh.box_growth * g : 0.0);
        break;
    }
    const Eigen::Vector3d ext = T.linear().cwiseAbs() * half;
    lo = lo.cwiseMin(T.translation() - ext);
    hi = hi.cwiseMax(T.translation() + ext);
  }
}

/// The candidates (the points in the cells c0..c1) within `limit` >= 0 of the link posed at A, into `out`, in
/// canonical order; stops at the first when `first_only`. Only the cells under reach_box are visited, not every
/// candidate: the same points as a test of each.
inline void near_points(const Index& ix, const LinkInfo& link, const Eigen::Isometry3d& A, double limit,
                        const detail::UniformGrid::Cell& c0, const detail::UniformGrid::Cell& c1, bool first_only,
                        std::vector<int>& out) {
  out.clear();
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInf), hi = -lo;
  reach_box(link, A, limit, lo, hi);
  if (ix.grid.size() == 0 || (lo.array() > ix.hi.array()).any() || (hi.array() < ix.lo.array()).any()) return;
  detail::UniformGrid::Cell b0 = ix.grid.cell_of(lo.cwiseMax(ix.lo)), b1 = ix.grid.cell_of(hi.cwiseMin(ix.hi));
  for (size_t k = 0; k < 3; ++k) {
    b0[k] = std::max(b0[k], c0[k]);
    b1[k] = std::min(b1[k], c1[k]);
    if (b0[k] > b1[k]) return;
  }
  std::vector<Eigen::Isometry3d> inv;
  for (const CollisionShape& sh : link.collisions) inv.push_back((A * sh.T_link_shape).inverse());
  for (std::int64_t x = b0[0]; x <= b1[0]; ++x)
    for (std::int64_t y = b0[1]; y <= b1[1]; ++y) {
      const auto [b, e] = ix.grid.z_run(x, y, b0[2], b1[2]);
      for (Eigen::Index i = b; i < e; ++i) {
        for (size_t k = 0; k < inv.size(); ++k) {
          const Eigen::Vector3d q = inv[k] * ix.grid.point(static_cast<int>(i));
          if (detail::within(link.collisions[k], q, limit)) {
            out.push_back(static_cast<int>(i));
            if (first_only) return;
            break;
          }
        }
      }
    }
}

/// The joints from the wrist down to link l, in order.
inline void chain_of(const Hand& hand, int l, std::vector<int>& chain) {
  chain.clear();
  for (int j = hand.links()[static_cast<size_t>(l)].parent_joint; j >= 0;
       j = hand.links()[static_cast<size_t>(hand.joints()[static_cast<size_t>(j)].parent_link)].parent_joint) {
    chain.push_back(j);
  }
  std::reverse(chain.begin(), chain.end());
}

/// The pose of the link at the end of `chain` for wrist W and joints q: Hand::fk_into's products in its order
/// (the same bits), for that link's joints alone (the closing poses one finger at a time).
inline Eigen::Isometry3d chain_pose(const Hand& hand, const std::vector<int>& chain, const Eigen::Isometry3d& W,
                                    const double* q) {
  Eigen::Isometry3d T = W;
  for (const int ji : chain) {
    const JointInfo& j = hand.joints()[static_cast<size_t>(ji)];
    T = T * j.T_parent_joint;
    apply_joint(j, q, T);
  }
  return T;
}

/// The world box of a shape posed at T (its local box: boxes exactly, cylinders, spheres, mesh hulls bounded).
inline void shape_box(const CollisionShape& sh, const Eigen::Isometry3d& T, Eigen::Vector3d& lo, Eigen::Vector3d& hi) {
  Eigen::Vector3d half = Eigen::Vector3d::Zero(), centre = Eigen::Vector3d::Zero();
  switch (sh.type) {
    case ShapeType::Box:
      half = 0.5 * sh.size;
      break;
    case ShapeType::Cylinder:
      half = Eigen::Vector3d(sh.size.x(), sh.size.x(), 0.5 * sh.size.y());
      break;
    case ShapeType::Sphere:
      half = Eigen::Vector3d::Constant(sh.size.x());
      break;
    case ShapeType::Mesh: {
      const Vec3Array& V = sh.hull->vertices;
      const Eigen::Vector3d vlo = V.colwise().minCoeff().transpose(), vhi = V.colwise().maxCoeff().transpose();
      centre = 0.5 * (vlo + vhi);
      half = 0.5 * (vhi - vlo);
      break;
    }
  }
  const Eigen::Vector3d c = T * centre, ext = T.linear().cwiseAbs() * half;
  lo = lo.cwiseMin(c - ext);
  hi = hi.cwiseMax(c + ext);
}

/// The first contact of any other link: closing_steps steps of the signed distance over the points under
/// the swept box, then bisection in the first step that comes within the tolerance.
inline Contact stepped_contact(const Hand& hand, const Index& ix, int l, const Eigen::Isometry3d& W,
                               const Eigen::VectorXd& p, const Eigen::VectorXd& cl, double tol, int steps, Scratch& s) {
  const LinkInfo& link = hand.links()[static_cast<size_t>(l)];
  chain_of(hand, l, s.chain);
  auto pose_at = [&](double t) {
    s.q = p + t * (cl - p);
    return chain_pose(hand, s.chain, W, s.q.data());
  };
  std::vector<Eigen::Isometry3d> A(static_cast<size_t>(steps) + 1);
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInf), hi = -lo;
  double stride = 0.0;  // how far a point of the link's boxes moves in one step, at most
  Eigen::Vector3d blo = Eigen::Vector3d::Constant(kInf), bhi = -blo;  // the link's box in its own frame
  for (const CollisionShape& sh : link.collisions) shape_box(sh, sh.T_link_shape, blo, bhi);
  const double reach = std::max(blo.norm(), bhi.norm());
  for (int k = 0; k <= steps; ++k) {
    A[static_cast<size_t>(k)] = pose_at(static_cast<double>(k) / steps);
    for (const CollisionShape& sh : link.collisions) shape_box(sh, A[static_cast<size_t>(k)] * sh.T_link_shape, lo, hi);
    if (k > 0) {
      const Eigen::Isometry3d step = A[static_cast<size_t>(k) - 1].inverse() * A[static_cast<size_t>(k)];
      stride =
          std::max(stride, step.translation().norm() + (step.linear() - Eigen::Matrix3d::Identity()).norm() * reach);
    }
  }
  Contact c;
  c.motion = A.back().translation() - A.front().translation();
  const Eigen::Vector3d grow = Eigen::Vector3d::Constant(2.0 * tol + stride);
  detail::UniformGrid::Cell c0, c1;
  if (!cells_under(ix, lo - grow, hi + grow, c0, c1)) return c;
  // The first step at which a candidate comes within tol.
  int k = 0;
  for (; k <= steps; ++k) {
    near_points(ix, link, A[static_cast<size_t>(k)], tol, c0, c1, true, s.cand);
    if (!s.cand.empty()) break;
  }
  if (k > steps) return c;
  // The bisection and the patch look only at t in [t_{k-1}, t_k]: a point within 2 tol of the link then is within
  // 2 tol + stride of it at t_k (signed distances are 1-Lipschitz in the point, and stride bounds how far the link
  // moves in a step, as it does for the candidates' box), so these candidates (2 stride for margin) lose none.
  near_points(ix, link, A[static_cast<size_t>(k)], k > 0 ? 2.0 * tol + 2.0 * stride : 2.0 * tol, c0, c1, false, s.cand);
  double a = k == 0 ? 0.0 : static_cast<double>(k - 1) / steps, b = static_cast<double>(k) / steps;
  for (int it = 0; k > 0 && it < 30 && b - a > 1e-9; ++it) {
    const double m = 0.5 * (a + b);
    (any_within(ix, link, pose_at(m), s.cand, tol) ? b : a) = m;
  }
  c.t = b;
  const Eigen::Isometry3d At = pose_at(b);
  std::vector<int> patch;
  for (const CollisionShape& sh : link.collisions) {
    const Eigen::Isometry3d inv = (At * sh.T_link_shape).inverse();
    for (const int i : s.cand)
      if (detail::within(sh, inv * ix.grid.point(i), 2.0 * tol)) patch.push_back(i);
  }
  std::sort(patch.begin(), patch.end());
  patch.erase(std::unique(patch.begin(), patch.end()), patch.end());
  // The contact point's own displacement over the closing (for the normal's orientation).
  const Eigen::Vector3d x = At.inverse() * ix.grid.point(patch.front());
  c.motion = A.back() * x - A.front() * x;
  patch_contact(ix, patch, c);
  return c;
}

}  // namespace closing

}  // namespace graspmix
