#include "graspmix/perception/segmentation.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iterator>
#include <limits>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "cloud_filters.hpp"
#include "cluster_merge.hpp"
#include "occlusion_merge.hpp"
#include "pile_split.hpp"
#include "segmentation_steps.hpp"
#include "table_noise.hpp"

namespace graspmix {

namespace {

using detail::Cameras;
using detail::Cloud;
using detail::Extraction;
using detail::finish;
using detail::heights;
using detail::table_noise;
using detail::TableNoise;

[[noreturn]] void bad(const std::string& m) { throw std::invalid_argument("segment_scene: " + m); }

/// Adds the seconds since it was made (or last added) to a step's time.
class Lap {
 public:
  void add_to(double& step) {
    const auto now = std::chrono::steady_clock::now();
    step += std::chrono::duration<double>(now - t_).count();
    t_ = now;
  }

 private:
  std::chrono::steady_clock::time_point t_ = std::chrono::steady_clock::now();
};

}  // namespace

namespace {

void check_inputs(const Vec3Array& points, const Vec3Array& viewpoints) {
  if (points.rows() == 0) bad("points: the cloud is empty");
  if (!points.allFinite()) bad("points: contains NaN or infinite values");
  const auto n = viewpoints.rows();
  if (n != 0 && n != 1 && n != points.rows()) {
    bad("viewpoints: expected 0, 1 or " + std::to_string(points.rows()) + " rows (one per point), got " +
        std::to_string(n));
  }
  if (!viewpoints.allFinite()) bad("viewpoints: contains NaN or infinite values");
}

pcl::PointXYZ to_pcl(const Vec3Array& P, int r) {
  return {static_cast<float>(P(r, 0)), static_cast<float>(P(r, 1)), static_cast<float>(P(r, 2))};
}

/// Rule 4's figure: along 8 directions in the plane, the least reach of the inliers beyond the objects
/// (the clusters found above the plane); +inf when there is no object.
double footprint_margin(const Vec3Array& P, const std::vector<int>& inliers, const Eigen::Vector4d& plane,
                        const std::vector<std::vector<int>>& objects) {
  if (objects.empty()) return std::numeric_limits<double>::infinity();
  const Eigen::Vector3d n = plane.head<3>();
  const Eigen::Vector3d u = n.unitOrthogonal(), v = n.cross(u);
  Eigen::Matrix<double, 3, 8> dirs;
  for (int k = 0; k < 8; ++k) dirs.col(k) = std::cos(k * M_PI / 4) * u + std::sin(k * M_PI / 4) * v;
  Eigen::Matrix<double, 1, 8> reach_in =
      Eigen::Matrix<double, 1, 8>::Constant(-std::numeric_limits<double>::infinity());
  Eigen::Matrix<double, 1, 8> reach_obj = reach_in;
  for (const int r : inliers) reach_in = reach_in.cwiseMax(P.row(r) * dirs);
  for (const auto& g : objects)
    for (const int r : g) reach_obj = reach_obj.cwiseMax(P.row(r) * dirs);
  return (reach_in - reach_obj).minCoeff();
}

/// A RANSAC candidate oriented towards the cameras and judged by rules 1-3 (segmentation.hpp).
PlaneCandidate judge(const Vec3Array& P, const Cameras& cams, const Eigen::VectorXf& coeffs,
                     const std::vector<int>& inliers, const SegmentationSettings& s) {
  PlaneCandidate c;
  c.plane = coeffs.cast<double>().head<4>();
  c.n_inliers = inliers.size();
  c.inlier_fraction = static_cast<double>(inliers.size()) / static_cast<double>(P.rows());
  c.camera_height = cams.height(c.plane, inliers);
  if (c.camera_height < 0) {
    c.plane = -c.plane;
    c.camera_height = -c.camera_height;
  }
  const Eigen::VectorXd h = heights(P, c.plane);
  c.behind_fraction =
      static_cast<double>((h.array() < -s.plane_behind_distance).count()) / static_cast<double>(P.rows());
  c.margin = std::numeric_limits<double>::quiet_NaN();  // rule 4 is judged on the objects (segment_scene)
  if (c.inlier_fraction < s.plane_min_fraction) {
    c.refused_by = 1;
    c.reason = "holds too few points (rule 1)";
  } else if (c.camera_height < s.plane_distance) {
    c.refused_by = 2;
    c.reason = "passes through the cameras (rule 2)";
  } else if (c.behind_fraction > s.plane_max_behind_fraction) {
    c.refused_by = 3;
    c.reason = "has points behind it (rule 3)";
  }
  c.accepted = c.reason.empty();
  return c;
}

/// RANSAC candidates found one after another (each on the points the previous ones left), judged by rules
/// 1-3 into out.candidates; returns the inliers of each.
std::vector<std::vector<int>> find_candidates(const Vec3Array& P, const Cameras& cams, const SegmentationSettings& s,
                                              Segmentation& out) {
  std::vector<std::vector<int>> found;
  Cloud::Ptr cloud(new Cloud);
  std::vector<int> remaining(static_cast<std::size_t>(P.rows()));
  std::iota(remaining.begin(), remaining.end(), 0);
  const double min_inliers = std::max(3.0, s.plane_min_fraction * static_cast<double>(P.rows()));
  for (int k = 0; k < s.plane_candidates && static_cast<double>(remaining.size()) >= min_inliers; ++k) {
    cloud->clear();
    for (const int r : remaining) cloud->push_back(to_pcl(P, r));
    Eigen::VectorXf coeffs;
    pcl::Indices local;
    const auto seed = s.seed + static_cast<std::uint64_t>(k);
    if (!detail::fit_plane(cloud, s.plane_distance, s.plane_max_iterations, seed, coeffs, local)) break;
    std::vector<int> inliers;
    inliers.reserve(local.size());
    std::vector<char> is_inlier(remaining.size(), 0);
    for (const auto i : local) {
      inliers.push_back(remaining[static_cast<std::size_t>(i)]);
      is_inlier[static_cast<std::size_t>(i)] = 1;
    }
    out.candidates.push_back(judge(P, cams, coeffs, inliers, s));
    found.push_back(std::move(inliers));
    if (out.candidates.back().inlier_fraction < s.plane_min_fraction) break;  // every later one is smaller still
    // The next search leaves out a band twice as wide, so the noise tails of this surface cannot come back
    // as a parallel plane of their own a few millimetres away.
    const Eigen::Vector4d& plane = out.candidates.back().plane;
    std::vector<int> left;
    left.reserve(remaining.size() - found.back().size());
    for (std::size_t i = 0; i < remaining.size(); ++i) {
      const int r = remaining[i];
      if (!is_inlier[i] && std::abs(P.row(r).dot(plane.head<3>()) + plane[3]) > 2 * s.plane_distance) left.push_back(r);
    }
    remaining.swap(left);
  }
  return found;
}

/// A caller's plane normalised and turned towards the cameras (kept as given without viewpoints).
Eigen::Vector4d orient_given(const Eigen::Vector4d& given, const Vec3Array& P, const Cameras& cams,
                             const SegmentationSettings& s) {
  if (!given.allFinite() || given.head<3>().norm() < 1e-12)
    bad("plane: [a, b, c, d] must be finite with (a, b, c) != 0");
  Eigen::Vector4d plane = given / given.head<3>().norm();
  if (!cams.given) return plane;
  std::vector<int> on_plane;
  const Eigen::VectorXd h = heights(P, plane);
  for (Eigen::Index r = 0; r < P.rows(); ++r)
    if (std::abs(h[r]) <= s.table_clearance) on_plane.push_back(static_cast<int>(r));
  return cams.height(plane, on_plane) < 0 ? Eigen::Vector4d(-plane) : plane;
}

/// The clusters above the support plane that do not rise above the table's own noise (AboveTableNoise: a noisy
/// table's tail above table_clearance falls apart into such fragments) go with the table. table_sample: where the
/// noise is measured (P's rows when null).
void drop_table_noise(const Vec3Array& P, const Eigen::Vector4d& plane, const SegmentationSettings& s, Extraction& e,
                      const Vec3Array* table_sample) {
  detail::AboveTableNoise above(P, plane, s.plane_distance, table_sample);
  std::vector<std::vector<int>> kept;
  for (auto& g : e.groups) {
    if (above.any(g)) {
      kept.push_back(std::move(g));
    } else {
      e.n_plane += g.size();
    }
  }
  e.groups.swap(kept);
}

/// Rows above the clearance (all without a plane), outliers removed, then Euclidean clusters; the clusters
/// smaller than min_cluster_size (or larger than a set maximum) are dropped.
Extraction extract(const Vec3Array& P, const Eigen::Vector4d* plane, const SegmentationSettings& s,
                   SegmentationTimes& times) {
  Lap lap;
  Extraction e;
  std::vector<int> rows;
  const Eigen::VectorXd h = plane ? heights(P, *plane) : Eigen::VectorXd();
  for (Eigen::Index r = 0; r < P.rows(); ++r)
    if (!plane || h[r] > s.table_clearance) rows.push_back(static_cast<int>(r));
  e.n_plane = static_cast<std::size_t>(P.rows()) - rows.size();
  Cloud::Ptr cloud(new Cloud);
  for (const int r : rows) cloud->push_back(to_pcl(P, r));
  lap.add_to(times.table_cut);
  if (s.remove_outliers && rows.size() > static_cast<std::size_t>(s.outlier_neighbours)) {
    const pcl::Indices kept = detail::statistical_inliers(cloud, s.outlier_neighbours, s.outlier_std_ratio);
    std::vector<int> kept_rows;
    Cloud::Ptr kept_cloud(new Cloud);
    std::vector<bool> is_kept(rows.size(), false);
    for (const auto i : kept) {
      kept_rows.push_back(rows[static_cast<std::size_t>(i)]);
      kept_cloud->push_back((*cloud)[static_cast<std::size_t>(i)]);
      is_kept[static_cast<std::size_t>(i)] = true;
    }
    for (std::size_t i = 0; i < rows.size(); ++i)
      if (!is_kept[i]) e.dropped.push_back(rows[i]);
    e.n_outliers = rows.size() - kept_rows.size();
    rows.swap(kept_rows);
    cloud = kept_cloud;
  }
  lap.add_to(times.outliers);
  if (rows.empty()) return e;
  for (const auto& f : detail::euclidean_clusters(cloud, s.cluster_tolerance)) {
    const auto n = static_cast<int>(f.size());
    if (n < s.min_cluster_size || (s.max_cluster_size > 0 && n > s.max_cluster_size)) {
      e.n_small += f.size();
      for (const auto i : f) e.dropped.push_back(rows[static_cast<std::size_t>(i)]);
      continue;
    }
    std::vector<int> g;
    for (const auto i : f) g.push_back(rows[static_cast<std::size_t>(i)]);
    std::sort(g.begin(), g.end());
    e.groups.push_back(std::move(g));
  }
  lap.add_to(times.clusters);
  return e;
}

/// The support plane by the rule: the candidates that pass rules 1-3, lowest (farthest from the cameras)
/// first, until one passes rule 4 on the objects above it; no plane when none does.
Extraction find_support(const Vec3Array& P, const Cameras& cams, const SegmentationSettings& s, Segmentation& out) {
  Lap lap;
  const std::vector<std::vector<int>> inliers = find_candidates(P, cams, s, out);
  lap.add_to(out.times.candidates);
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < out.candidates.size(); ++i)
    if (out.candidates[i].accepted) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return out.candidates[a].camera_height > out.candidates[b].camera_height;
  });
  for (const auto i : order) {
    PlaneCandidate& c = out.candidates[i];
    Extraction e = extract(P, &c.plane, s, out.times);
    lap = Lap();
    // Judged on what rises above the candidate's noise when something does (a noisy table's fragments reach its
    // edges); on every cluster when nothing does (an object's face, seen without a table, has only its noise
    // above it, and that keeps it no support).
    detail::AboveTableNoise above(P, c.plane, s.plane_distance);
    std::vector<std::vector<int>> rising;
    std::copy_if(e.groups.begin(), e.groups.end(), std::back_inserter(rising),
                 [&](const auto& g) { return above.any(g); });
    c.margin = footprint_margin(P, inliers[i], c.plane, rising.empty() ? e.groups : rising);
    lap.add_to(out.times.clusters);
    if (c.margin >= s.plane_margin) {
      out.plane = c.plane;
      out.plane_found = true;
      return e;
    }
    c.accepted = false;
    c.refused_by = 4;
    c.reason = "does not reach beyond the objects (rule 4)";
  }
  return extract(P, nullptr, s, out.times);
}

}  // namespace

