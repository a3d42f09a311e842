#pragma once
// Exact depth images for the perception tests: cameras posed by where they look, pixel rays, and the first hit of
// a ray with planes and axis-aligned boxes in closed form (test_visibility, test_depth_scene, test_completion).
#include <algorithm>
#include <functional>
#include <limits>
#include <utility>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "graspmix/perception/camera.hpp"

namespace graspmix::test {

inline const double kRayMiss = std::numeric_limits<double>::infinity();

/// A camera at `eye` looking at `target`, world z up: x right, y down, z forward.
inline Eigen::Isometry3d looking_at(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
  const Eigen::Vector3d z = (target - eye).normalized();
  const Eigen::Vector3d x = z.cross(Eigen::Vector3d::UnitZ()).normalized();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() << x, z.cross(x), z;
  T.translation() = eye;
  return T;
}

/// The world direction of pixel coordinates (u, v) scaled so its camera z is 1: a point at depth s is eye + s dir.
inline Eigen::Vector3d ray(const PinholeCamera& cam, const Eigen::Isometry3d& T, double u, double v) {
  return T.linear() * cam.back_project(u, v, 1.0);
}

/// First hit t > 0 of o + t d with what the scene holds, inf for none.
using RayScene = std::function<double(const Eigen::Vector3d& o, const Eigen::Vector3d& d)>;

inline double hit_plane(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& n, double c) {
  const double t = (c - n.dot(o)) / n.dot(d);
  return t > 0 ? t : kRayMiss;
}

inline double hit_box(const Eigen::Vector3d& o, const Eigen::Vector3d& d, const Eigen::Vector3d& lo,
                      const Eigen::Vector3d& hi) {
  double t0 = 0, t1 = kRayMiss;
  for (int k = 0; k < 3; ++k) {
    double a = (lo[k] - o[k]) / d[k], b = (hi[k] - o[k]) / d[k];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return t0 <= t1 && t0 > 0 ? t0 : kRayMiss;
}

/// The depth image of `scene` seen by cam at T: at each pixel centre, the depth (camera z) of the first hit.
inline DepthImage render(const PinholeCamera& cam, const Eigen::Isometry3d& T, const RayScene& scene) {
  DepthImage out(cam.height(), cam.width());
  for (int v = 0; v < cam.height(); ++v)
    for (int u = 0; u < cam.width(); ++u) out(v, u) = scene(T.translation(), ray(cam, T, u, v));
  return out;
}

}  // namespace graspmix::test
