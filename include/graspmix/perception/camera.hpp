#pragma once
// A depth camera as a driver describes it: pinhole intrinsics, the depth image, the organized cloud in the
// sensor frame, and the camera's pose in the world.
//
// Sensor frame (PCL's and OpenCV's): x right, y down, z forward along the optical axis. Pixel (u, v) is
// (column, row); pixel centres lie at integer coordinates, so a point projects to u = fx x / z + cx,
// v = fy y / z + cy, and it falls in pixel (round(u), round(v)). An image of width W covers u in [-0.5, W - 0.5).
#include <cmath>
#include <cstdint>
#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "graspmix/core/types.hpp"

namespace graspmix {

/// A depth image: height x width, row-major (row v, column u), metres along the optical axis (z, not the
/// range along the ray). NaN, 0 and +inf mean "no return" (the conventions of ROS drivers, of 16-bit depth
/// images and of the simulated cameras); a negative or -inf depth is an error.
using DepthImage = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

/// Whether a depth value is a return: finite and > 0.
inline bool has_return(double depth) { return depth > 0 && depth < std::numeric_limits<double>::infinity(); }
/// The number of pixels with a return; throws std::invalid_argument naming `what` and the first pixel with a
/// negative (or -inf) depth.
std::int64_t count_returns(const Eigen::Ref<const DepthImage>& depth, const char* what = "depth");

/// How far a camera pose's quaternion norm may be from 1 before it is refused (graspmix.perception's
/// camera_to_world uses the same bound): poses are written with a few digits, a wrong order of
/// components or a Euler triple is far off.
inline constexpr double kUnitQuaternionTolerance = 1e-3;

/// Pinhole intrinsics of a depth camera, without lens distortion (drivers publish rectified images).
class PinholeCamera {
 public:
  /// Throws std::invalid_argument naming the parameter unless fx, fy > 0, cx, cy finite and width,
  /// height > 0 (and at most 1,000,000 each).
  PinholeCamera(double fx, double fy, double cx, double cy, int width, int height);

  double fx() const { return fx_; }
  double fy() const { return fy_; }
  double cx() const { return cx_; }
  double cy() const { return cy_; }
  int width() const { return width_; }
  int height() const { return height_; }
  /// The 3x3 matrix K = [[fx, 0, cx], [0, fy, cy], [0, 0, 1]].
  Eigen::Matrix3d matrix() const;

  /// Continuous pixel coordinates (u, v) of a point in the sensor frame; NaN for a point with z <= 0.
  Eigen::Vector2d project(const Eigen::Vector3d& p_camera) const {
    if (!(p_camera.z() > 0)) return Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
    const double inv_z = 1.0 / p_camera.z();
    return {fx_ * p_camera.x() * inv_z + cx_, fy_ * p_camera.y() * inv_z + cy_};
  }
  /// The pixel (column, row) holding continuous coordinates (u, v), or false when they fall outside the image.
  bool pixel(const Eigen::Vector2d& uv, int& column, int& row) const {
    // Shifted by half a pixel, a point of the image has coordinates in [0, width) x [0, height), where truncation
    // is floor (and cheaper: std::floor is a library call on baseline x86-64).
    const double c = uv.x() + 0.5, r = uv.y() + 0.5;
    if (!(c >= 0 && c < width_ && r >= 0 && r < height_)) return false;  // NaN fails too
    column = static_cast<int>(c);
    row = static_cast<int>(r);
    return true;
  }
  /// The point (sensor frame) at `depth` along the optical axis on the ray through (u, v).
  Eigen::Vector3d back_project(double u, double v, double depth) const {
    return {(u - cx_) * depth / fx_, (v - cy_) * depth / fy_, depth};
  }
  /// The pixels of `depth` with a return; throws std::invalid_argument naming `what` unless depth is
  /// height() x width() with no negative depth.
  std::int64_t check_image(const Eigen::Ref<const DepthImage>& depth, const char* what = "depth") const;
  /// The organized cloud of a depth image of this camera's size: (height * width, 3) in the sensor frame,
  /// row v * width + u, NaN rows where there is no return. Throws std::invalid_argument (naming `what`) for
  /// an image of another size or a negative depth.
  Vec3Array back_project(const Eigen::Ref<const DepthImage>& depth, const char* what = "depth") const;

  bool operator==(const PinholeCamera& o) const {
    return fx_ == o.fx_ && fy_ == o.fy_ && cx_ == o.cx_ && cy_ == o.cy_ && width_ == o.width_ && height_ == o.height_;
  }
  bool operator!=(const PinholeCamera& o) const { return !(*this == o); }

 private:
  double fx_, fy_, cx_, cy_;
  int width_, height_;
};

/// Intrinsics fitted to an organized cloud, with the fit's residual.
struct PinholeFit {
  PinholeCamera camera;
  double rms_px = 0.0;       ///< px: root-mean-square reprojection residual over the valid pixels
  std::int64_t n_valid = 0;  ///< pixels with a finite point in front of the camera
};

/// The pinhole intrinsics of an organized cloud (height * width, 3) in the sensor frame (row v * width + u;
/// NaN rows = no return): fx, cx by least squares over u = fx x / z + cx, and fy, cy over v = fy y / z + cy,
/// on every valid pixel. Throws std::invalid_argument naming `what` for a wrong row count, a finite point
/// with z <= 0, fewer than two distinct valid columns or rows, a fit with a focal length <= 0 or an RMS
/// residual above max_rms_px (not a pinhole image in the sensor frame: a cloud in the world frame, or
/// unorganized).
PinholeFit fit_pinhole(const Eigen::Ref<const Vec3Array>& points, int height, int width, double max_rms_px = 0.5,
                       const char* what = "points");

/// The depth image (height x width, the points' z; NaN where a row is not finite) of an organized cloud
/// (height * width, 3) in the sensor frame, row v * width + u. Throws std::invalid_argument naming `what` for a
/// wrong row count.
DepthImage depth_of_organized(const Eigen::Ref<const Vec3Array>& points, int height, int width,
                              const char* what = "points");

/// T_world_camera from [x, y, z, qx, qy, qz, qw]; throws std::invalid_argument naming `what` for a
/// non-finite value or a quaternion whose norm is off 1 by more than kUnitQuaternionTolerance (then
/// normalised).
Eigen::Isometry3d camera_pose(const Eigen::Ref<const Eigen::Matrix<double, 7, 1>>& pose,
                              const char* what = "T_world_camera");

/// Throws std::invalid_argument naming `what` unless T is finite and its linear part a rotation (orthonormal
/// to 1e-6, determinant +1).
void check_rigid(const Eigen::Isometry3d& T, const char* what = "T_world_camera");

}  // namespace graspmix
