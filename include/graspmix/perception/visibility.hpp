#pragma once
// What the cameras saw, as a model of space (docs/design.md, "Scenes"): for every view, any point of space is
// seen free (in front of the surface the view observed along the point's ray), surface (within
// surface_tolerance of it) or unseen (behind it, outside the image, or on a ray that returned nothing).
//
// A view is an image of ranges around a viewpoint, so a query is O(1): project the point, read its pixel.
//   - from_depth: a depth image with its pinhole intrinsics and T_world_camera;
//   - from_organized: an organized cloud in the sensor frame (the intrinsics fitted to it, fit_pinhole);
//   - from_points: an unorganized cloud in the world frame and the viewpoint it was seen from, binned into
//     a spherical range image around the viewpoint (pcl::RangeImage), each bin the nearest range in it.
// Along a pinhole pixel's ray the observed surface is at the pixel's depth (a surface parallel to the image
// plane across the pixel's footprint); along a spherical bin's ray at the bin's range.
//
// Views combine (add_view) by this rule: a point is Surface if any view has it within surface_tolerance of
// its surface; else SeenFree if any view sees it in front; else Unseen. A hand may use space one camera saw
// free even if another camera could not see it, and what any camera saw as surface stays surface.
//
// OccupancyMap (grasp/occupancy.hpp) holds the same information for a region, voxelised; this model keeps
// the images, so it answers at the sensor's resolution anywhere, and with the signed distance to the surface.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "graspmix/core/types.hpp"
#include "graspmix/perception/camera.hpp"

namespace graspmix {

enum class SpaceState : std::uint8_t { SeenFree = 0, Surface = 1, Unseen = 2 };

struct VisibilitySettings {
  /// m: a point whose range is within this of the observed surface's along its ray is Surface (>= 0): a few
  /// times the depth noise (the simulated cameras' is 1 mm), the occupancy map's default cell.
  double surface_tolerance = 0.005;
  /// rad: the bin size of from_points' spherical range image, in (0, 0.5]. 0.005 rad is 3 mm at 0.6 m, the
  /// clean-up's voxel at a table-top camera's distance: finer bins leave holes between the points (unseen),
  /// coarser ones blur the silhouettes (a bin holds its nearest point, so the blur is towards unseen).
  double angular_resolution = 0.005;
  /// A pixel of a depth image or an organized cloud with no return (NaN, 0, +inf): true, the sensor saw
  /// nothing up to its range, so the pixel's whole ray is seen free; false, the pixel says nothing (unseen).
  /// Dark, shiny and far surfaces return nothing too, hence the default. from_points' empty bins are
  /// always unseen: an unorganized cloud keeps no record of the rays that returned nothing.
  bool no_return_is_free = false;
  /// px: from_organized refuses a cloud whose fitted intrinsics leave a larger RMS reprojection residual.
  double max_fit_rms = 0.5;
  /// The largest image one view may hold (pixels): bounds from_points' image at a fine angular resolution (PCL
  /// holds 32 bytes a pixel; the whole sphere of directions is 0.8 million pixels at 0.005 rad, 20 million at
  /// 0.001 rad) and a depth image's size.
  std::int64_t max_pixels = 10'000'000;
};

/// How a view was made.
enum class ViewKind : std::uint8_t { Pinhole = 0, Spherical = 1 };

/// What a view is (diagnostics; the images stay inside the model).
struct ViewInfo {
  ViewKind kind = ViewKind::Pinhole;
  /// The sensor's pose in the world: a pinhole camera's (x right, y down, z forward); a spherical image's
  /// viewpoint, its z towards the points' bounding sphere's centre.
  Eigen::Isometry3d T_world_sensor = Eigen::Isometry3d::Identity();
  std::optional<PinholeCamera> camera;  ///< the intrinsics of a pinhole view (fitted by from_organized)
  int width = 0, height = 0;            ///< image size in pixels (a spherical image cropped to its points)
  std::int64_t n_returns = 0;           ///< pixels with a return
  double angular_resolution = 0.0;      ///< rad, spherical views
  double fit_rms_px = 0.0;              ///< px, from_organized's fit residual (0 otherwise)
  double seconds = 0.0;                 ///< s, wall time to build the view
};

namespace detail {
class VisibilityView;  // one view's image and projection (src/perception/visibility_view.hpp)
}  // namespace detail

class VisibilityModel {
 public:
  /// A model of no view (every point Unseen) to add views to; throws std::invalid_argument for bad settings.
  explicit VisibilityModel(const VisibilitySettings& settings = {});
  /// One view: a depth image (camera.height() x camera.width(), metres along z; NaN, 0, +inf = no return)
  /// from a camera at T_world_camera. Throws std::invalid_argument for an image of another size, a negative
  /// depth, an image with no return at all, a pose that is not rigid, or bad settings. The model keeps the image:
  /// a temporary or a std::move'd image is taken over, anything else copied once.
  static VisibilityModel from_depth(DepthImage depth, const PinholeCamera& camera,
                                    const Eigen::Isometry3d& T_world_camera, const VisibilitySettings& settings = {});
  /// One view: an organized cloud (height * width, 3) in the sensor frame (row v * width + u, NaN rows = no
  /// return); its intrinsics are fitted (fit_pinhole, max_fit_rms) and its depths are the points' z.
  /// Throws std::invalid_argument as fit_pinhole and from_depth do.
  static VisibilityModel from_organized(const Eigen::Ref<const Vec3Array>& points, int height, int width,
                                        const Eigen::Isometry3d& T_world_camera,
                                        const VisibilitySettings& settings = {});
  /// One view: an unorganized cloud (N, 3) in the world frame seen from `viewpoint` (NaN rows are skipped),
  /// as a spherical range image at settings.angular_resolution. Throws std::invalid_argument for no finite
  /// point away from the viewpoint, a non-finite viewpoint, or an image of more than max_pixels.
  static VisibilityModel from_points(const Eigen::Ref<const Vec3Array>& points, const Eigen::Vector3d& viewpoint,
                                     const VisibilitySettings& settings = {});

