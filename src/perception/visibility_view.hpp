#pragma once
// One view of a VisibilityModel (include/graspmix/perception/visibility.hpp): an image of the observed surface
// around a sensor and its projection. Pinhole views live in visibility.cpp, spherical ones (pcl::RangeImage)
// in visibility_spherical.cpp, so PCL stays out of every header but this folder's sources.
#include <memory>

#include <Eigen/Core>

#include "graspmix/perception/visibility.hpp"

namespace graspmix::detail {

class VisibilityView {
 public:
  explicit VisibilityView(ViewInfo info) : info_(std::move(info)) {}
  virtual ~VisibilityView() = default;
  VisibilityView(const VisibilityView&) = delete;
  VisibilityView& operator=(const VisibilityView&) = delete;

  /// The signed distance (m) along p's ray (p in the world frame) from p to the surface this view observed,
  /// positive in front; NaN where the view says nothing (outside its image, behind the sensor, a pixel with
  /// no return), +inf on a pixel with no return when no_return_is_free (pinhole views only).
  virtual double signed_distance(const Eigen::Vector3d& p, bool no_return_is_free) const = 0;
  /// signed_distance of every row of points (N, 3) into out (N): by default one call a point; a view may loop
  /// itself, the same arithmetic without a call per point.
  virtual void signed_distances(const Eigen::Ref<const Vec3Array>& points, bool no_return_is_free, double* out) const {
    for (Eigen::Index i = 0; i < points.rows(); ++i)
      out[i] = signed_distance(points.row(i).transpose(), no_return_is_free);
  }

  const ViewInfo& info() const { return info_; }

 protected:
  ViewInfo info_;
};

/// A spherical range image of `points` (world frame, non-finite rows skipped) around `viewpoint`
/// (visibility_spherical.cpp). Throws std::invalid_argument as VisibilityModel::from_points documents.
std::shared_ptr<const VisibilityView> make_spherical_view(const Eigen::Ref<const Vec3Array>& points,
                                                          const Eigen::Vector3d& viewpoint,
                                                          const VisibilitySettings& settings);

}  // namespace graspmix::detail