namespace {

/// The objects of an extraction after the support is chosen: the table's noise dropped, the merge and join rules,
/// the objects described into `out`.
void finish_objects(const Vec3Array& P, const Eigen::VectorXi& sources, const Cameras& cams,
                    const SegmentationSettings& s, Extraction e, Segmentation& out,
                    const Vec3Array* table_sample = nullptr) {
  Lap lap;
  if (out.plane_found || out.plane_given) drop_table_noise(P, out.plane, s, e, table_sample);
  lap.add_to(out.times.clusters);
  if (s.merge_seen_through && e.groups.size() > 1) {
    const Vec3Array one = cams.single.transpose();
    const Vec3Array& seen_from = cams.per_point.rows() > 0 ? cams.per_point : one;
    out.n_merged = detail::merge_seen_through(P, seen_from, e.groups, s.merge_through_fraction, s.merge_inset);
  }
  lap.add_to(out.times.merge);
  if (s.join_occluded && out.visibility && e.groups.size() > 1) {
    const auto model = cams.join_model ? cams.join_model() : out.visibility;
    out.n_joined = detail::join_occluded(P, *model, e.groups,
                                         detail::JoinRule{s.join_max_gap, s.join_seen_margin, s.join_max_size});
  }
  lap.add_to(out.times.join);
  if (s.split_touching) {
    const Vec3Array one = cams.single.transpose();
    const Vec3Array& seen_from = cams.per_point.rows() > 0 ? cams.per_point : one;
    out.n_split = detail::split_touching(
        P, seen_from, e.groups,
        detail::SplitRule{std::max(s.split_voxel_resolution, s.voxel_size), s.split_seed_resolution,
                          s.split_concavity_tolerance, s.split_min_points, s.split_max_size});
  }
  // A piece cut off an object can be the table's noise the object stood in (a noisy near table joins the base
  // of what stands on it into one cluster): judged again.
  if (out.n_split > 0 && (out.plane_found || out.plane_given)) drop_table_noise(P, out.plane, s, e, table_sample);
  lap.add_to(out.times.split);
  finish(P, sources, e, s, out);
  lap.add_to(out.times.objects);
}

}  // namespace

