// Spherical views of a VisibilityModel: an unorganized cloud as pcl::RangeImage around its viewpoint.
//
// PCL bins each point by its angles from the sensor (its own projection, lookup-table atan2 and asin) and keeps
// the nearest range per bin (noise_level 0), filling the empty neighbours of a point's bin on the way; queries
// go through the same projection, so a point falls into the bin its ray's points were binned into. The image
// is built around the viewpoint with the points relative to it (PCL works in float: world coordinates far from
// the origin would lose millimetres), its z axis towards the points' bounding sphere, so that the sphere's
// image is small (createFromPointCloudWithKnownSize) and the seam of the angles lies behind the sensor.
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/range_image/range_image.h>

#include "perception/visibility_view.hpp"

namespace graspmix::detail {

namespace {

constexpr double kMinRange = 1e-6;  // m: points this close to the viewpoint have no direction

class SphericalView final : public VisibilityView {
 public:
  SphericalView(ViewInfo info, pcl::RangeImage image, const Eigen::Vector3d& viewpoint)
      : VisibilityView(std::move(info)), image_(std::move(image)), viewpoint_(viewpoint) {}

  double signed_distance(const Eigen::Vector3d& p, bool /*no_return_is_free: empty bins are unseen*/) const override {
    const Eigen::Vector3d rel = p - viewpoint_;
    const double range = rel.norm();
    if (!(range > kMinRange)) return std::numeric_limits<double>::quiet_NaN();
    float x = 0, y = 0, r = 0;
    image_.getImagePoint(Eigen::Vector3f(rel.cast<float>()), x, y, r);
    int column = 0, row = 0;
    image_.real2DToInt2D(x, y, column, row);
    if (!image_.isInImage(column, row)) return std::numeric_limits<double>::quiet_NaN();
    const float observed = image_.getPoint(column, row).range;  // -inf: no point in this bin
    if (!std::isfinite(observed)) return std::numeric_limits<double>::quiet_NaN();
    return static_cast<double>(observed) - range;
  }

 private:
  pcl::RangeImage image_;
  Eigen::Vector3d viewpoint_;
};

/// A rotation whose z axis points along `forward` (identity for a zero vector).
Eigen::Matrix3d looking_along(const Eigen::Vector3d& forward) {
  if (!(forward.norm() > 1e-12)) return Eigen::Matrix3d::Identity();
  const Eigen::Vector3d z = forward.normalized();
  const Eigen::Vector3d helper = std::abs(z.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d x = helper.cross(z).normalized();
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = z.cross(x);
  R.col(2) = z;
  return R;
}

/// The pixels PCL allocates for a bounding sphere (centre c relative to the sensor, radius r): the sphere's
/// angular size when the sensor is outside it, else the whole sphere of directions.
double pixels_needed(const Eigen::Vector3d& c, double r, double resolution) {
  const double d = c.norm();
  if (d <= r) return std::floor(2 * M_PI / resolution) * std::floor(M_PI / resolution);
  const double side = 2 * std::ceil(0.5 * 2 * std::asin(r / d) / resolution);
  return side * side;
}

}  // namespace

std::shared_ptr<const VisibilityView> make_spherical_view(const Eigen::Ref<const Vec3Array>& points,
                                                          const Eigen::Vector3d& viewpoint,
                                                          const VisibilitySettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!viewpoint.allFinite()) throw std::invalid_argument("viewpoint: contains NaN or infinite values");
  pcl::PointCloud<pcl::PointXYZ> cloud;
  cloud.reserve(static_cast<std::size_t>(points.rows()));
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d rel = points.row(i).transpose() - viewpoint;
    if (!rel.allFinite() || !(rel.norm() > kMinRange)) continue;
    cloud.push_back(
        pcl::PointXYZ(static_cast<float>(rel.x()), static_cast<float>(rel.y()), static_cast<float>(rel.z())));
    centre += rel;
  }
  if (cloud.empty()) {
    throw std::invalid_argument("points: no finite point away from the viewpoint (" + std::to_string(points.rows()) +
                                " rows)");
  }
  centre /= static_cast<double>(cloud.size());
  double radius = 0;
  for (const auto& q : cloud) radius = std::max(radius, (q.getVector3fMap().cast<double>() - centre).norm());
  radius += 1e-6;  // the farthest point inside, after float rounding
  const double res = settings.angular_resolution;
  const double needed = pixels_needed(centre, radius, res);
  if (needed > static_cast<double>(settings.max_pixels)) {
    throw std::invalid_argument("points: a spherical image at angular_resolution " + std::to_string(res) +
                                " rad needs " + std::to_string(static_cast<std::int64_t>(needed)) +
                                " pixels, more than max_pixels = " + std::to_string(settings.max_pixels) +
                                " (coarsen the resolution)");
  }
  const Eigen::Matrix3d R_world_sensor = looking_along(centre);
  Eigen::Affine3f sensor = Eigen::Affine3f::Identity();
  sensor.linear() = R_world_sensor.cast<float>();
  pcl::RangeImage image;
  image.createFromPointCloudWithKnownSize(cloud, static_cast<float>(res), centre.cast<float>(),
                                          static_cast<float>(radius), sensor, pcl::RangeImage::CAMERA_FRAME, 0.0f, 0.0f,
                                          0);
  ViewInfo info;
  info.kind = ViewKind::Spherical;
  info.T_world_sensor = Eigen::Isometry3d::Identity();
  info.T_world_sensor.linear() = R_world_sensor;
  info.T_world_sensor.translation() = viewpoint;
  info.width = static_cast<int>(image.width);
  info.height = static_cast<int>(image.height);
  for (const auto& px : image.points) info.n_returns += std::isfinite(px.range) ? 1 : 0;
  info.angular_resolution = res;
  info.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return std::make_shared<SphericalView>(info, std::move(image), viewpoint);
}

}  // namespace graspmix::detail
