// Pinhole intrinsics, depth images, the intrinsics of an organized cloud and camera poses.
#include "graspmix/perception/camera.hpp"

#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace graspmix {

namespace {

constexpr int kMaxImageSide = 1'000'000;  // pixels: far beyond any sensor, small enough for int products

std::string number(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

void check_side(int n, const char* name) {
  if (n <= 0 || n > kMaxImageSide) {
    throw std::invalid_argument(std::string("camera: ") + name + " must be in [1, " + std::to_string(kMaxImageSide) +
                                "] pixels, got " + std::to_string(n));
  }
}

/// Least squares of y = slope x + offset over pairs (x, y), centred for accuracy; the sum of squared residuals.
struct LineFit {
  double slope = 0, offset = 0, sse = 0;
};

LineFit fit_line(const std::vector<double>& x, const std::vector<double>& y) {
  const auto n = static_cast<double>(x.size());
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < x.size(); ++i) mx += x[i], my += y[i];
  mx /= n;
  my /= n;
  double sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) sxx += (x[i] - mx) * (x[i] - mx), sxy += (x[i] - mx) * (y[i] - my);
  LineFit f;
  f.slope = sxx > 0 ? sxy / sxx : 0.0;
  f.offset = my - f.slope * mx;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double r = y[i] - (f.slope * x[i] + f.offset);
    f.sse += r * r;
  }
  return f;
}

}  // namespace

PinholeCamera::PinholeCamera(double fx, double fy, double cx, double cy, int width, int height)
    : fx_(fx), fy_(fy), cx_(cx), cy_(cy), width_(width), height_(height) {
  if (!(fx > 0) || !std::isfinite(fx))
    throw std::invalid_argument("camera: fx must be finite and > 0 px, got " + number(fx));
  if (!(fy > 0) || !std::isfinite(fy))
    throw std::invalid_argument("camera: fy must be finite and > 0 px, got " + number(fy));
  if (!std::isfinite(cx)) throw std::invalid_argument("camera: cx must be finite, got " + number(cx));
  if (!std::isfinite(cy)) throw std::invalid_argument("camera: cy must be finite, got " + number(cy));
  check_side(width, "width");
  check_side(height, "height");
}

Eigen::Matrix3d PinholeCamera::matrix() const {
  Eigen::Matrix3d K;
  K << fx_, 0, cx_, 0, fy_, cy_, 0, 0, 1;
  return K;
}

std::int64_t count_returns(const Eigen::Ref<const DepthImage>& depth, const char* what) {
  std::int64_t n = 0;
  for (Eigen::Index r = 0; r < depth.rows(); ++r)
    for (Eigen::Index c = 0; c < depth.cols(); ++c) {
      const double d = depth(r, c);
      if (d < 0) {
        throw std::invalid_argument(std::string(what) + ": pixel (row " + std::to_string(r) + ", column " +
                                    std::to_string(c) + ") has a negative depth (" + number(d) +
                                    " m); no return is NaN, 0 or +inf");
      }
      n += has_return(d) ? 1 : 0;
    }
  return n;
}

std::int64_t PinholeCamera::check_image(const Eigen::Ref<const DepthImage>& depth, const char* what) const {
  if (depth.rows() != height_ || depth.cols() != width_) {
    throw std::invalid_argument(std::string(what) + ": expected a " + std::to_string(height_) + " x " +
                                std::to_string(width_) + " image (the camera's height x width), got " +
                                std::to_string(depth.rows()) + " x " + std::to_string(depth.cols()));
  }
  return count_returns(depth, what);
}

Vec3Array PinholeCamera::back_project(const Eigen::Ref<const DepthImage>& depth, const char* what) const {
  check_image(depth, what);
  Vec3Array out(static_cast<Eigen::Index>(height_) * width_, 3);
  for (int v = 0; v < height_; ++v)
    for (int u = 0; u < width_; ++u) {
      const double d = depth(v, u);
      const Eigen::Vector3d p =
          has_return(d) ? back_project(u, v, d) : Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
      out.row(static_cast<Eigen::Index>(v) * width_ + u) = p.transpose();
    }
  return out;
}

DepthImage depth_of_organized(const Eigen::Ref<const Vec3Array>& points, int height, int width, const char* what) {
  check_side(height, "height");
  check_side(width, "width");
  if (points.rows() != static_cast<Eigen::Index>(height) * width) {
    throw std::invalid_argument(std::string(what) + ": an organized cloud of " + std::to_string(height) + " x " +
                                std::to_string(width) + " needs " + std::to_string(std::int64_t{height} * width) +
                                " rows (height * width), got " + std::to_string(points.rows()));
  }
  DepthImage depth(height, width);
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      const auto row = points.row(static_cast<Eigen::Index>(v) * width + u);
      depth(v, u) = row.allFinite() ? row.z() : std::numeric_limits<double>::quiet_NaN();
    }
  return depth;
}

