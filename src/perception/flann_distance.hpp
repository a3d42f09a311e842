#pragma once
// FLANN's squared distance between two PCL points, private to perception: the sources that must find the same
// neighbours as PCL's kd-tree (cloud_filters.cpp, knn_distances.cpp) use it, each built without floating-point
// contraction (CMakeLists.txt), so each product is rounded as FLANN's are.
#include <pcl/point_types.h>

namespace graspmix::detail {
namespace {  // a copy in each source that includes it: each keeps its own compile options

/// FLANN's L2_Simple<float>: the squares summed in float, x then y then z.
inline float flann_squared(const pcl::PointXYZ& a, float bx, float by, float bz) {
  float d2 = 0, d = 0;
  d = a.x - bx, d2 += d * d;
  d = a.y - by, d2 += d * d;
  d = a.z - bz, d2 += d * d;
  return d2;
}

inline float flann_squared(const pcl::PointXYZ& a, const pcl::PointXYZ& b) { return flann_squared(a, b.x, b.y, b.z); }

}  // namespace
}  // namespace graspmix::detail
