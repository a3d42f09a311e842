#pragma once
// Point cloud files: PCD (ascii, binary, binary_compressed) and PLY (ascii, binary) through PCL's
// readers, and .npy (N, 3) arrays. Real files are organised (width x height with NaN holes), carry
// extra fields (rgb, intensity, ...) and an acquisition viewpoint: invalid points are dropped and
// counted, extra fields are listed but not loaded, the viewpoint is returned as a pose. Clouds merged
// from several cameras carry one viewpoint per point instead (PCL's PointWithViewpoint: vp_x vp_y vp_z).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "graspmix/core/types.hpp"

namespace graspmix {

/// A cloud read from a file (or made from arrays), with what the file said about it.
struct CloudData {
  Vec3Array points;   ///< (N, 3) finite points, metres, in the file's frame
  Vec3Array normals;  ///< (N, 3) when the file had normal_x/y/z for every kept point, else 0 rows
  /// (N, 3) the position of the camera that saw each kept point, from the fields vp_x vp_y vp_z
  /// (PCL's PointWithViewpoint), else 0 rows.
  Vec3Array viewpoints;
  /// The sensor pose [x, y, z, qx, qy, qz, qw] from the PCD VIEWPOINT / PLY camera element, in the
  /// cloud's frame (PCL's sensor_origin_ / sensor_orientation_); identity when the file had none.
  Eigen::Matrix<double, 7, 1> viewpoint = (Eigen::Matrix<double, 7, 1>() << 0, 0, 0, 0, 0, 0, 1).finished();
  bool has_viewpoint = false;           ///< true when the file gave a viewpoint other than the identity
  std::vector<std::string> fields;      ///< every field of the file, in file order (x, y, z, rgb, ...)
  std::uint32_t width = 0, height = 0;  ///< as in the header: height > 1 for organised clouds
  std::size_t n_invalid = 0;            ///< points dropped for a NaN or infinite coordinate
  std::string format;                   ///< "pcd ascii", "pcd binary", "pcd binary_compressed", "ply", "npy"
  std::string path;                     ///< where it came from
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

/// Writes float32 x y z (and normal_x normal_y normal_z when normals has rows, then vp_x vp_y vp_z
/// when viewpoints has rows: one camera position per point, PCL's PointWithViewpoint) as an
/// unorganised cloud. .pcd encodings: "ascii", "binary" (default), "binary_compressed"; .ply: "ascii"
/// or "binary" (vp_x vp_y vp_z as vertex properties). viewpoint (7) goes into the PCD header (PLY
/// files keep none). Throws std::invalid_argument.
void save_cloud(
    const std::string& path, const Vec3Array& points, const Vec3Array& normals = {},
    const std::string& encoding = "binary",
    const Eigen::Matrix<double, 7, 1>& viewpoint = (Eigen::Matrix<double, 7, 1>() << 0, 0, 0, 0, 0, 0, 1).finished(),
    const Vec3Array& viewpoints = {});

}  // namespace graspmix
