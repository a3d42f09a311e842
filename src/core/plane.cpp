#include "graspmix/core/plane.hpp"

#include <algorithm>
#include <vector>

namespace graspmix {

namespace {

/// a x + b y + c z + d, written out so that every rule sums the terms in the same order.
double height(const Eigen::Vector4d& plane, const Eigen::Ref<const Vec3Array>& points, Eigen::Index i) {
  return plane[0] * points(i, 0) + plane[1] * points(i, 1) + plane[2] * points(i, 2) + plane[3];
}

bool majority_below(const Eigen::Vector4d& plane, const Eigen::Ref<const Vec3Array>& points) {
  long side = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) side += height(plane, points, i) > 0 ? 1 : -1;
  return side < 0;
}

bool mean_below(const Eigen::Vector4d& plane, const Eigen::Ref<const Vec3Array>& points) {
  return (points * plane.head<3>()).array().mean() + plane[3] < 0;
}

bool median_below(const Eigen::Vector4d& plane, const Eigen::Ref<const Vec3Array>& points) {
  std::vector<double> h(static_cast<std::size_t>(points.rows()));
  for (Eigen::Index i = 0; i < points.rows(); ++i) h[static_cast<std::size_t>(i)] = height(plane, points, i);
  const std::size_t mid = h.size() / 2;
  std::nth_element(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(mid), h.end());
  if (h.size() % 2 == 1) return h[mid] < 0;
  const double below = *std::max_element(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(mid));
  return 0.5 * (below + h[mid]) < 0;
}

}  // namespace

Eigen::Vector4d orient_plane(const Eigen::Vector4d& plane, const Eigen::Ref<const Vec3Array>& points, PlaneSide rule) {
  if (points.rows() == 0) return plane;
  bool flip = false;
  switch (rule) {
    case PlaneSide::Majority:
      flip = majority_below(plane, points);
      break;
    case PlaneSide::Mean:
      flip = mean_below(plane, points);
      break;
    case PlaneSide::Median:
      flip = median_below(plane, points);
      break;
  }
  return flip ? Eigen::Vector4d(-plane) : plane;
}

}  // namespace graspmix
