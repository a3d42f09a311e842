#pragma once
// The unseen side of one segmented object, completed by a stated rule (docs/design.md, "Completion").
//
// A camera sees an object's front and top; grasp synthesis needs its back too. complete_object proposes
// hypotheses of the whole object from its observed points and keeps the one the views contradict least:
//   1. Mirror (Bohg et al. 2011, "Mind the gap"): a plane perpendicular to the support plane, its normal
//      within mirror_angle_steps * mirror_angle_step of either principal axis of the footprint (the points
//      projected onto the table) and turned away from the camera, its offset between the footprint's middle
//      along that normal and mirror_max_depth behind its far edge. The observed points and their normals
//      mirrored through it are the hypothesis.
//   2. Rotation: a vertical axis through the circle fitted (Kasa least squares, trimmed) to the footprint's
//      outline; refused unless the outline's inliers are circle_min_inliers of it and within circle_max_rms.
//      The observed points' profile (height, radius, normal), binned at `spacing`, swept around the axis is
//      the hypothesis.
//   3. Extrusion (the fallback): below the highest observed point of every outline cell of the footprint, a
//      wall straight down to the table, each column stopped at its first seen-free sample; normals horizontal,
//      out of the footprint.
// Each hypothesis is scored on at most max_scoring_points of its points (an even subsample), classified
// by the visibility model: free_fraction (SeenFree: space a camera saw empty, which no part of the object can
// be in), surface_fraction (on the observed surface: the hypothesis predicts what was seen) and
// unseen_fraction (behind the observed surface: what the hypothesis adds), each of the points some view
// says something about. score = surface_fraction - free_weight * free_fraction. A hypothesis is accepted
// when free_fraction <= max_free_fraction, unseen_fraction >= min_unseen_fraction and a view says something
// about at least half of its points. The winner: an accepted rotation unless an accepted mirror scores more than
// rotation_margin above it (a surface of revolution is mirror symmetric about every plane through its axis, so
// where both explain the views about equally the stronger symmetry is taken), else the best-scoring accepted
// mirror, else the extrusion if it adds any point, else None.
//
// The completion is the winner's points where the views say Unseen or Surface (never SeenFree, never where
// no view says anything: nothing beyond what the images could have seen), at least min_height above the
// plane, thinned to one per `spacing` cell and none within observed_clearance of an observed point (the surface the
// camera saw is not doubled). An object the image border cuts (a pinhole view whose image edge
// lies within border_margin px of an observed point) is completed all the same, with a warning.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "graspmix/core/plane.hpp"
#include "graspmix/core/types.hpp"
#include "graspmix/perception/segmentation.hpp"
#include "graspmix/perception/visibility.hpp"

