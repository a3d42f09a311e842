#pragma once
// The points that bound a link's collision shapes, private to the library (grasp/contact_quality.cpp's flat wall,
// grasp/topdown_seeds.cpp's fingertip extents).
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

}  // namespace graspmix
