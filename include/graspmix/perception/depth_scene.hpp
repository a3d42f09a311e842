#pragma once
// The scene model of one depth camera's view as its driver gives it: a depth image with its intrinsics, or an
// organized cloud in the sensor frame, and the camera's pose in the world. The same scene (support plane, objects)
// as segment_scene's on the same view's points (segmentation.hpp: every rule and setting), made cheaper by the
// image's structure:
//  1. subsampling in image space: blocks of image_stride x image_stride pixels (0: the largest block whose side at
//     the median depth of the returns is within half a voxel_size, so that the voxel grid keeps its points: 1 for a
//     640 x 480 camera 0.8 m away at 3 mm, 2 at 0.4 m), each block one point, the mean of its returns that
//     lie within voxel_size of their median depth (one surface, not a blend across an occluding edge, and not
//     biased towards the camera under depth noise as the nearest return would be); the voxel grid then sees a
//     few times fewer points;
//  2. the support plane, objects and rules of segment_scene on those points in the world frame, the camera their
//     one viewpoint; the plane searched for (or a given one turned towards the camera) on coarser blocks
//     (plane_image_stride pixels: RANSAC and the rule need the table's extent, not its every point), the objects
//     then made of the fine blocks above it and the table's noise measured on the coarse ones on it (each set
//     voxelised on its own);
//  3. the visibility model straight from the full-resolution image (VisibilityModel::from_depth): no range image
//     to bin, and the camera's own resolution, no-return pixels and image border. The join rule alone judges gaps
//     on the image pooled to visibility_resolution (made only when the rule has two pieces to judge; each pixel
//     the nearest return within that angle, as a bin of segment_scene's range images holds its nearest point):
//     at the camera's own resolution the sensor's lateral noise shows slivers of table through the shadow between
//     an object's pieces, and the pieces stayed apart (one view, development objects, GMM, 300 attempts: 75.3%
//     with the sharp image, 80.3% pooled, 78.0% for segment_scene on the same views' points; docs/one-view.md).
// Segmentation::sources are pixel indices (row v * width + u) of the full image: each object point's pixel.
#include <optional>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "graspmix/core/types.hpp"
#include "graspmix/perception/camera.hpp"
#include "graspmix/perception/segmentation.hpp"

namespace graspmix {

/// The scene of a depth image (camera.height() x camera.width(), metres along z; NaN, 0, +inf = no return) taken
/// by `camera` at T_world_camera; points and plane in the world frame. Throws std::invalid_argument for an image
/// of another size, a negative depth, no return at all, a pose that is not rigid, bad settings, and as
/// segment_scene does (no object above the plane, ...).
Segmentation segment_depth(const Eigen::Ref<const DepthImage>& depth, const PinholeCamera& camera,
                           const Eigen::Isometry3d& T_world_camera, const SegmentationSettings& settings = {},
                           const std::optional<Eigen::Vector4d>& plane = std::nullopt);

/// The scene of an organized cloud (height * width, 3) in the sensor frame (x right, y down, z forward; row
/// v * width + u; NaN rows = no return) from a camera at T_world_camera: the intrinsics are fitted
/// (fit_pinhole, at most max_fit_rms px of residual), the visibility model built from the points' z, and each
/// block's point is the mean of the cloud's own points (not re-projected depths). Throws std::invalid_argument
/// as fit_pinhole and segment_depth do.
Segmentation segment_organized(const Eigen::Ref<const Vec3Array>& points, int height, int width,
                               const Eigen::Isometry3d& T_world_camera, const SegmentationSettings& settings = {},
                               const std::optional<Eigen::Vector4d>& plane = std::nullopt,
                               double max_fit_rms = VisibilitySettings{}.max_fit_rms);

/// segment_organized with the intrinsics known (e.g. fitted once already, PinholeFit::camera): the cloud has
/// camera.height() * camera.width() rows; each block's point is the mean of the cloud's own points. Throws
/// std::invalid_argument as segment_organized does (but for the fit).
Segmentation segment_organized(const Eigen::Ref<const Vec3Array>& points, const PinholeCamera& camera,
                               const Eigen::Isometry3d& T_world_camera, const SegmentationSettings& settings = {},
                               const std::optional<Eigen::Vector4d>& plane = std::nullopt);

/// The block side (pixels) segment_depth uses for `depth`: settings' image_stride when > 0, else the largest
/// block whose side at the median depth of the returns is within half a voxel_size (1 when voxel_size is 0).
int image_stride(const Eigen::Ref<const DepthImage>& depth, const PinholeCamera& camera,
                 const SegmentationSettings& settings);

}  // namespace graspmix
