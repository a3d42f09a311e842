#pragma once
// Cloud steps private to perception that prepare_cloud and segment_scene share: the voxel grid, seeded
// RANSAC plane fitting and statistical outlier removal.
#include <cstdint>
#include <memory>
#include <vector>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <Eigen/Core>

namespace graspmix::detail {

using Cloud = pcl::PointCloud<pcl::PointXYZ>;

/// A voxel grid's centroids and the voxel of every input point (its centroid's row).
struct VoxelCells {
  Cloud::Ptr centroids;
  std::vector<int> voxel_of_point;
};

/// pcl::VoxelGrid's filter (a cubic leaf, every point finite, no minimum per voxel) in one pass that also
/// yields each point's voxel: the same cell index of every point (float arithmetic as PCL's), the same
/// integer sort of (cell, row) pairs, so the centroids are PCL's bit for bit (float sums in the same order),
/// one per occupied cell in increasing cell index. Throws std::invalid_argument when the cell index would
/// overflow 32 bits (PCL would warn and return the cloud unfiltered); callers check this first with a
/// message of their own.
VoxelCells voxel_grid(const Cloud& cloud, float leaf);

/// Connected components of `cloud` under "closer than tolerance" (pcl::EuclideanClusterExtraction's clusters
/// with a kd-tree search: float squared distances < float(tolerance^2), every size kept): each cluster's
/// indices in increasing order, the clusters by their lowest index (PCL's seed order). A uniform grid of
/// cell tolerance and a union-find instead of a tree; PCL's own when the cloud spans too many cells.
std::vector<std::vector<int>> euclidean_clusters(const Cloud::ConstPtr& cloud, double tolerance);

/// pcl::KdTreeFLANN's radiusSearch among one cloud's own points, by a uniform grid of cells a little wider than
/// the radius: near(i, out) gives the rows of every point whose float squared distance to point i (FLANN's: x, then
/// y, then z) is below float(radius^2), i itself included, in increasing order; PCL's tree where the cloud spans too
/// many cells or holds a non-finite point.
class RadiusSearch {
 public:
  RadiusSearch(const Cloud::ConstPtr& cloud, double radius);
  ~RadiusSearch();
  void near(int i, std::vector<int>& out) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The plane model's point tests (count, selection) fit_plane uses: Fast, a cheaper form that passes the same
/// points (bit for bit: cloud_filters.cpp is built without floating-point contraction); Stock, PCL's own
/// (the reference the tests hold Fast to).
enum class PlaneTests { Fast, Stock };

/// The dominant plane of `cloud` by RANSAC seeded with `seed` (inlier threshold `distance`, at most
/// `iterations`), refitted by least squares on its inliers and normalised ((a, b, c) unit), with the
/// inliers of the refined plane. False if RANSAC finds no model. PCL's RANSAC and plane model, with the
/// model's point tests as `tests` says.
bool fit_plane(const Cloud::ConstPtr& cloud, double distance, int iterations, std::uint64_t seed,
               Eigen::VectorXf& coeffs, pcl::Indices& inliers, PlaneTests tests = PlaneTests::Fast);

/// fit_plane's point tests on their own (what its plane model counts and selects for a hypothesis).
std::size_t count_within_plane(const Cloud::ConstPtr& cloud, const Eigen::VectorXf& coeffs, double threshold);
pcl::Indices select_within_plane(const Cloud::ConstPtr& cloud, const Eigen::VectorXf& coeffs, double threshold);

/// Indices of the points PCL's StatisticalOutlierRemoval keeps (mean distance to the k nearest within
/// mean + std_ratio * std over the cloud), in increasing order: PCL's filter with its searches in parallel.
pcl::Indices statistical_inliers(const Cloud::ConstPtr& cloud, int k, double std_ratio);

}  // namespace graspmix::detail
