#pragma once
// Point cloud files: PCD (ascii, binary, binary_compressed) and PLY (ascii, binary little and big endian)
// through graspmix's own readers and writers, which read them as PCL's do (without linking pcl_io), and .npy
// (N, 3) arrays. Real files are organised (width x height with NaN holes), carry extra fields (rgb, intensity,
// ...) and an acquisition viewpoint: invalid points are dropped and counted, and each kept point's pixel is
// kept (`pixels`, `organized_grid`); extra fields are listed but not loaded, the viewpoint is returned as a
// pose. Clouds merged from several cameras carry one viewpoint per point instead (PCL's PointWithViewpoint:
// vp_x vp_y vp_z).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "graspmix/core/types.hpp"

namespace graspmix {

/// A cloud read from a file (or made from arrays), with what the file said about it.
struct CloudData {
  Vec3Array points;   ///< (N, 3) finite points, metres, in the file's frame
  Vec3Array normals;  ///< (N, 3) when the file had normal_x/y/z for every kept point, else 0 rows
  /// (N, 3) the position of the camera that saw each kept point, from the fields vp_x vp_y vp_z
  /// (PCL's PointWithViewpoint), else 0 rows.
  Vec3Array viewpoints;
  /// The sensor pose [x, y, z, qx, qy, qz, qw] from the PCD VIEWPOINT, in the cloud's frame (PCL's
  /// sensor_origin_ / sensor_orientation_); identity when the file had none, and for PLY files (whose camera
  /// element PCL 1.13's reader did not return either).
  Eigen::Matrix<double, 7, 1> viewpoint = (Eigen::Matrix<double, 7, 1>() << 0, 0, 0, 0, 0, 0, 1).finished();
  bool has_viewpoint = false;           ///< true when the file gave a viewpoint other than the identity
  std::vector<std::string> fields;      ///< every field of the file, in file order (x, y, z, rgb, ...)
  std::uint32_t width = 0, height = 0;  ///< as in the header: height > 1 for organised clouds
  /// For an organised file (height > 1): the pixel v * width + u of each kept point in the width x height
  /// grid, row v, column u (points[k] was at pixels[k]); empty for an unorganised one (height 1).
  Eigen::Matrix<std::int64_t, Eigen::Dynamic, 1> pixels;
  std::size_t n_invalid = 0;  ///< points dropped for a NaN or infinite coordinate
  std::string format;         ///< "pcd ascii", "pcd binary", "pcd binary_compressed", "ply", "npy"
  std::string path;           ///< where it came from
};

/// Reads .pcd, .ply or .npy (by extension, case-insensitive). Throws std::invalid_argument naming
/// the file and the problem: missing, empty, wrong header, truncated data, no x/y/z fields, no
/// points, or no finite point.
CloudData load_cloud(const std::string& path);

/// Drops rows with a non-finite coordinate (and normals that are not finite for every kept row)
/// exactly as load_cloud does; viewpoints (N, 3), when given, follow the kept rows and must be finite
/// on every kept row (throws otherwise); `source` names the data in errors.
CloudData cloud_from_arrays(const RowMatrixXd& points, const RowMatrixXd& normals = {},
                            const std::string& source = "points", const RowMatrixXd& viewpoints = {});

/// An organised cloud's points on its image grid: (height * width, 3), row v * width + u the point at pixel
/// (u, v), NaN where the file had no finite point. Throws std::invalid_argument naming the cloud's path for
/// an unorganised cloud (height 1) or pixels that do not fit its grid.
Vec3Array organized_grid(const CloudData& cloud);

/// organized_grid written into `out` ((height * width) * 3 doubles, row-major), with T_file_camera each point
/// mapped from the file's frame into the frame of a camera at that pose (p -> T_file_camera^-1 p; NaN stays NaN):
/// one pass, the grid a camera's driver gives from a file whose VIEWPOINT is that camera's pose. Throws as
/// organized_grid does.
void organized_grid_into(const CloudData& cloud, double* out,
                         const std::optional<Eigen::Isometry3d>& T_file_camera = std::nullopt);

/// Writes float32 x y z (and normal_x normal_y normal_z when normals has rows, then vp_x vp_y vp_z
/// when viewpoints has rows: one camera position per point, PCL's PointWithViewpoint). .pcd encodings:
/// "ascii", "binary" (default), "binary_compressed"; .ply: "ascii" or "binary" little endian (vp_x vp_y vp_z
/// as vertex properties). viewpoint (7) goes into the PCD header (PLY files keep none).
/// width x height: 0 x 0 (default) writes an unorganised cloud of finite points; height > 1 an organised
/// one: points has width * height rows, v * width + u the pixel (u, v), and a row with NaN is a hole (its
/// normals and viewpoints may be NaN too). PLY has no standard image grid, so an organised cloud is written
/// as .pcd only. Throws std::invalid_argument.
void save_cloud(
    const std::string& path, const Vec3Array& points, const Vec3Array& normals = {},
    const std::string& encoding = "binary",
    const Eigen::Matrix<double, 7, 1>& viewpoint = (Eigen::Matrix<double, 7, 1>() << 0, 0, 0, 0, 0, 0, 1).finished(),
    const Vec3Array& viewpoints = {}, std::uint32_t width = 0, std::uint32_t height = 0);

}  // namespace graspmix
