#pragma once
// The scene model: a depth camera's cloud split into the support plane and the objects on it.
//
// Steps: voxel grid (prepare_cloud's, so per-point data follow through `sources`); the support plane,
// given or searched for (rule below); points within table_clearance of it or behind it dropped;
// statistical outlier removal on the object points only (after the cut: cheaper, and the table's
// points cannot make an object's edge look like an outlier); Euclidean clusters of what is left. Once the
// support is chosen, a cluster whose points all lie within 5 sigma of the table's own scatter (robust: the
// median and MAD of the heights near the plane, when they look like a table's noise), of the whole table's
// or of the table in the 15 x 15 cm around the point (one view's near table is noisier than its far one), is
// a fragment of a noisy table's tail, not an object, and goes with the table; so does such a piece the split
// rule cuts off an object (a noisy table's tail can join an object's base). Rule 4 below sees those fragments
// when nothing else stands above a candidate, so the noise above an object's face keeps that face no support.
//
// Which side of a plane is "up": the side the cameras are on, decided by the viewpoints, never by
// where most points lie (far-field noise can outnumber an object). Per-point viewpoints (N, 3): the mean
// signed height of the viewpoints of the points on the plane (every camera that sees a surface is on its
// side); one viewpoint: its side; no viewpoint: the camera is taken at the cloud frame's origin (the PCD
// convention: a cloud without VIEWPOINT is in its sensor's frame).
//
// The support plane rule (when no plane is given). RANSAC finds up to plane_candidates planes, the
// inliers of each removed before the next. A candidate is the support when all of these hold:
//  1. it holds at least plane_min_fraction of the voxelised points;
//  2. the cameras are off it (the mean camera height above it is at least plane_distance);
//  3. at most plane_max_behind_fraction of all points lie more than plane_behind_distance behind it
//     (on the far side from the cameras): a face of an object has the rest of that object behind it,
//     a table has only noise there;
//  4. its inliers extend beyond the objects' footprint: along each of 8 directions in the plane, the
//     farthest inlier is at least plane_margin beyond the farthest object point (object points: those
//     more than table_clearance above it, in the clusters that rise above its noise as the table's noise
//     rule above judges them, or in every cluster when none does), so a table reaches past what stands on
//     it, and a noisy table's fragments, which reach its edges, do not refuse it.
// Among the accepted candidates the support is the lowest: the one farthest from the cameras.
// An object-only cloud (no extended surface under it) therefore yields no plane, and then every
// point is an object point. A cloud over 90% of which lies within the noise of a plane refused only by rule 2
// (the camera in it: a world-frame table seen from no camera given) is a table with nothing on it: an error.
//
// The merge rule (objects seen through another): a cluster A is part of a larger cluster B when at least
// merge_through_fraction of A's lines of sight (from the camera that saw each point to the point) pass
// through B's convex envelope inset by merge_inset. The envelope is B's 26-DOP: 13 slabs bounding B's points
// along its box axes, their face and body diagonals (a convex hull's close outer approximation, never
// degenerate). A solid convex object hides what lies behind it, so lines of sight to a visible neighbour
// do not cross it (packed boxes 1 cm apart, one view with the acquisition's noise: at most 7%, a thin strip
// of a box seen over another's edge); the inside of a container seen over its rim does (a mug's inner wall
// cut off by a thin noisy rim: 35-55%). Merges
// repeat, smallest cluster first, until none applies, before the objects are described and ordered.
// What it does not join: parts seen beside the object (a mug's handle behind its body: under 15%). An
// object inside an open container joins it only when seen through the container's envelope: a 4 cm cube in a
// 16 x 16 x 8 cm box with 5 mm walls, seen from 45 degrees, stays its own object, because the container falls
// apart into its walls (its floor is within table_clearance and goes with the table) and a wall's envelope,
// thinner than twice merge_inset, is crossed by no line of sight.
//
// The join rule (pieces of one object cut apart by a shadow in the view; only with viewpoints, which build the
// visibility model, and after the merge rule): two clusters A and B are one object when
//  1. their gap (least distance between their points) is at most join_max_gap;
//  2. the views did not see the gap empty: over A's and B's facing segments (each point within 5 mm of the least
//     gap joined to its nearest point of the other, the 16 nearest), the median of how far each segment's
//     interior samples lie in front of the observed surface (Segmentation::visibility's signed distance; the
//     largest over 9 samples, unseen counts as behind) is at most join_seen_margin. A gap in the shadow of a
//     nearer object or of the object itself lies behind what the camera saw; between objects standing apart
//     the camera sees the table (or a farther object) beyond the gap;
//  3. the joined cluster stays the size of one object: its principal box's largest side is at most
//     join_max_size.
// Pairs that pass are joined nearest first (the pairs with the joined cluster judged again) until none passes.
// Chosen on one-view clutter scenes of the development objects (docs/clutter.md, "Objects found"). What it cannot
// tell apart: an object seen in front of another with the gap between them hidden (objects touching in a pile)
// passes rule 2 as pieces do, and only rule 3 keeps them apart; a piece that is itself the occluder (a bar of an
// object lying across the rest of it) stands in front of the gap, which the camera then sees, and stays apart.
//
// The split rule (objects touching in a pile; split_touching; after the join rule): a cluster whose
// principal box's largest side exceeds split_max_size is larger than one object and is cut:
//  1. its points, in a frame centred on the camera that saw them (so that the patches' normals face it), are made
//     supervoxels (pcl::SupervoxelClustering, voxel split_voxel_resolution, seeds split_seed_resolution apart) and
//     grouped by PCL's LCCP: neighbouring patches stay together when the crease between them is convex, or concave
//     by less than split_concavity_tolerance; a crease more concave than that is a cut;
//  2. a piece with fewer than split_min_points points goes back to the piece its points touch most (within two
//     supervoxel voxels), smallest first;
//  3. the pieces re-join, the pair that touches most first, while the joined piece's largest principal-box side
//     stays within split_max_size: the cluster ends as few pieces as objects of that size can make it.
// Objects touching in a pile meet at a concave crease (one resting on or leaning against another); one object within
// split_max_size is never tried, whatever its creases (a mug's handle, a bowl's inside, the lobes of an irregular
// shape: LCCP cuts all of these). Chosen on one-view pile and packed scenes of the development objects
// (docs/clutter.md, "Objects found"). What it cannot do: split a cluster of touching objects no larger than one object
// (about half of the pile's merged clusters there), or cut where the contact shows no concave crease (two boxes
// flush, their faces coplanar across the contact; a contact seen edge-on); and a single object larger than
// split_max_size with a concave crease is cut.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "graspmix/core/plane.hpp"
#include "graspmix/core/types.hpp"
#include "graspmix/perception/cleanup.hpp"
#include "graspmix/perception/visibility.hpp"

