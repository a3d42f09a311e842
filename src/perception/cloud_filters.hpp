#pragma once
// Cloud steps private to perception that prepare_cloud and segment_scene share: seeded RANSAC plane
// fitting and statistical outlier removal.
#include <cstdint>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <Eigen/Core>

namespace graspmix::detail {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

/// The dominant plane of `cloud` by RANSAC seeded with `seed` (inlier threshold `distance`, at most
/// `iterations`), refitted by least squares on its inliers and normalised ((a, b, c) unit), with the
/// inliers of the refined plane. False if RANSAC finds no model.
bool fit_plane(const Cloud::ConstPtr& cloud, double distance, int iterations, std::uint64_t seed,
               Eigen::VectorXf& coeffs, pcl::Indices& inliers);

/// Indices of the points PCL's StatisticalOutlierRemoval keeps (mean distance to the k nearest within
/// mean + std_ratio * std over the cloud).
pcl::Indices statistical_inliers(const Cloud::ConstPtr& cloud, int k, double std_ratio);

}  // namespace graspmix::detail