namespace graspmix {

enum class CompletionKind : std::uint8_t { None = 0, Mirror = 1, Rotation = 2, Extrusion = 3 };

struct CompletionSettings {
  /// m: the completed points' spacing (one per cubic cell of this side), the profile's bins and the footprint's
  /// cells; segment_scene's voxel (3 mm), so completed and observed points are alike.
  double spacing = 0.003;
  /// A hypothesis with more of its points in seen-free space is refused, in [0, 1]: a few points for the depth
  /// and pixel noise at silhouettes. (0.1 admits the true cylinder under the simulated camera's noise, 4-8 %, but
  /// also a rotation about a 9 x 6 cm box; see docs/design.md, "Completion".)
  double max_free_fraction = 0.05;
  /// A hypothesis with less of its points in unseen space adds too little to be one, in [0, 1] (keeps the
  /// mirror from planes that map the visible side onto itself).
  double min_unseen_fraction = 0.15;
  /// score = surface_fraction - free_weight * free_fraction (>= 0): a contradiction costs more than an agreement.
  double free_weight = 4.0;
  /// rad: the step between the mirror planes' orientations around each principal axis of the footprint (> 0).
  double mirror_angle_step = 0.07;
  /// Orientations each side of each principal axis (0..20): 3 steps of 0.07 rad cover +-12 degrees.
  int mirror_angle_steps = 3;
  /// m: the mirror plane lies at most this far behind the footprint's far edge (>= 0): for objects whose top
  /// the camera does not see.
  double mirror_max_depth = 0.05;
  /// m: the rotation's outline points within this RMS of their circle (> 0).
  double circle_max_rms = 0.003;
  /// The fraction of the outline within 2 circle_max_rms of its circle for a rotation, in [0, 1].
  double circle_min_inliers = 0.7;
  /// m: no rotation about a circle larger than this (> 0): a straight outline fits a huge circle.
  double max_radius = 0.25;
  /// m: the neighbourhood of the observed points' normals (PCA of the points within it; > spacing).
  double normal_radius = 0.01;
  /// Points each hypothesis is scored on (an even subsample; >= 16): the scoring's cost.
  int max_scoring_points = 160;
  /// px: an observed point this close to a pinhole view's image edge sets the border warning (>= 0).
  double border_margin = 2.0;
  /// m: completed points lower than this above the support plane are dropped, as the segmentation drops observed
  /// ones (the table's clearance: a finger reaching the table is the plane term's to judge). >= 0.
  double min_height = kTableClearance;
  /// The rotation wins over the best accepted mirror unless the mirror's score is higher by more than this, in
  /// [0, 1]: a surface of revolution is mirror symmetric about every plane through its axis, so where both explain
  /// the views about equally the stronger symmetry is taken; a box whose outline an arc happens to fit is not one.
  double rotation_margin = 0.05;
  /// m: no completed point within this of an observed point (> 0): the surface the camera saw is not doubled by
  /// a layer just behind it (two voxels: the observed surface's own thickness with the depth noise).
  double observed_clearance = 0.006;
};

struct CompletionHypothesis {
  CompletionKind kind = CompletionKind::None;
  double score = 0;             ///< surface_fraction - free_weight * free_fraction
  double free_fraction = 0;     ///< of the scored points a view says something about: SeenFree
  double surface_fraction = 0;  ///< ... on the observed surface (Surface)
  double unseen_fraction = 0;   ///< ... behind it (Unseen)
  double known_fraction = 0;    ///< of the scored points: some view says something (finite signed distance)
  bool accepted = false;        ///< passes the header's acceptance rule
  /// Mirror: the plane [a, b, c, d] (unit normal away from the camera). Rotation: [x, y, z, r], the axis's foot
  /// on the support plane and the circle's radius (m); the axis is the plane's normal. Extrusion: zeros.
  Eigen::Vector4d plane_or_axis = Eigen::Vector4d::Zero();
};

struct Completion {
  CompletionKind kind = CompletionKind::None;  ///< the winner's kind
  double score = 0;                            ///< the winner's score (0 for None)
  Vec3Array points;                            ///< (M, 3) the completed points only, world frame
  Vec3Array normals;                           ///< (M, 3) unit, out of the object
  /// Every hypothesis scored (the mirrors' best per principal axis), the winner first when there is one.
  std::vector<CompletionHypothesis> hypotheses;
  std::string warning;  ///< why completion was limited (object cut by the image border), empty if nothing
  double seconds = 0;   ///< s, wall time
};

/// The completion of one object (header comment) from its observed points (N, 3; voxelised, world frame), the
/// support plane a x + b y + c z + d = 0 ((a, b, c) unit, towards the cameras) and what the cameras saw.
/// Throws std::invalid_argument naming the cause for no points, a non-finite point, a plane that is not
/// finite or whose normal is not unit, a camera in or below the plane, points mostly below the plane, a
/// model with no view, or settings out of range.
Completion complete_object(const Eigen::Ref<const Vec3Array>& points, const Eigen::Vector4d& plane,
                           const VisibilityModel& visibility, const CompletionSettings& settings = {});

/// Throws std::invalid_argument naming the field unless the settings are in range.
void check_completion_settings(const CompletionSettings& s);

/// Every object of a segmented scene completed.
struct SceneCompletion {
  std::vector<std::optional<Completion>> completions;  ///< per object; unset where nothing was completed
  std::vector<std::string> notes;  ///< why an object (or every object) was not completed, and the warnings
  double seconds = 0;              ///< s, wall time
};

/// Each object of `scene` completed from its visibility model and plane. Without a visibility model (no
/// viewpoint) or a plane nothing is completed and a note says why; an object complete_object refuses (e.g. seen by
/// a camera in the support plane) stays as seen, with a note naming it and why. Throws std::invalid_argument for
/// settings out of range (whether or not anything could be completed).
SceneCompletion complete_scene(const Segmentation& scene, const CompletionSettings& settings = {});

}  // namespace graspmix