namespace graspmix {

struct SegmentationSettings {
  /// The workspace, a box in the world frame [x_min, y_min, z_min, x_max, y_max, z_max] (m): the input is cropped
  /// to it before anything else (the rest of a view stays in the model of what the camera saw); empty: no crop.
  std::vector<double> workspace;
  /// Voxel-grid leaf size (m), 0 = off; the same as the clean-up's (features must see the same density).
  double voxel_size = CleanupSettings{}.voxel_size;
  double plane_distance = CleanupSettings{}.plane_distance;           ///< RANSAC inlier threshold (m)
  int plane_max_iterations = CleanupSettings{}.plane_max_iterations;  ///< RANSAC iterations per candidate
  std::uint64_t seed = 0;                                             ///< seeds RANSAC
  /// Search for the support plane (the rule below); false: the cloud is objects only, no plane is searched.
  bool find_plane = true;
  int plane_candidates = 3;                 ///< planes tried, each on the points the previous ones left
  double plane_min_fraction = 0.05;         ///< rule 1: fraction of the voxelised points a candidate holds
  double plane_behind_distance = 0.01;      ///< rule 3: m behind the plane for a point to count as behind it
  double plane_max_behind_fraction = 0.05;  ///< rule 3: fraction of all points allowed behind it (faces: > 0.1)
  double plane_margin = 0.01;               ///< rule 4: m the inliers must reach beyond the objects' footprint
  /// m: points at most this far above the support plane (or behind it) are the table and are dropped.
  /// Also the default of a synthesis' (SynthesisOptions().segmentation, Python).
  double table_clearance = kTableClearance;
  bool remove_outliers = CleanupSettings{}.remove_outliers;        ///< on the object points only
  int outlier_neighbours = CleanupSettings{}.outlier_neighbours;   ///< k of the mean-distance statistic
  double outlier_std_ratio = CleanupSettings{}.outlier_std_ratio;  ///< mean + ratio * std cut
  /// m: two object points closer than this are in one object (pcl::EuclideanClusterExtraction). Voxel
  /// centroids of one surface lie about one voxel (3 mm) apart, up to 2 voxels diagonally or on steep
  /// faces; packed objects stand about 1 cm apart. 6 mm joins the first and keeps the second apart.
  double cluster_tolerance = 0.006;
  int min_cluster_size = 20;            ///< clusters with fewer points are noise, dropped (and counted)
  int max_cluster_size = 0;             ///< clusters with more points are dropped; 0 = no limit
  bool merge_seen_through = true;       ///< the merge rule (above): a cluster seen through another joins it
  double merge_through_fraction = 0.2;  ///< fraction of a cluster's lines of sight that must cross the other
  /// m the other's envelope is inset by: lines of sight grazing its edge (flying pixels at an occluding edge
  /// stretch the envelope towards what it hides) do not count; the cluster tolerance's 6 mm.
  double merge_inset = 0.006;
  /// The join rule (above): clusters whose gap the view leaves unseen are pieces of one object. Off without
  /// viewpoints (no visibility model).
  bool join_occluded = true;
  /// m: rule 1, clusters farther apart are never joined: an occluder's shadow on a one-view clutter scene's
  /// development objects cut pieces at most 3-4 cm apart; wider gaps joined mostly objects that stand apart.
  double join_max_gap = 0.03;
  /// m: rule 2, the views saw the gap empty when they saw more than this beyond it (the median over the facing
  /// segments): the visibility model's own tolerance, so a segment counts as seen when a sample of it is
  /// SeenFree. 1-1.5 cm joined a few more pieces on the development scenes but also two 5 cm cubes packed 1 cm
  /// apart seen along their row, whose slot the camera sees only about 1 cm deep.
  double join_seen_margin = VisibilitySettings{}.surface_tolerance;
  /// m: rule 3, the joined cluster's largest principal-box side: the largest object the clutter lists hold
  /// (150 mm across, data/objects/clutter_dev.txt).
  double join_max_size = 0.15;
  /// The split rule (above): a cluster larger than one object is cut at its concave creases into the objects
  /// touching in it. On the development piles it halved the merged clusters (15 -> 8; it leaves those no larger
  /// than one object) and changed no single object's grasp (docs/clutter.md). A single object longer than
  /// split_max_size seen whole (four views) can be cut: SynthesisOptions.paper() turns the rule off.
  bool split_touching = true;
  double split_voxel_resolution = 0.004;  ///< m: rule 1, the supervoxels' voxel (at least voxel_size)
  double split_seed_resolution = 0.015;   ///< m: rule 1, the supervoxels' seed spacing
  /// rad: rule 1, a crease concave by less than this is no cut (20 degrees; LCCP's usual 10 left one more merged
  /// cluster on the development piles, 9 against 8)
  double split_concavity_tolerance = 0.35;
  /// rule 2: a piece with fewer points goes back (150 voxels, about a 4 x 4 cm face at 3 mm; on the development
  /// scenes at 10 degrees, 60 left more pieces, pile 31 against 22, and 250 missed more pile objects, 6 against 4)
  int split_min_points = 150;
  /// m: only clusters larger than this are cut, and pieces re-join within it (rule 3): the largest object the
  /// clutter lists hold, as join_max_size
  double split_max_size = 0.15;
  /// m: with a point target, the split rule is tried again on the segment the point names, gated at this size instead
  /// of split_max_size (split_object_near; with split_touching): the user says one object is there. Of the 27
  /// neighbours lifted instead of a named object from the depth image on the development scenes, 26 came from one
  /// segment of both, no larger than one object; with it 12 (docs/one-view.md, "The named segment split again").
  double split_named_max_size = 0.12;
  /// The model of what the cameras saw (Segmentation::visibility, built when viewpoints are given): m within
  /// which a point is on the observed surface, and rad per bin of each view's range image (VisibilitySettings).
  /// 8 mm, not the model's own 5 mm: a scene's cloud carries its camera's depth noise and a range image's bin
  /// its nearest point, and the completion judged against it lifted most on the development objects at 8 mm
  /// (one view, clutter_dev, GMM: 71.7% at 5 mm, 80.8% at 8, 76.7% at 10, 74.2% at 12; docs/one-view.md).
  double visibility_tolerance = 0.008;
  double visibility_resolution = VisibilitySettings{}.angular_resolution;
  /// px: a depth image's scene (segment_depth) keeps in its visibility model the image median-filtered over
  /// (2 r + 1)^2 pixels, r this (0: the image as it is, in [0, 5]): lone pixels at an object's outline that took the
  /// depth of the table behind would otherwise see through the object and refute its completion. 1 by default: on
  /// the development objects (one view, GMM, 300 attempts) it lifted 84.0% under the paper's depth noise against
  /// 71.3% without (clean 88.7 / 89.3%), 2 lifted less (docs/one-view.md).
  int visibility_median_window = 1;
  /// A depth image's scene (segment_depth): pixels per block side of the image-space subsampling, 0 = chosen
  /// per image, the largest block whose side at the median depth of the returns stays within half a voxel_size.
  int image_stride = 0;
  /// A depth image's scene: pixels per block side of the points the support plane is searched on (RANSAC and the
  /// rule need the table's extent, not its every point); the objects are then made of the image_stride blocks
  /// above it. At most image_stride: the plane is searched on those.
  int plane_image_stride = 4;
};

/// One object: a Euclidean cluster above the support plane.
struct SceneObject {
  int index = 0;         ///< its label in Segmentation::labels and its place in Segmentation::objects
  Eigen::VectorXi rows;  ///< its rows of Segmentation::points
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Vector3d obb_center = Eigen::Vector3d::Zero();  ///< oriented bounding box (principal axes)
  /// columns: the box's axes in the cloud's frame, by decreasing variance of the points, right-handed
  Eigen::Matrix3d obb_rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d obb_extents = Eigen::Vector3d::Zero();  ///< full side lengths along those axes (m)
  std::size_t n_points = 0;
};

/// What the support plane rule saw of one RANSAC candidate (in the order found).
struct PlaneCandidate {
  Eigen::Vector4d plane = Eigen::Vector4d::Zero();  ///< oriented towards the cameras, (a, b, c) unit
  std::size_t n_inliers = 0;
  double inlier_fraction = 0.0;  ///< rule 1
  double camera_height = 0.0;    ///< rule 2: mean height of the cameras above it (m)
  double behind_fraction = 0.0;  ///< rule 3
  double margin = 0.0;           ///< rule 4: least reach of the inliers beyond the footprint (m)
  bool accepted = false;
  int refused_by = 0;  ///< the rule (1-4) that refused it; 0 when accepted
  std::string reason;  ///< why it was refused, in words (empty when accepted)
};

/// Wall time (s) of each step of segment_scene; the table cut, outliers and clusters are summed over the
/// candidates the support rule tried (each is judged on the objects above it).
struct SegmentationTimes {
  double voxel = 0;       ///< the voxel grid and the sources of its centroids
  double candidates = 0;  ///< RANSAC candidates and rules 1-3
  double table_cut = 0;   ///< the points above the table_clearance
  double outliers = 0;    ///< statistical outlier removal on them
  double clusters = 0;    ///< Euclidean clusters (and rule 4's footprint)
  double visibility = 0;  ///< the model of what the cameras saw
  double merge = 0;       ///< the merge rule
  double join = 0;        ///< the join rule (a depth image: with the pooled image it judges gaps on)
  double split = 0;       ///< the split rule
  double objects = 0;     ///< the objects described, ordered and written out
};

struct Segmentation {
  /// a x + b y + c z + d = 0, (a, b, c) unit towards the cameras; zero when there is no plane
  Eigen::Vector4d plane = Eigen::Vector4d::Zero();
  bool plane_found = false;  ///< found by the rule
  bool plane_given = false;  ///< given by the caller (then plane_found is false)
  Vec3Array points;          ///< the objects' points (voxelised), grouped by object
  Eigen::VectorXi labels;    ///< per point, its object's index
  Eigen::VectorXi sources;   ///< per point, the input row whose per-point data it carries (CleanupResult)
  /// Ordered by decreasing point count, ties by centroid x, then y, then z: index 0 is the largest.
  std::vector<SceneObject> objects;
  std::vector<PlaneCandidate> candidates;  ///< the rule's figures (empty with a given plane)
  /// What the cameras saw (one view per distinct viewpoint, from the voxelised cloud, table included); null
  /// when no viewpoint was given (a cloud's own frame says nothing of where its camera was looking from).
  std::shared_ptr<const VisibilityModel> visibility;
  std::size_t n_input = 0, n_after_voxel = 0;
  /// dropped as the table: within table_clearance of it, behind it, or in a cluster within its noise
  std::size_t n_plane = 0;
  std::size_t n_outliers = 0;        ///< dropped by the outlier removal
  std::size_t n_small_clusters = 0;  ///< points of clusters under min_cluster_size (or over the maximum)
  /// The points the clean-up dropped (voxelised): the statistical outliers and the clusters dropped for their size
  /// (under min_cluster_size or over max_cluster_size), of the points above table_clearance when there is a plane
  /// (a noisy table's small fragments above it among them), of all points when there is none. No object's; what a
  /// closing finger may still meet (scene synthesis' target-first check closes on them).
  Vec3Array dropped = Vec3Array(0, 3);
  std::size_t n_merged = 0;  ///< clusters joined to another by the merge rule
  std::size_t n_joined = 0;  ///< clusters joined to another by the join rule
  std::size_t n_split = 0;   ///< clusters added by the split rule (pieces cut off another)
  std::size_t n_output = 0;
  double seconds = 0.0;     ///< wall time of the whole segmentation
  SegmentationTimes times;  ///< and of each step
};

/// The support plane and the objects of `points` (N, 3) seen from `viewpoints` (0 x 3: none, 1 x 3 or
/// N x 3), with `plane` the known support when given. Throws std::invalid_argument (the message names
/// the cause) on empty or non-finite points, viewpoints of the wrong shape or non-finite, bad settings,
/// a degenerate plane, and when no object point is left ("no object above the support plane").
Segmentation segment_scene(const Vec3Array& points, const Vec3Array& viewpoints,
                           const SegmentationSettings& settings = {},
                           const std::optional<Eigen::Vector4d>& plane = std::nullopt);

/// The split rule (above) on the object of `scene` a point target names (select_targets: the one whose points come
/// nearest `point`, within kPointTargetMaxDistance), gated at
/// settings.split_named_max_size instead of split_max_size (its other settings as given): a point target names one
/// object, so a segment there no larger than one object may still hold two (the named object and a neighbour it
/// touches, which the size gate leaves whole). The rule's limit: a single object that long with a concave crease (a
/// mug with its handle) is cut too, and the piece nearest the point is its target. viewpoints: one row, or one per
/// point of the scene (none: nothing is cut). When it cuts, the objects are described, ordered and indexed again as
/// segment_scene does (n_split counts the pieces added). Returns the pieces added (0: the scene unchanged). Throws
/// std::invalid_argument for a non-finite point, a point that names no object (select_targets' error) or viewpoints
/// of another number of rows.
std::size_t split_object_near(Segmentation& scene, const Vec3Array& viewpoints, const Eigen::Vector3d& point,
                              const SegmentationSettings& settings);

}  // namespace graspmix
