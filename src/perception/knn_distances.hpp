#pragma once
// Each point's mean distance to its k nearest neighbours as pcl::StatisticalOutlierRemoval computes it, private to
// perception (the outlier filter of cloud_filters.cpp).
#include <vector>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

namespace graspmix::detail {

/// The statistic's inputs: per point its mean distance to its k nearest others (0 for a non-finite point) and the
/// number of finite points.
struct KnnDistances {
  std::vector<float> mean;
  int valid = 0;
  int from_tree = 0;  ///< points whose neighbours the kd-tree found (the grid could not vouch for them)
};

/// PCL's statistic bit for bit: a point's k + 1 nearest (itself first) by FLANN's float squared distances
/// (x, then y, then z), their square roots summed in double from the nearest, divided by k. The neighbours are
/// searched in a uniform grid (cells about one and a half times the typical reach of k + 1 neighbours, wider where
/// the cloud's box would need over 16 cells a point; the 27 cells around a point): a point's result is taken from
/// the grid only when its (k + 1)-th nearest there is nearer than anything outside those cells can be. PCL's
/// kd-tree searches the other points, those whose 27 cells hold over 32 (k + 1) points (a dense spot: no query
/// scans a crowd), and every point of a cloud with a non-finite point, of k + 1 points or fewer, or too wide for
/// the grid. Parallel (OpenMP).
KnnDistances knn_mean_distances(const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& cloud, int k);

}  // namespace graspmix::detail