void detail::segment_voxelised(const Vec3Array& P, const Eigen::VectorXi& sources, const Cameras& cams,
                               const SegmentationSettings& s, const std::optional<Eigen::Vector4d>& plane,
                               Segmentation& out) {
  Lap lap;
  Extraction e;
  if (plane) {
    out.plane = orient_given(*plane, P, cams, s);
    out.plane_given = true;
    lap.add_to(out.times.candidates);
    e = extract(P, &out.plane, s, out.times);
  } else if (s.find_plane) {
    e = find_support(P, cams, s, out);
  } else {
    e = extract(P, nullptr, s, out.times);
  }
  finish_objects(P, sources, cams, s, std::move(e), out);
}

void detail::search_support(const Vec3Array& P, const Cameras& cams, const SegmentationSettings& s,
                            const std::optional<Eigen::Vector4d>& plane, Segmentation& out) {
  if (plane) {
    out.plane = orient_given(*plane, P, cams, s);
    out.plane_given = true;
  } else if (s.find_plane) {
    find_support(P, cams, s, out);
  }
}

void detail::segment_on_support(const Vec3Array& P, const Eigen::VectorXi& sources, const Cameras& cams,
                                const SegmentationSettings& s, Segmentation& out, const Vec3Array* table_sample) {
  const bool plane = out.plane_found || out.plane_given;
  finish_objects(P, sources, cams, s, extract(P, plane ? &out.plane : nullptr, s, out.times), out, table_sample);
}

