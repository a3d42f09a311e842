#pragma once
// segment_scene's steps after its input is made points (segmentation.cpp), shared by the scene of a depth image
// (depth_scene.cpp), which makes its points in image space instead of by the voxel grid alone.
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "graspmix/core/types.hpp"
#include "graspmix/perception/segmentation.hpp"
#include "graspmix/perception/visibility.hpp"

namespace graspmix::detail {

/// The cameras as the voxelised points see them: one per point (input viewpoints indexed by sources), or
/// one for all (the given one, or the origin when none is given).
struct Cameras {
  Vec3Array per_point;
  Eigen::Vector3d single = Eigen::Vector3d::Zero();
  bool given = false;
  /// The model the join rule judges gaps on, made when the rule has two pieces to judge (a depth image's pooled
  /// image); unset: the scene's own visibility model.
  std::function<std::shared_ptr<const VisibilityModel>()> join_model;

  /// Mean height above `plane` of the cameras that saw `rows` (all cameras when rows is empty).
  double height(const Eigen::Vector4d& plane, const std::vector<int>& rows) const {
    const Eigen::Vector3d n = plane.head<3>();
    if (per_point.rows() == 0) return n.dot(single) + plane[3];
    double sum = 0;
    if (rows.empty()) return (per_point * n).array().mean() + plane[3];
    for (const int r : rows) sum += per_point.row(r).dot(n);
    return sum / static_cast<double>(rows.size()) + plane[3];
  }
};

/// Whether world point p lies in the settings' workspace (always, without one).
inline bool in_workspace(const SegmentationSettings& s, const Eigen::Vector3d& p) {
  if (s.workspace.empty()) return true;
  for (int k = 0; k < 3; ++k)
    if (!(p[k] >= s.workspace[static_cast<std::size_t>(k)] && p[k] <= s.workspace[static_cast<std::size_t>(k) + 3]))
      return false;
  return true;
}

/// The error of an input with no point (or return) inside the workspace: std::invalid_argument("<what>: nothing ...").
[[noreturn]] void nothing_in_workspace(const SegmentationSettings& s, const char* what);

/// Throws std::invalid_argument ("segment_scene: ...") naming the first setting out of range.
void check_segmentation_settings(const SegmentationSettings& s);

/// The settings of the scene's visibility model (Segmentation::visibility).
VisibilitySettings visibility_settings(const SegmentationSettings& s);

/// The support plane (given, found by the rule, or none), the objects above it, the merge and join rules, and the
/// objects described into `out`, from the voxelised points P whose rows carry the input rows `sources`, seen by
/// `cams`; out.visibility (when set) serves the join rule. Adds each step's time to out.times.
void segment_voxelised(const Vec3Array& P, const Eigen::VectorXi& sources, const Cameras& cams,
                       const SegmentationSettings& s, const std::optional<Eigen::Vector4d>& plane, Segmentation& out);

/// segment_voxelised in two steps on two point sets: the support on P (a given plane turned towards the cameras, or
/// the plane by the rule when find_plane: out.plane, plane_found, candidates, rule 4 judged on P's objects), then
/// the objects of other points above the support (or of all of them without one). table_sample: where the table's
/// noise is to be measured on other points than P's (a depth image's: P's table and objects come from blocks of
/// different sizes, whose scatter differs), a sample of the scene as fine as P's objects, evenly over the image.
void search_support(const Vec3Array& P, const Cameras& cams, const SegmentationSettings& s,
                    const std::optional<Eigen::Vector4d>& plane, Segmentation& out);
void segment_on_support(const Vec3Array& P, const Eigen::VectorXi& sources, const Cameras& cams,
                        const SegmentationSettings& s, Segmentation& out, const Vec3Array* table_sample = nullptr);

/// The objects above a plane (or of the whole cloud without one) as groups of rows of P, with what each
/// step dropped.
struct Extraction {
  std::vector<std::vector<int>> groups;
  std::size_t n_plane = 0, n_outliers = 0, n_small = 0;
  /// rows of the outliers and of the clusters dropped for their size (Segmentation::dropped)
  std::vector<int> dropped;
};

/// The objects of an extraction described and ordered as documented (segmentation.hpp) into `out`, from the points
/// P whose rows carry the input rows `src` (scene_objects.cpp); throws std::invalid_argument ("segment_scene: ...")
/// for a scene with no object, naming the likely cause.
void finish(const Vec3Array& P, const Eigen::VectorXi& src, const Extraction& e, const SegmentationSettings& s,
            Segmentation& out);

/// The scene's objects made again from `groups` (rows of scene.points, each sorted): described, ordered and indexed
/// as segment_scene does; the counts of points dropped kept.
void regroup(Segmentation& scene, std::vector<std::vector<int>> groups, const SegmentationSettings& s);

}  // namespace graspmix::detail
