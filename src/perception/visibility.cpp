// The visibility model: pinhole views (depth images, organized clouds) and the rule that combines views.
#include "graspmix/perception/visibility.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "perception/visibility_view.hpp"

namespace graspmix {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

/// A depth image and its camera: the pixel a point projects to holds the depth of the surface along its ray.
class PinholeView final : public detail::VisibilityView {
 public:
  PinholeView(ViewInfo info, DepthImage depth, const PinholeCamera& camera, const Eigen::Isometry3d& T_world_camera)
      : VisibilityView(std::move(info)),
        depth_(std::move(depth)),
        camera_(camera),
        R_camera_world_(T_world_camera.linear().transpose()),
        t_camera_world_(-(R_camera_world_ * T_world_camera.translation())) {}

  double signed_distance(const Eigen::Vector3d& p, bool no_return_is_free) const override {
    return distance(p, no_return_is_free);
  }
  void signed_distances(const Eigen::Ref<const Vec3Array>& points, bool no_return_is_free, double* out) const override {
    for (Eigen::Index i = 0; i < points.rows(); ++i) out[i] = distance(points.row(i).transpose(), no_return_is_free);
  }

 private:
  double distance(const Eigen::Vector3d& p, bool no_return_is_free) const {
    const Eigen::Vector3d q = R_camera_world_ * p + t_camera_world_;
    int column = 0, row = 0;
    if (!camera_.pixel(camera_.project(q), column, row)) return kNaN;  // behind the camera or outside the image
    const double d = depth_(row, column);
    if (std::isnan(d)) return no_return_is_free ? kInf : kNaN;
    // The surface at depth d along p's own ray lies at range |q| d / z.
    return q.norm() * (d / q.z() - 1.0);
  }

