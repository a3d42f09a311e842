#pragma once
// The points that bound a link's collision shapes, private to the library (grasp/contact_quality.cpp's flat wall,
// grasp/topdown_seeds.cpp's fingertip extents).
#include <Eigen/Core>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "graspmix/robot/hand.hpp"

namespace graspmix {

/// The points that bound a link's collision shapes, in the link frame: a box's corners, a mesh's hull vertices, a
/// cylinder's rims (16 points each), a sphere's 6 poles.
inline std::vector<Eigen::Vector3d> shape_corners(const std::vector<CollisionShape>& shapes) {
  std::vector<Eigen::Vector3d> out;
  for (const CollisionShape& sh : shapes) {
    const Eigen::Vector3d h = 0.5 * sh.size;
    switch (sh.type) {
      case ShapeType::Box:
        for (int k = 0; k < 8; ++k)
          out.push_back(sh.T_link_shape *
                        Eigen::Vector3d(k & 1 ? h.x() : -h.x(), k & 2 ? h.y() : -h.y(), k & 4 ? h.z() : -h.z()));
        break;
      case ShapeType::Cylinder:
        for (int k = 0; k < 32; ++k) {
          const double a = 2.0 * M_PI * (k % 16) / 16.0;
          out.push_back(sh.T_link_shape *
                        Eigen::Vector3d(sh.size.x() * std::cos(a), sh.size.x() * std::sin(a), k < 16 ? -h.y() : h.y()));
        }
        break;
      case ShapeType::Sphere:
        for (int k = 0; k < 6; ++k)
          out.push_back(sh.T_link_shape * (sh.size.x() * (k % 2 ? 1.0 : -1.0) * Eigen::Vector3d::Unit(k / 2)));
        break;
      case ShapeType::Mesh:
        if (sh.hull)
          for (Eigen::Index i = 0; i < sh.hull->vertices.rows(); ++i)
            out.push_back(sh.T_link_shape * Eigen::Vector3d(sh.hull->vertices.row(i).transpose()));
        break;
    }
  }
  return out;
}

/// A link's shape bounds in the wrist frame at a configuration: their points (shape_corners) and their mean, its
/// middle (zero for a link without shapes); a link's origin may sit on its joint's axis, its middle does not.
struct LinkBounds {
  std::vector<Eigen::Vector3d> corners;
  Eigen::Vector3d middle = Eigen::Vector3d::Zero();
};

/// The bounds of `links` (indices of hand's links) with the wrist at the origin and the joints at q.
inline std::vector<LinkBounds> link_bounds(const Hand& hand, const std::vector<int>& links, const Eigen::VectorXd& q) {
  std::vector<Eigen::Isometry3d> poses(static_cast<size_t>(hand.n_links()));
  hand.fk_into(Eigen::Isometry3d::Identity(), q.data(), poses.data());
  std::vector<LinkBounds> out(links.size());
  for (size_t f = 0; f < links.size(); ++f) {
    const size_t l = static_cast<size_t>(links[f]);
    for (const Eigen::Vector3d& x : shape_corners(hand.links()[l].collisions)) out[f].corners.push_back(poses[l] * x);
    for (const Eigen::Vector3d& x : out[f].corners) out[f].middle += x / static_cast<double>(out[f].corners.size());
  }
  return out;
}

/// Fingertips' middles (LinkBounds::middle, one per fingertip, at least one): their mean, and the span from the
/// first fingertip's middle to the mean of the others' (zero for one fingertip). The line of the span is the line
/// the fingers close along: grasp/topdown_seeds.cpp lays it across the object, grasp/grasp_depth.cpp's cylinder is
/// as wide as half of it.
struct FingertipSpan {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Vector3d span = Eigen::Vector3d::Zero();
};

inline FingertipSpan fingertip_span(const std::vector<Eigen::Vector3d>& middles) {
  FingertipSpan out;
  Eigen::Vector3d others = Eigen::Vector3d::Zero();
  for (size_t f = 0; f < middles.size(); ++f) {
    out.mean += middles[f] / static_cast<double>(middles.size());
    if (f > 0) others += middles[f] / static_cast<double>(middles.size() - 1);
  }
  if (middles.size() > 1) out.span = others - middles.front();
  return out;
}

}  // namespace graspmix
