#include "graspmix/perception/cleanup.hpp"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <pcl/common/common.h>
#include <pcl/filters/crop_box.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "cloud_filters.hpp"
#include "graspmix/core/plane.hpp"

namespace graspmix {

namespace {

using detail::Cloud;

/// Input rows that follow the points through every step: `origin` is a point's own input row (-1 once
/// voxel-averaged), `source` the input row whose per-point data it carries (CleanupResult::sources).
struct Rows {
  std::vector<int> origin, source;
};

Cloud::Ptr subset(const Cloud& c, const pcl::Indices& idx, Rows& rows) {
  Cloud::Ptr out(new Cloud);
  out->reserve(idx.size());
  Rows kept;
  kept.origin.reserve(idx.size());
  kept.source.reserve(idx.size());
  for (const auto i : idx) {
    out->push_back(c[static_cast<std::size_t>(i)]);
    kept.origin.push_back(rows.origin[static_cast<std::size_t>(i)]);
    kept.source.push_back(rows.source[static_cast<std::size_t>(i)]);
  }
  rows = std::move(kept);
  return out;
}

[[noreturn]] void bad(const std::string& m) { throw std::invalid_argument("prepare_cloud: " + m); }

void check_inputs(const Vec3Array& points, const CleanupSettings& s) {
  if (points.rows() == 0) bad("points: the cloud is empty");
  if (!points.allFinite()) bad("points: contains NaN or infinite values (load_cloud drops them)");
  if (s.voxel_size < 0 || !std::isfinite(s.voxel_size)) bad("voxel_size must be >= 0 (0 switches it off)");
  if (s.remove_outliers && (s.outlier_neighbours < 1 || !(s.outlier_std_ratio > 0))) {
    bad("outlier_neighbours must be >= 1 and outlier_std_ratio > 0");
  }
  if (s.remove_plane &&
      (!(s.plane_distance > 0) || s.plane_max_iterations < 1 || s.plane_min_fraction < 0 || s.plane_min_fraction > 1)) {
    bad("plane_distance must be > 0, plane_max_iterations >= 1 and plane_min_fraction in [0, 1]");
  }
  // NaN compares false both ways, so it must be caught before the order check; +-inf is a side left open.
  if (s.crop_min.hasNaN() || s.crop_max.hasNaN()) bad("crop_min and crop_max must be numbers (+-inf: open), not NaN");
  if (s.crop && (s.crop_min.array() > s.crop_max.array()).any()) bad("crop_min must be <= crop_max in every axis");
}

/// The cloud in PCL's float points, with every point's input row in `origin`.
Cloud::Ptr to_pcl(const Vec3Array& points, Rows& rows) {
  Cloud::Ptr cloud(new Cloud);
  cloud->resize(static_cast<std::size_t>(points.rows()));
  rows.origin.resize(static_cast<std::size_t>(points.rows()));
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    (*cloud)[static_cast<std::size_t>(i)] = pcl::PointXYZ(
        static_cast<float>(points(i, 0)), static_cast<float>(points(i, 1)), static_cast<float>(points(i, 2)));
    rows.origin[static_cast<std::size_t>(i)] = static_cast<int>(i);
  }
  rows.source = rows.origin;
  return cloud;
}

Cloud::Ptr crop(const Cloud::Ptr& cloud, const CleanupSettings& s, Rows& rows) {
  pcl::CropBox<pcl::PointXYZ> box;
  const float big = std::numeric_limits<float>::max();
  Eigen::Vector4f lo, hi;
  for (int k = 0; k < 3; ++k) {
    lo[k] = static_cast<float>(std::max<double>(s.crop_min[k], -big));
    hi[k] = static_cast<float>(std::min<double>(s.crop_max[k], big));
  }
  lo[3] = hi[3] = 1.0f;
  box.setMin(lo);
  box.setMax(hi);
  box.setInputCloud(cloud);
  pcl::Indices kept;
  box.filter(kept);
  return subset(*cloud, kept, rows);
}

/// PCL's voxel grid indexes voxels with 32-bit integers and, when they would overflow, warns on stderr and
/// returns the cloud unfiltered: refuse such a cloud (usually a stray point far away) instead.
void check_voxel_count(const Cloud& cloud, double voxel) {
  pcl::PointXYZ min_p, max_p;
  pcl::getMinMax3D(cloud, min_p, max_p);
  const Eigen::Array3d lo = min_p.getVector3fMap().cast<double>().array();
  const Eigen::Array3d hi = max_p.getVector3fMap().cast<double>().array();
  const Eigen::Array3d cells = ((hi - lo) / voxel).floor() + 1.0;
  const double n = cells.prod();
  if (n > static_cast<double>(std::numeric_limits<std::int32_t>::max())) {
    const Eigen::Array3d extent = hi - lo;
    bad("the cloud spans " + std::to_string(extent.x()) + " x " + std::to_string(extent.y()) + " x " +
        std::to_string(extent.z()) + " m: a voxel grid of " + std::to_string(voxel) + " m would need " +
        std::to_string(n) + " cells (more than PCL can index); crop the cloud or use a larger voxel_size");
  }
}

/// Voxel centroids (pcl::VoxelGrid's): no point keeps an input row (origin -1); `source` follows each
/// centroid to the member of its voxel nearest to it (squared distance in float, as a FLANN search would
/// measure it; on a tie the lowest row), so per-point data survive the averaging. Linear: one integer sort
/// (as PCL's own, which yields each point's voxel too), no search tree.
Cloud::Ptr voxel_down(const Cloud::Ptr& cloud, const CleanupSettings& s, Rows& rows) {
  check_voxel_count(*cloud, s.voxel_size);
  detail::VoxelCells cells;
  try {
    cells = detail::voxel_grid(*cloud, static_cast<float>(s.voxel_size));
  } catch (const std::invalid_argument&) {  // float rounding past check_voxel_count's figure: the same refusal
    bad("the cloud is too large for a voxel grid of " + std::to_string(s.voxel_size) +
        " m (more cells than 32-bit indices hold); crop the cloud or use a larger voxel_size");
  }
  const Cloud::Ptr& down = cells.centroids;
  if (down->empty()) bad("the voxel grid returned no point (voxel_size too small for the cloud's extent?)");
  const std::vector<int>& voxel = cells.voxel_of_point;
  std::vector<int> nearest(down->size(), -1);
  std::vector<float> best(down->size(), std::numeric_limits<float>::infinity());
  for (std::size_t i = 0; i < cloud->size(); ++i) {  // rows in increasing order: strict < keeps the lowest
    const auto v = static_cast<std::size_t>(voxel[i]);
    const auto &p = (*cloud)[i], &c = (*down)[v];
    const float dx = p.x - c.x, dy = p.y - c.y, dz = p.z - c.z;
    const float d2 = dx * dx + dy * dy + dz * dz;
    if (d2 < best[v]) {
      best[v] = d2;
      nearest[v] = rows.source[i];
    }
  }
  rows.source.swap(nearest);
  rows.origin.assign(down->size(), -1);
  return down;
}

Cloud::Ptr remove_outliers(const Cloud::Ptr& cloud, const CleanupSettings& s, Rows& rows) {
  return subset(*cloud, detail::statistical_inliers(cloud, s.outlier_neighbours, s.outlier_std_ratio), rows);
}

/// The support plane found and removed (with what lies below it if asked), oriented towards the
/// object: the side most of the points off the plane are on (PlaneSide::Majority). Records the plane
/// in r; the cloud unchanged if there is no plane with enough inliers.
Cloud::Ptr remove_support_plane(const Cloud::Ptr& cloud, const CleanupSettings& s, Rows& rows, CleanupResult& r) {
  Eigen::VectorXf coeffs;
  pcl::Indices inliers;
  if (!detail::fit_plane(cloud, s.plane_distance, s.plane_max_iterations, s.seed, coeffs, inliers)) return cloud;
  if (static_cast<double>(inliers.size()) < s.plane_min_fraction * static_cast<double>(cloud->size())) return cloud;
  std::vector<char> is_inlier(cloud->size(), 0);
  for (const auto i : inliers) is_inlier[static_cast<std::size_t>(i)] = 1;
  Vec3Array off_plane(static_cast<Eigen::Index>(cloud->size() - inliers.size()), 3);
  Eigen::Index n_off = 0;
  for (std::size_t i = 0; i < cloud->size(); ++i) {
    if (is_inlier[i]) continue;
    const auto& p = (*cloud)[i];
    off_plane.row(n_off++) << p.x, p.y, p.z;
  }
  const Eigen::Vector4d plane = orient_plane(coeffs.cast<double>().head<4>(), off_plane, PlaneSide::Majority);
  pcl::Indices kept;
  for (std::size_t i = 0; i < cloud->size(); ++i) {
    if (is_inlier[i]) continue;
    const auto& p = (*cloud)[i];
    const double dist = plane[0] * p.x + plane[1] * p.y + plane[2] * p.z + plane[3];
    if (s.remove_below_plane && dist < 0) continue;
    kept.push_back(static_cast<pcl::index_t>(i));
  }
  r.plane = plane;
  r.plane_found = true;
  r.n_plane_inliers = inliers.size();
  return subset(*cloud, kept, rows);
}

}  // namespace