  /// Every view of an unorganized cloud (N, 3) in the world frame: `viewpoints` is one row (every point seen
  /// from there) or N rows (the camera that saw each point); the rows seen from one viewpoint make one
  /// from_points view. Throws std::invalid_argument for another number of rows, no viewpoint, a non-finite
  /// viewpoint, and as from_points does.
  static VisibilityModel from_views(const Eigen::Ref<const Vec3Array>& points,
                                    const Eigen::Ref<const Vec3Array>& viewpoints,
                                    const VisibilitySettings& settings = {});

  /// Adds the views of `other` (shared, not copied). Throws std::invalid_argument when other's settings
  /// differ from this model's (its views would be judged by another tolerance).
  void add_view(const VisibilityModel& other);

  /// The state of point p (world frame) under the rule of the header's comment. (Named apart from the batch
  /// classify: an Eigen expression converts to a point and to an array alike, so overloads would be ambiguous.)
  SpaceState state(const Eigen::Vector3d& p) const;
  /// The state of every row of points (N, 3), in parallel (OpenMP).
  std::vector<SpaceState> classify(const Eigen::Ref<const Vec3Array>& points) const;
  /// The signed distance (m) along p's ray from p to the observed surface, positive in front of it, chosen
  /// over the views by the same rule (the nearest surface within tolerance; else the largest distance in
  /// front; else the least behind), so that state(p) is the state of this distance: |d| <= tolerance is
  /// Surface, d > tolerance SeenFree, else Unseen. +inf on a no-return ray taken as free; NaN where no view
  /// says anything (outside every image, or no return).
  double signed_distance(const Eigen::Vector3d& p) const;
  /// signed_distance of every row of points (N, 3), in parallel (OpenMP).
  Eigen::VectorXd signed_distances(const Eigen::Ref<const Vec3Array>& points) const;
  /// The same on the calling thread into out (N values): for callers that spread their own work over threads.
  void signed_distances_into(const Eigen::Ref<const Vec3Array>& points, double* out) const;

  int n_views() const { return static_cast<int>(views_.size()); }
  /// What view i is (0 <= i < n_views()); throws std::out_of_range otherwise.
  const ViewInfo& view(int i) const;
  const VisibilitySettings& settings() const { return settings_; }

 private:
  VisibilitySettings settings_;
  std::vector<std::shared_ptr<const detail::VisibilityView>> views_;
};

/// The state a signed distance d (m) stands for at tolerance t: Surface for |d| <= t, SeenFree for d > t,
/// Unseen for d < -t or NaN.
inline SpaceState state_of_distance(double d, double t) {
  if (d > t) return SpaceState::SeenFree;
  if (d >= -t) return SpaceState::Surface;
  return SpaceState::Unseen;  // behind, or NaN
}

/// Throws std::invalid_argument naming the field unless the settings are in range.
void check_visibility_settings(const VisibilitySettings& s);

}  // namespace graspmix