  DepthImage depth_;  ///< metres along z, NaN where no return
  PinholeCamera camera_;
  Eigen::Matrix3d R_camera_world_;
  Eigen::Vector3d t_camera_world_;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// A pinhole view of a depth image, checked and taken over (no return made NaN in place); fit_rms_px and the start
/// time go into its ViewInfo.
std::shared_ptr<const detail::VisibilityView> make_pinhole_view(DepthImage image, const PinholeCamera& camera,
                                                                const Eigen::Isometry3d& T_world_camera,
                                                                const VisibilitySettings& settings, double fit_rms_px,
                                                                std::chrono::steady_clock::time_point t0) {
  check_rigid(T_world_camera, "T_world_camera");
  if (image.rows() != camera.height() || image.cols() != camera.width()) camera.check_image(image, "depth");  // throws
  ViewInfo info;
  // One pass: the returns counted and every other pixel made NaN, but for a negative depth, check_image's error.
  bool negative = false;
  for (Eigen::Index i = 0; i < image.size(); ++i) {
    double& d = image.data()[i];
    negative |= d < 0;
    if (has_return(d))
      ++info.n_returns;
    else if (!(d < 0))
      d = kNaN;
  }
  if (negative) camera.check_image(image, "depth");  // throws, naming the first negative pixel
  if (info.n_returns == 0) throw std::invalid_argument("depth: no pixel has a return (every depth is NaN, 0 or inf)");
  if (static_cast<double>(image.size()) > static_cast<double>(settings.max_pixels)) {
    throw std::invalid_argument("depth: " + std::to_string(image.size()) +
                                " pixels, more than max_pixels = " + std::to_string(settings.max_pixels));
  }
  info.kind = ViewKind::Pinhole;
  info.T_world_sensor = T_world_camera;
  info.camera = camera;
  info.width = camera.width();
  info.height = camera.height();
  info.fit_rms_px = fit_rms_px;
  info.seconds = seconds_since(t0);
  return std::make_shared<PinholeView>(info, std::move(image), camera, T_world_camera);
}

bool same_settings(const VisibilitySettings& a, const VisibilitySettings& b) {
  return a.surface_tolerance == b.surface_tolerance && a.angular_resolution == b.angular_resolution &&
         a.no_return_is_free == b.no_return_is_free && a.max_fit_rms == b.max_fit_rms && a.max_pixels == b.max_pixels;
}

}  // namespace

void check_visibility_settings(const VisibilitySettings& s) {
  const std::string w = "VisibilitySettings: ";
  if (!(s.surface_tolerance >= 0) || !std::isfinite(s.surface_tolerance))
    throw std::invalid_argument(w + "surface_tolerance must be finite and >= 0 (m), got " +
                                std::to_string(s.surface_tolerance));
  if (!(s.angular_resolution > 0 && s.angular_resolution <= 0.5))
    throw std::invalid_argument(w + "angular_resolution must be in (0, 0.5] rad, got " +
                                std::to_string(s.angular_resolution));
  if (!(s.max_fit_rms > 0) || !std::isfinite(s.max_fit_rms))
    throw std::invalid_argument(w + "max_fit_rms must be finite and > 0 (px), got " + std::to_string(s.max_fit_rms));
  if (s.max_pixels <= 0) throw std::invalid_argument(w + "max_pixels must be > 0, got " + std::to_string(s.max_pixels));
}

VisibilityModel::VisibilityModel(const VisibilitySettings& settings) : settings_(settings) {
  check_visibility_settings(settings_);
}

VisibilityModel VisibilityModel::from_depth(DepthImage depth, const PinholeCamera& camera,
                                            const Eigen::Isometry3d& T_world_camera,
                                            const VisibilitySettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  VisibilityModel model(settings);
  model.views_.push_back(make_pinhole_view(std::move(depth), camera, T_world_camera, settings, 0.0, t0));
  return model;
}

VisibilityModel VisibilityModel::from_organized(const Eigen::Ref<const Vec3Array>& points, int height, int width,
                                                const Eigen::Isometry3d& T_world_camera,
                                                const VisibilitySettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  VisibilityModel model(settings);
  const PinholeFit fit = fit_pinhole(points, height, width, settings.max_fit_rms, "points");
  model.views_.push_back(make_pinhole_view(depth_of_organized(points, height, width), fit.camera, T_world_camera,
                                           settings, fit.rms_px, t0));
  return model;
}

VisibilityModel VisibilityModel::from_points(const Eigen::Ref<const Vec3Array>& points,
                                             const Eigen::Vector3d& viewpoint, const VisibilitySettings& settings) {
  VisibilityModel model(settings);
  model.views_.push_back(detail::make_spherical_view(points, viewpoint, settings));
  return model;
}

VisibilityModel VisibilityModel::from_views(const Eigen::Ref<const Vec3Array>& points,
                                            const Eigen::Ref<const Vec3Array>& viewpoints,
                                            const VisibilitySettings& settings) {
  const Eigen::Index n = viewpoints.rows();
  if (n != 1 && n != points.rows()) {
    throw std::invalid_argument("viewpoints: expected 1 or " + std::to_string(points.rows()) +
                                " rows (one per point), got " + std::to_string(n));
  }
  if (!viewpoints.allFinite()) throw std::invalid_argument("viewpoints: contains NaN or infinite values");
  if (n == 1) return from_points(points, viewpoints.row(0).transpose(), settings);
  // The rows of each distinct viewpoint, in the order the viewpoints first appear.
  std::map<std::array<double, 3>, std::vector<Eigen::Index>> rows;
  std::vector<std::array<double, 3>> order;
  for (Eigen::Index i = 0; i < n; ++i) {
    const std::array<double, 3> key{viewpoints(i, 0), viewpoints(i, 1), viewpoints(i, 2)};
    auto [it, inserted] = rows.try_emplace(key);
    if (inserted) order.push_back(key);
    it->second.push_back(i);
  }
  VisibilityModel model(settings);
  for (const auto& key : order) {
    const auto& r = rows[key];
    Vec3Array seen(static_cast<Eigen::Index>(r.size()), 3);
    for (std::size_t j = 0; j < r.size(); ++j) seen.row(static_cast<Eigen::Index>(j)) = points.row(r[j]);
    model.add_view(from_points(seen, Eigen::Vector3d(key[0], key[1], key[2]), settings));
  }
  return model;
}

void VisibilityModel::add_view(const VisibilityModel& other) {
  if (!same_settings(settings_, other.settings_)) {
    throw std::invalid_argument(
        "add_view: the other model's settings differ from this one's (build every view with the same "
        "VisibilitySettings)");
  }
  // A copy first: adding a model to itself doubles its views without invalidating the range.
  const auto theirs = other.views_;
  views_.insert(views_.end(), theirs.begin(), theirs.end());
}

double VisibilityModel::signed_distance(const Eigen::Vector3d& p) const {
  const double t = settings_.surface_tolerance;
  double surface = kNaN, front = -kInf, behind = kNaN;
  for (const auto& view : views_) {
    const double d = view->signed_distance(p, settings_.no_return_is_free);
    if (std::isnan(d)) continue;
    if (std::abs(d) <= t) {
      if (std::isnan(surface) || std::abs(d) < std::abs(surface)) surface = d;
    } else if (d > t) {
      front = std::max(front, d);
    } else if (std::isnan(behind) || d > behind) {
      behind = d;
    }
  }
  if (!std::isnan(surface)) return surface;
  if (front > t) return front;
  return behind;
}

SpaceState VisibilityModel::state(const Eigen::Vector3d& p) const {
  return state_of_distance(signed_distance(p), settings_.surface_tolerance);
}

std::vector<SpaceState> VisibilityModel::classify(const Eigen::Ref<const Vec3Array>& points) const {
  const Eigen::VectorXd d = signed_distances(points);  // state(p) is the state of p's distance
  std::vector<SpaceState> out(static_cast<std::size_t>(points.rows()));
  for (Eigen::Index i = 0; i < d.size(); ++i)
    out[static_cast<std::size_t>(i)] = state_of_distance(d[i], settings_.surface_tolerance);
  return out;
}

Eigen::VectorXd VisibilityModel::signed_distances(const Eigen::Ref<const Vec3Array>& points) const {
  Eigen::VectorXd out(points.rows());
  const Eigen::Index n = points.rows();
  constexpr Eigen::Index kChunk = 1024;  // rows a thread takes at a time
  const Eigen::Index chunks = (n + kChunk - 1) / kChunk;
#pragma omp parallel for schedule(static) if (n >= 4096)
  for (Eigen::Index c = 0; c < chunks; ++c) {
    const Eigen::Index b = c * kChunk;
    signed_distances_into(points.middleRows(b, std::min(kChunk, n - b)), out.data() + b);
  }
  return out;
}

void VisibilityModel::signed_distances_into(const Eigen::Ref<const Vec3Array>& points, double* out) const {
  // One view's distance is the model's (signed_distance's rule picks the only one there is): the view's own loop.
  if (views_.size() == 1) {
    views_.front()->signed_distances(points, settings_.no_return_is_free, out);
    return;
  }
  for (Eigen::Index i = 0; i < points.rows(); ++i) out[i] = signed_distance(points.row(i).transpose());
}

const ViewInfo& VisibilityModel::view(int i) const {
  if (i < 0 || i >= n_views()) {
    throw std::out_of_range("view: index " + std::to_string(i) + " out of range (" + std::to_string(n_views()) +
                            " views)");
  }
  return views_[static_cast<std::size_t>(i)]->info();
}

}  // namespace graspmix
