#pragma once
// Scene clean-up before features: crop box, voxel-grid down-sampling, statistical outlier removal and
// removal of the dominant support plane (RANSAC). Each step can be switched off. The plane is kept
// in the result because the collision expert keeps hands out of the table.
#include <cstddef>
#include <cstdint>
#include <limits>

#include <Eigen/Core>

#include "graspmix/core/types.hpp"

namespace graspmix {

struct CleanupSettings {
  bool crop = false;  ///< keep only points inside [crop_min, crop_max] (metres, the cloud's frame)
  Eigen::Vector3d crop_min = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  Eigen::Vector3d crop_max = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  /// Voxel-grid leaf size (m); every occupied voxel becomes the centroid of its points. 0 = off.
  /// Demonstration and query clouds must share it (curvatures depend on density).
  double voxel_size = 0.003;
  bool remove_outliers = true;      ///< PCL StatisticalOutlierRemoval
  int outlier_neighbours = 20;      ///< k of the mean-distance statistic
  double outlier_std_ratio = 2.0;   ///< drop points whose mean k-distance exceeds mean + ratio * std
  bool remove_plane = true;         ///< find the dominant plane by RANSAC and remove it
  double plane_distance = 0.005;    ///< RANSAC inlier threshold (m)
  int plane_max_iterations = 1000;  ///< RANSAC iterations
  /// A plane counts as the support only with at least this fraction of the (cleaned) points;
  /// otherwise nothing is removed and plane_found is false.
  double plane_min_fraction = 0.2;
  bool remove_below_plane = true;  ///< also drop points on the far side of the plane from the object
  std::uint64_t seed = 0;          ///< seeds RANSAC (PCL's own generators are reseeded with it)
};

struct CleanupResult {
  Vec3Array points;         ///< the object points that remain
  Eigen::VectorXi indices;  ///< for every remaining point, its input row (-1 when voxel-averaged)
  /// for every remaining point, the input row whose per-point data (camera viewpoint, camera index) it
  /// carries: its own row, or for a voxel centroid the row of the input point nearest to it in its voxel.
  /// Never -1: per-point data survive every step, indexed as data[sources].
  Eigen::VectorXi sources;
  /// Plane a x + b y + c z + d = 0 with (a, b, c) unit and pointing to the side the object is on.
  Eigen::Vector4d plane = Eigen::Vector4d::Zero();
  bool plane_found = false;
  std::size_t n_input = 0, n_after_crop = 0, n_after_voxel = 0, n_after_outliers = 0;
  std::size_t n_plane_inliers = 0, n_output = 0;
  double seconds = 0.0;  ///< wall time of the whole clean-up
};

/// Runs the enabled steps in the order crop, voxel grid, outliers, plane. Throws
/// std::invalid_argument on bad settings, non-finite points, or when no point survives.
CleanupResult prepare_cloud(const Vec3Array& points, const CleanupSettings& settings = {});

}  // namespace graspmix