CleanupResult prepare_cloud(const Vec3Array& points, const CleanupSettings& s) {
  const auto t0 = std::chrono::steady_clock::now();
  check_inputs(points, s);
  CleanupResult r;
  r.n_input = static_cast<std::size_t>(points.rows());
  Rows rows;
  Cloud::Ptr cloud = to_pcl(points, rows);
  if (s.crop) cloud = crop(cloud, s, rows);
  r.n_after_crop = cloud->size();
  if (cloud->empty()) bad("no point is inside the crop box");
  if (s.voxel_size > 0) cloud = voxel_down(cloud, s, rows);
  r.n_after_voxel = cloud->size();
  if (s.remove_outliers && cloud->size() > static_cast<std::size_t>(s.outlier_neighbours)) {
    cloud = remove_outliers(cloud, s, rows);
  }
  r.n_after_outliers = cloud->size();
  if (s.remove_plane && cloud->size() >= 3) cloud = remove_support_plane(cloud, s, rows, r);
  r.n_output = cloud->size();
  if (cloud->empty()) bad("no point is left after the clean-up (the plane took everything?)");
  r.points.resize(static_cast<Eigen::Index>(cloud->size()), 3);
  r.indices.resize(static_cast<Eigen::Index>(cloud->size()));
  r.sources.resize(static_cast<Eigen::Index>(cloud->size()));
  for (std::size_t i = 0; i < cloud->size(); ++i) {
    const auto& p = (*cloud)[i];
    r.points.row(static_cast<Eigen::Index>(i)) << p.x, p.y, p.z;
    r.indices[static_cast<Eigen::Index>(i)] = rows.origin[i];
    r.sources[static_cast<Eigen::Index>(i)] = rows.source[i];
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace graspmix
