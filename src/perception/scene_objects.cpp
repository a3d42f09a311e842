// The objects of a segmentation described, ordered and indexed into the Segmentation (segment_scene's last step,
// and split_object_near's when it cuts a scene's object again), with the errors of a scene that has none.
#include <algorithm>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "cluster_merge.hpp"
#include "segmentation_steps.hpp"
#include "table_noise.hpp"

namespace graspmix {

namespace {

using detail::heights;
using detail::table_noise;
using detail::TableNoise;

[[noreturn]] void bad(const std::string& m) { throw std::invalid_argument("segment_scene: " + m); }

/// Centroid and oriented bounding box (principal axes of the points' covariance) of `rows` of P.
SceneObject describe(const Vec3Array& P, const std::vector<int>& rows) {
  SceneObject o;
  o.n_points = rows.size();
  Eigen::Matrix3d R;
  detail::principal_axes(P, rows, o.centroid, R);
  Vec3Array C(static_cast<Eigen::Index>(rows.size()), 3);
  for (std::size_t i = 0; i < rows.size(); ++i) C.row(static_cast<Eigen::Index>(i)) = P.row(rows[i]);
  C.rowwise() -= o.centroid.transpose();
  const Vec3Array L = C * R;
  const Eigen::Vector3d lo = L.colwise().minCoeff().transpose(), hi = L.colwise().maxCoeff().transpose();
  o.obb_rotation = R;
  o.obb_extents = hi - lo;
  o.obb_center = o.centroid + R * (0.5 * (lo + hi));
  return o;
}

/// A plane holding more than this fraction of a cloud (within its noise) is the cloud: a table with nothing, or
/// little, on it.
constexpr double kCloudIsPlane = 0.9;

/// No support plane was accepted, and the plane that holds most of the cloud within its noise was refused only
/// because the camera lies in it (rule 2): the cloud is a table seen by no camera it knows (the PCD convention's
/// camera at the origin, in a world-frame table's own plane), not objects to grasp. An error saying so.
void refuse_a_table_seen_from_its_plane(const Vec3Array& P, const Segmentation& out, double plane_distance) {
  if (out.plane_found || out.plane_given || out.candidates.empty() || out.candidates.front().refused_by != 2) return;
  const Eigen::VectorXd h = heights(P, out.candidates.front().plane);
  const TableNoise noise = table_noise(h, plane_distance);
  Eigen::Index in = 0;
  for (Eigen::Index r = 0; r < h.size(); ++r) in += noise.holds(h[r], plane_distance) ? 1 : 0;
  const double fraction = static_cast<double>(in) / static_cast<double>(std::max<Eigen::Index>(h.size(), 1));
  if (fraction > kCloudIsPlane) {
    bad("no object found: " + std::to_string(static_cast<int>(100 * fraction)) +
        "% of the cloud lies in one plane, refused as the support only because the camera is in it; give the "
        "camera's position (viewpoints, --viewpoint or --camera-pose)");
  }
}

/// When no object stands on the plane but enough points for one lie beyond table_clearance behind it: the likely
/// causes, named (the plane is turned towards the cameras, so a camera placed below the table puts the objects
/// behind it; a given plane may be wrong itself). Empty otherwise.
std::string behind_hint(const Vec3Array& P, const Eigen::Vector4d& plane, bool given, const SegmentationSettings& s) {
  const Eigen::Index behind = (heights(P, plane).array() < -s.table_clearance).count();
  if (behind < s.min_cluster_size) return "";
  return "; " + std::to_string(behind) + " points lie behind it, on the side away from the cameras: is " +
         (given ? "the plane given right, and " : "") +
         "the camera's position right (a viewpoint or camera pose below the table, or a pose inverted, puts the "
         "objects there)?";
}

}  // namespace

void detail::finish(const Vec3Array& P, const Eigen::VectorXi& src, const Extraction& e, const SegmentationSettings& s,
                    Segmentation& out) {
  out.n_plane = e.n_plane;
  out.n_outliers = e.n_outliers;
  out.n_small_clusters = e.n_small;
  out.dropped = P(e.dropped, Eigen::all);
  refuse_a_table_seen_from_its_plane(P, out, s.plane_distance);
  if (e.groups.empty()) {
    if (!(out.plane_found || out.plane_given)) bad("no object in the cloud (every cluster is under min_cluster_size)");
    bad("no object above the support plane (every point is within table_clearance of it, behind it, in a cluster "
        "under min_cluster_size, or in one no higher than the table's own noise)" +
        behind_hint(P, out.plane, out.plane_given, s));
  }
  std::vector<SceneObject> described;
  for (const auto& g : e.groups) described.push_back(describe(P, g));
  std::vector<std::size_t> order(e.groups.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    const SceneObject &x = described[a], &y = described[b];
    if (x.n_points != y.n_points) return x.n_points > y.n_points;
    return std::lexicographical_compare(x.centroid.data(), x.centroid.data() + 3, y.centroid.data(),
                                        y.centroid.data() + 3);
  });
  std::size_t n = 0;
  for (const auto& g : e.groups) n += g.size();
  out.points.resize(static_cast<Eigen::Index>(n), 3);
  out.labels.resize(static_cast<Eigen::Index>(n));
  out.sources.resize(static_cast<Eigen::Index>(n));
  Eigen::Index row = 0;
  for (const auto i : order) {
    SceneObject o = described[i];
    o.index = static_cast<int>(out.objects.size());
    o.rows.resize(static_cast<Eigen::Index>(e.groups[i].size()));
    for (std::size_t j = 0; j < e.groups[i].size(); ++j, ++row) {
      out.points.row(row) = P.row(e.groups[i][j]);
      out.labels[row] = o.index;
      out.sources[row] = src[e.groups[i][j]];
      o.rows[static_cast<Eigen::Index>(j)] = static_cast<int>(row);
    }
    out.objects.push_back(std::move(o));
  }
  out.n_output = n;
}

void detail::regroup(Segmentation& scene, std::vector<std::vector<int>> groups, const SegmentationSettings& s) {
  Extraction e;
  e.groups = std::move(groups);
  e.n_plane = scene.n_plane;
  e.n_outliers = scene.n_outliers;
  e.n_small = scene.n_small_clusters;
  const Vec3Array dropped = scene.dropped;
  const Vec3Array P = scene.points;
  const Eigen::VectorXi sources = scene.sources;
  scene.objects.clear();
  finish(P, sources, e, s, scene);
  scene.dropped = dropped;
}

}  // namespace graspmix