PinholeFit fit_pinhole(const Eigen::Ref<const Vec3Array>& points, int height, int width, double max_rms_px,
                       const char* what) {
  const std::string w(what);
  check_side(height, "height");
  check_side(width, "width");
  if (!(max_rms_px > 0) || !std::isfinite(max_rms_px))
    throw std::invalid_argument(w + ": the largest RMS residual must be finite and > 0 px, got " + number(max_rms_px));
  if (points.rows() != static_cast<Eigen::Index>(height) * width) {
    throw std::invalid_argument(w + ": an organized cloud of " + std::to_string(height) + " x " +
                                std::to_string(width) + " needs " + std::to_string(std::int64_t{height} * width) +
                                " rows (height * width), got " + std::to_string(points.rows()));
  }
  // x / z against the column and y / z against the row of every valid pixel.
  std::vector<double> ax, ay, us, vs;
  for (auto* v : {&ax, &ay, &us, &vs}) v->reserve(static_cast<std::size_t>(points.rows()));
  std::vector<bool> column_seen(static_cast<std::size_t>(width)), row_seen(static_cast<std::size_t>(height));
  int n_columns = 0, n_rows = 0;
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) {
      const Eigen::Vector3d p = points.row(static_cast<Eigen::Index>(v) * width + u).transpose();
      if (!p.allFinite()) continue;  // no return
      if (!(p.z() > 0)) {
        throw std::invalid_argument(w + ": the point of pixel (row " + std::to_string(v) + ", column " +
                                    std::to_string(u) + ") has z = " + number(p.z()) +
                                    " <= 0: an organized cloud is in the sensor frame (z forward)");
      }
      ax.push_back(p.x() / p.z());
      ay.push_back(p.y() / p.z());
      us.push_back(u);
      vs.push_back(v);
      if (!column_seen[static_cast<std::size_t>(u)]) column_seen[static_cast<std::size_t>(u)] = true, ++n_columns;
      if (!row_seen[static_cast<std::size_t>(v)]) row_seen[static_cast<std::size_t>(v)] = true, ++n_rows;
    }
  if (n_columns < 2 || n_rows < 2) {
    throw std::invalid_argument(w + ": the intrinsics need valid points in two columns and two rows at least, got " +
                                std::to_string(n_columns) + " column(s) and " + std::to_string(n_rows) + " row(s) (" +
                                std::to_string(ax.size()) + " valid points)");
  }
  const LineFit fu = fit_line(ax, us), fv = fit_line(ay, vs);
  if (!(fu.slope > 0) || !(fv.slope > 0)) {
    throw std::invalid_argument(w + ": the fitted focal lengths (fx " + number(fu.slope) + ", fy " + number(fv.slope) +
                                ") are not positive: is the cloud in the sensor frame (x right, y down, z forward)?");
  }
  const auto n = static_cast<std::int64_t>(ax.size());
  const double rms = std::sqrt((fu.sse + fv.sse) / static_cast<double>(n));
  if (!(rms <= max_rms_px)) {
    throw std::invalid_argument(w +
                                ": not a pinhole image in the sensor frame: the fitted intrinsics leave an RMS "
                                "reprojection residual of " +
                                number(rms) + " px (at most " + number(max_rms_px) +
                                "); is the cloud organized, in the sensor frame?");
  }
  return {PinholeCamera(fu.slope, fv.slope, fu.offset, fv.offset, width, height), rms, n};
}

Eigen::Isometry3d camera_pose(const Eigen::Ref<const Eigen::Matrix<double, 7, 1>>& pose, const char* what) {
  const std::string w(what);
  if (!pose.allFinite()) throw std::invalid_argument(w + ": the pose [x, y, z, qx, qy, qz, qw] has a non-finite value");
  const double n = pose.tail<4>().norm();
  if (!(std::abs(n - 1.0) <= kUnitQuaternionTolerance)) {
    throw std::invalid_argument(w + ": [qx, qy, qz, qw] = [" + number(pose[3]) + ", " + number(pose[4]) + ", " +
                                number(pose[5]) + ", " + number(pose[6]) + "] is not a unit quaternion (norm " +
                                number(n) + ")");
  }
  const Eigen::Quaterniond q(pose[6] / n, pose[3] / n, pose[4] / n, pose[5] / n);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = pose.head<3>();
  return T;
}

void check_rigid(const Eigen::Isometry3d& T, const char* what) {
  const Eigen::Matrix3d R = T.linear();
  if (!T.matrix().allFinite()) throw std::invalid_argument(std::string(what) + ": the pose has a non-finite value");
  const double off = (R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  if (!(off <= 1e-6) || !(R.determinant() > 0)) {
    throw std::invalid_argument(std::string(what) +
                                ": the rotation is not orthonormal with determinant +1 (|R^T R - I| = " + number(off) +
                                ", det " + number(R.determinant()) + ")");
  }
}

}  // namespace graspmix
