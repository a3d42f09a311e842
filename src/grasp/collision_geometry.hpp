#pragma once
// Geometry of the collision expert, private to the library (grasp/collision.cpp): the signed distance to a
// link's shape, the grid cells an oriented box can meet, and a box's depth below a half-space.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "graspmix/robot/hand.hpp"

namespace graspmix::detail {

/// Signed distance from p (shape frame) to the shape's surface, negative inside.
inline double signed_distance(const CollisionShape& s, const Eigen::Vector3d& p) {
  switch (s.type) {
    case ShapeType::Box: {
      const Eigen::Vector3d q = p.cwiseAbs() - 0.5 * s.size;
      return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
    }
    case ShapeType::Cylinder: {
      const Eigen::Vector2d d(std::hypot(p.x(), p.y()) - s.size.x(), std::abs(p.z()) - 0.5 * s.size.y());
      return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
    }
    case ShapeType::Sphere:
      return p.norm() - s.size.x();
    case ShapeType::Mesh: {
      const RowMatrixXd& P = *s.hull_planes;
      double best = -std::numeric_limits<double>::infinity();
      for (Eigen::Index f = 0; f < P.rows(); ++f) {
        best = std::max(best, P(f, 0) * p.x() + P(f, 1) * p.y() + P(f, 2) * p.z() - P(f, 3));
      }
      return best;
    }
  }
  return std::numeric_limits<double>::infinity();
}

/// The signed distance from p (shape frame) where it is at most `limit`, else some value > limit (+inf when the
/// proxy decides): a mesh's proxy box first (hand.hpp: outside the box grown by box_growth * max(limit, 0), the
/// hull is farther than limit), then its hull's planes, largest facet first, stopping at the first one past the
/// limit. Wherever signed_distance(s, p) <= limit the two are equal, bit for bit.
inline double signed_distance_within(const CollisionShape& s, const Eigen::Vector3d& p, double limit) {
  if (s.type != ShapeType::Mesh) return signed_distance(s, p);
  const Eigen::Vector3d q = s.T_shape_box.linear().transpose() * (p - s.T_shape_box.translation());
  const double grow = limit > 0 ? s.box_growth * limit : 0.0;
  if ((q.cwiseAbs() - s.box_half).maxCoeff() > grow) return std::numeric_limits<double>::infinity();
  const RowMatrixXd& P = *s.hull_planes;
  double best = -std::numeric_limits<double>::infinity();
  for (Eigen::Index f = 0; f < P.rows(); ++f) {
    const double d = P(f, 0) * p.x() + P(f, 1) * p.y() + P(f, 2) * p.z() - P(f, 3);
    if (d > limit) return d;
    best = std::max(best, d);
  }
  return best;
}

/// A mesh's proxy boxes seen from p (shape frame): `excess`, the largest of |q| - box_half over the axes of the
/// proxy box (q: p in its frame; <= 0 inside it, where it is the box's signed distance and so a lower bound of
/// the hull's), and `inner`, the signed distance to the inner box (an upper bound of the hull's; +inf without
/// one).
struct ProxyView {
  double excess, inner;
};
inline ProxyView proxy_view(const CollisionShape& s, const Eigen::Vector3d& p) {
  const Eigen::Vector3d q = (s.T_shape_box.linear().transpose() * (p - s.T_shape_box.translation())).cwiseAbs();
  ProxyView v{(q - s.box_half).maxCoeff(), std::numeric_limits<double>::infinity()};
  if (s.box_inner.minCoeff() > 0.0) {
    const Eigen::Vector3d d = q - s.box_inner;
    v.inner = d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
  }
  return v;
}

/// Whether p (shape frame) lies within `limit` of the shape (signed_distance <= limit), a mesh's inner proxy
/// answering yes where it can before the planes (signed_distance_within otherwise).
inline bool within(const CollisionShape& s, const Eigen::Vector3d& p, double limit) {
  if (s.type == ShapeType::Mesh && s.box_inner.minCoeff() > 0.0) {
    const Eigen::Vector3d d =
        (s.T_shape_box.linear().transpose() * (p - s.T_shape_box.translation())).cwiseAbs() - s.box_inner;
    const double m = d.maxCoeff();  // the inner box's signed distance is m inside it, |d+| outside (>= m)
    if (m <= limit && (m <= 0.0 ? m : d.cwiseMax(0.0).norm()) <= limit) return true;
  }
  return signed_distance_within(s, p, limit) <= limit;
}

/// The cells of a grid (origin o, cubic cells of side h) that an oriented box (centre c, axes the columns of
/// R, half extents half) grown by r can meet, column by column. A cell is left out only when one of the
/// box's axes separates it from the grown box, with a margin over rounding: every point the per-point box
/// test keeps lies in a cell kept here. Set up once per pose; column() costs a few multiplications.
class BoxColumns {
 public:
  BoxColumns(const Eigen::Vector3d& o, double h, const Eigen::Vector3d& c, const Eigen::Matrix3d& R,
             const Eigen::Vector3d& half, double r) {
    constexpr double kMargin = 1e-9;  // m
    const double dx0 = o.x() + 0.5 * h - c.x(), dy0 = o.y() + 0.5 * h - c.y();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d a = R.col(k);
      Axis& ax = axes_[k];
      ax.s0 = a.x() * dx0 + a.y() * dy0;
      ax.sx = a.x() * h;
      ax.sy = a.y() * h;
      ax.bound = half[k] + r + 0.5 * h * a.cwiseAbs().sum() + kMargin;
      ax.flat = std::abs(a.z()) < 1e-12;
      ax.inv = ax.flat ? 0.0 : 1.0 / a.z();
    }
    inv_h_ = 1.0 / h;
    z_shift_ = (c.z() - o.z()) / h - 0.5;
  }