Segmentation segment_scene(const Vec3Array& points, const Vec3Array& viewpoints, const SegmentationSettings& s,
                           const std::optional<Eigen::Vector4d>& plane) {
  const auto t0 = std::chrono::steady_clock::now();
  detail::check_segmentation_settings(s);
  check_inputs(points, viewpoints);
  if (!s.workspace.empty()) {  // the points (and their own viewpoints) inside the workspace, then the input rows
    std::vector<Eigen::Index> rows;
    for (Eigen::Index r = 0; r < points.rows(); ++r)
      if (detail::in_workspace(s, points.row(r).transpose())) rows.push_back(r);
    if (rows.empty()) detail::nothing_in_workspace(s, "segment_scene: points");
    const auto n = static_cast<Eigen::Index>(rows.size());
    Vec3Array P(n, 3), V(viewpoints.rows() > 1 ? n : viewpoints.rows(), 3);
    for (Eigen::Index i = 0; i < n; ++i) P.row(i) = points.row(rows[static_cast<std::size_t>(i)]);
    if (viewpoints.rows() > 1) {
      for (Eigen::Index i = 0; i < n; ++i) V.row(i) = viewpoints.row(rows[static_cast<std::size_t>(i)]);
    } else {
      V = viewpoints;
    }
    SegmentationSettings inside = s;
    inside.workspace.clear();
    Segmentation out = segment_scene(P, V, inside, plane);
    for (Eigen::Index i = 0; i < out.sources.size(); ++i) out.sources[i] = static_cast<int>(rows[out.sources[i]]);
    out.n_input = static_cast<std::size_t>(points.rows());
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return out;
  }
  Segmentation out;
  out.n_input = static_cast<std::size_t>(points.rows());
  CleanupSettings voxel;  // prepare_cloud's voxel grid only: the sources follow every centroid
  voxel.voxel_size = s.voxel_size;
  voxel.remove_outliers = false;
  voxel.remove_plane = false;
  Lap lap;
  const CleanupResult down = prepare_cloud(points, voxel);
  const Vec3Array& P = down.points;
  out.n_after_voxel = static_cast<std::size_t>(P.rows());
  Cameras cams;
  cams.given = viewpoints.rows() > 0;
  if (viewpoints.rows() == 1) cams.single = viewpoints.row(0).transpose();
  if (viewpoints.rows() > 1) {
    cams.per_point.resize(P.rows(), 3);
    for (Eigen::Index i = 0; i < P.rows(); ++i) cams.per_point.row(i) = viewpoints.row(down.sources[i]);
  }
  lap.add_to(out.times.voxel);
  if (cams.given) {
    const Vec3Array one = cams.single.transpose();
    out.visibility = std::make_shared<const VisibilityModel>(
        VisibilityModel::from_views(P, cams.per_point.rows() ? cams.per_point : one, detail::visibility_settings(s)));
  }
  lap.add_to(out.times.visibility);
  detail::segment_voxelised(P, down.sources, cams, s, plane, out);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace graspmix