  /// The cells [z0, z1] of column (x, y) within [zmin, zmax] the box can meet; false when none.
  bool column(std::int64_t x, std::int64_t y, std::int64_t zmin, std::int64_t zmax, std::int64_t& z0,
              std::int64_t& z1) const {
    double lo = -std::numeric_limits<double>::infinity(), hi = std::numeric_limits<double>::infinity();
    for (const Axis& ax : axes_) {
      // The axis' projection of the cell centre's offset from c: s + a.z (z_c - c.z), |.| <= bound.
      const double s = ax.s0 + static_cast<double>(x) * ax.sx + static_cast<double>(y) * ax.sy;
      if (ax.flat) {
        if (std::abs(s) > ax.bound) return false;
        continue;
      }
      double l = (-ax.bound - s) * ax.inv, u = (ax.bound - s) * ax.inv;
      if (l > u) std::swap(l, u);
      lo = std::max(lo, l);
      hi = std::min(hi, u);
    }
    if (!(lo <= hi)) return false;
    // Cell z has its centre at o.z + (z + 0.5) h: z_c - c.z in [lo, hi].
    const double f0 = std::max(std::ceil(lo * inv_h_ + z_shift_), static_cast<double>(zmin));
    const double f1 = std::min(std::floor(hi * inv_h_ + z_shift_), static_cast<double>(zmax));
    if (!(f0 <= f1)) return false;
    z0 = static_cast<std::int64_t>(f0);
    z1 = static_cast<std::int64_t>(f1);
    return true;
  }

 private:
  struct Axis {
    double s0 = 0, sx = 0, sy = 0, bound = 0, inv = 0;
    bool flat = false;
  };
  Axis axes_[3];
  double inv_h_ = 1, z_shift_ = 0;
};

/// FCL's penetration depth of a box posed at T against the half-space {n . x <= d} (boxHalfspaceIntersect,
/// the same formula): negative when clear.
inline double box_halfspace_depth(const Eigen::Vector3d& side, const Eigen::Isometry3d& T, const Eigen::Vector3d& n,
                                  double d) {
  const Eigen::Vector3d Q = T.linear().transpose() * n;
  const Eigen::Vector3d B(std::abs(Q[0] * side[0]), std::abs(Q[1] * side[1]), std::abs(Q[2] * side[2]));
  return 0.5 * (B[0] + B[1] + B[2]) - (n.dot(T.translation()) - d);
}

}  // namespace graspmix::detail
