#pragma once
// synthesize_scene: the whole path from one camera's view (a depth image or an organized cloud with the camera's
// pose) or a cloud to ranked grasps, in one call:
//
//   1. the scene: the support plane and the objects (segment_depth, segment_organized or segment_scene), each
//      object's unseen side completed (complete_object; settings.completion), the target objects chosen (Target);
//   2. what every target shares: the scene's occupancy map (collision model "occupancy": OctoMap's rays of the
//      whole input, table included) or the surface model's map of unseen space (its visibility model baked over
//      the objects' box: the collision settings' unseen_weight), the collision expert W on every object's
//      observed and completed points and the plane, the clear approach's collision test (balls of
//      approach.clearance), the kinematic expert (its plane oriented towards the objects), the approach-axis
//      expert (when an axis is asked for) and the caller's experts, in this order;
//   3. per target object: its surface features (normals towards the cameras that saw each point, a completed
//      point's towards a viewpoint COMPLETED_VIEW_DISTANCE out along its outward normal; the observed points
//      first), each point's prior weight in the query densities (1 observed, query.completed_weight completed);
//      per grasp type: the hard "clear_of_neighbours" (in a scene of several objects: the hand, at the grasp and
//      at its pre-grasp, holds no point of another object), the hard clear approach, the soft grasp depth
//      (grasp_depth.hpp) and the soft contact quality on the target's own surface, then
//      GraspSynthesizer::synthesize (query densities, sampling, ranking, annealing) with the settings' seed;
//   4. every target's and type's grasps ranked together by log L (a stable sort: equal scores keep the targets'
//      and types' order). A type with a log_reference (a model of several grasp types) has it subtracted from
//      its grasps' log L and recorded as the term kTypeReferenceTerm = -log_reference, so types compare.
//
// This is what graspmix.GraspModel.synthesize runs (Python reads the input and builds the GraspSet from the
// result); a C++ program calls it with the library's defaults (SceneSynthesisSettings{}) as examples/cpp shows.
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "graspmix/core/types.hpp"
#include "graspmix/grasp/approach.hpp"
#include "graspmix/grasp/collision.hpp"
#include "graspmix/grasp/contact_quality.hpp"
#include "graspmix/grasp/experts.hpp"
#include "graspmix/grasp/grasp_depth.hpp"
#include "graspmix/grasp/occupancy.hpp"
#include "graspmix/grasp/synthesis.hpp"
#include "graspmix/perception/camera.hpp"
#include "graspmix/perception/completion.hpp"
#include "graspmix/perception/segmentation.hpp"
#include "graspmix/perception/surface.hpp"
#include "graspmix/perception/targets.hpp"

namespace graspmix {

/// A depth image (camera.height() x camera.width(), metres along z; NaN, 0, +inf: no return) of `camera` posed at
/// T_world_camera.
struct DepthView {
  DepthImage depth;
  PinholeCamera camera;
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
};

/// An organized cloud (camera.height() * camera.width(), 3) in the sensor frame (x right, y down, z forward;
/// NaN rows: no return) with its intrinsics (fit_pinhole's when the driver gives none), posed at T_world_camera.
struct OrganizedView {
  Vec3Array points;
  PinholeCamera camera;
  Eigen::Isometry3d T_world_camera = Eigen::Isometry3d::Identity();
};

/// Any cloud (N, 3) in the world frame and the cameras that saw it: viewpoints 0 x 3 (unknown: nothing is
/// completed, no space is unseen), 1 x 3 (one camera) or N x 3 (each point's).
struct CloudInput {
  Vec3Array points;
  Vec3Array viewpoints;
};

using SceneInput = std::variant<DepthView, OrganizedView, CloudInput>;

/// m: a completed point's normal is oriented towards a virtual viewpoint this far out along its outward normal.
inline constexpr double kCompletedViewDistance = 1.0;
/// The term of log L that makes the scores of a model's grasp types comparable: -log L_ref of the grasp's type.
inline constexpr const char* kTypeReferenceTerm = "type_reference";
/// The term of log L that rejects a grasp whose finger meets another object before the target
/// (ContactQualitySettings::target_first): 0 or -inf.
inline constexpr const char* kTargetFirstTerm = "target_first";
/// m: target_side's radius by default: the target-first check does not count as the target's its completed points
/// within this of what it counts as other objects' (a completion may reach behind a neighbour's seen surface, and a
/// finger that meets it there meets the neighbour). synthesize_scene takes the completion's observed_clearance (the
/// same two voxels by default: no completed point within it of the object's own observed points either).
inline constexpr double kTargetSideClearance = 0.006;

/// Object `index`'s surface features as synthesize_scene computes them: its observed points (normals towards the
/// camera that saw each, `viewpoints` one row per scene point; 0 rows: unknown, normals propagated), then its
/// completed points (completions[index]; normals towards a viewpoint kCompletedViewDistance out along their
/// outward normal). Throws std::invalid_argument for an index out of range, completions not one per object or
/// viewpoints not one per point, and as compute_surface_features does.
SurfaceCloud object_surface(const Segmentation& scene, const Vec3Array& viewpoints,
                            const std::vector<std::optional<Completion>>& completions, int index,
                            const SurfaceFeatureSettings& settings);

/// Each point of a target's surface, its prior weight in the query densities: 1 where observed (an index below
/// n_observed, as object_surface orders them), completed_weight where completed; empty when nothing is completed.
Eigen::VectorXd query_weights(const SurfaceCloud& surface, Eigen::Index n_observed, double completed_weight);

/// The rows of a target's surface (object_surface's order: n_observed observed points first) the target-first check
/// counts as the target's: every observed point, and every completed point at least `radius` from each row of
/// `others` (what the check closes on as other objects': their observed points and the points the segmentation
/// dropped that are not the target's). Ascending. Throws std::invalid_argument for a radius not finite and > 0 or a
/// surface without one index per point.
Eigen::VectorXi target_side(const SurfaceCloud& surface, Eigen::Index n_observed, const Vec3Array& others,
                            double radius = kTargetSideClearance);

/// One grasp type of a model: its synthesiser (contact models and configuration model), its name and, in a
/// model of several types, its reference score log L_ref (unset: one type, scores as they are).
struct SceneGraspType {
  std::shared_ptr<const GraspSynthesizer> synthesizer;
  std::string name;
  std::optional<double> log_reference;
};

/// Every setting of the path; each part's defaults are its struct's (the library's defaults); an optional part
/// unset turns its step off. segmentation.voxel_size and features.radius must be the model's (the features are
/// compared with the demonstration's).
struct SceneSynthesisSettings {
  SegmentationSettings segmentation;
  std::optional<CompletionSettings> completion = CompletionSettings{};
  SurfaceFeatureSettings features;
  SynthesizerSettings synthesizer;
  CollisionSettings collision;
  OccupancySettings occupancy;
  std::optional<KinematicFeasibilitySettings> kinematic = KinematicFeasibilitySettings{};
  AxisAlignmentSettings axis_alignment;
  std::optional<ClearApproachSettings> approach = ClearApproachSettings{};
  std::optional<ContactQualitySettings> contact_quality = ContactQualitySettings{};
  std::optional<GraspDepthSettings> grasp_depth = GraspDepthSettings{};
};

/// What a call asks besides the settings.
struct SceneRequest {
  std::optional<Eigen::Vector4d> plane;                ///< a known support plane instead of the one searched for
  Target target;                                       ///< the objects to grasp
  std::optional<Eigen::Vector3d> approach_axis;        ///< prefer wrists approaching along it (axis_alignment)
  KinematicFeasibilityExpert::Reachability reachable;  ///< the hard reachability test (needs settings.kinematic)
  std::vector<std::shared_ptr<const Expert>> experts;  ///< the caller's experts, after the standard ones
};

/// One ranked grasp: the synthesiser's, with its object (an index of scene.objects) and grasp type (an index of
/// the types given).
struct SceneGrasp {
  Grasp grasp;
  int object = 0;
  int type = 0;
};

/// Wall times (s) of the path's steps.
struct SceneSynthesisTiming {
  double segmentation = 0;          ///< the scene, the completion and the choice of targets
  std::optional<double> occupancy;  ///< the occupancy map or the map of unseen space; unset: no map made
  /// the targets' surface features and the experts built on them (GraspModel.synthesize reports as "features"
  /// what its total leaves of the other stages: Python's share too)
  double features = 0;
  double query = 0, sampling = 0, optimisation = 0;  ///< the synthesiser's stages, summed over targets and types
  double total = 0;
};

struct SceneSynthesis {
  Segmentation scene;
  Vec3Array viewpoints;  ///< the camera of every point of scene.points (0 rows: unknown)
  /// every object's completion (settings.completion; without it, none and no note)
  SceneCompletion completion;
  std::vector<int> targets;            ///< the objects grasps were sampled on
  std::vector<SurfaceCloud> surfaces;  ///< per target, its surface (observed points, then completed ones)
  /// per type: the names of Grasp::log_terms() (SynthesisResult::term_names(), then kTargetFirstTerm when the scene
  /// has other objects and the check is on, then kTypeReferenceTerm when the type has a log_reference)
  std::vector<std::vector<std::string>> term_names;
  std::vector<SceneGrasp> grasps;  ///< best first
  SceneSynthesisTiming timing;
  int evaluations = 0;  ///< grasps scored in all
  int rejected = 0;     ///< samples a hard constraint rejected
};

/// The path of the header comment. Throws std::invalid_argument naming the cause for bad input (as the
/// segmentation, the completion's settings and the experts' constructors do), no grasp types or a type without
/// a synthesiser, a collision model "occupancy" without viewpoints, reachable without the kinematic expert, and
/// as select_targets does.
SceneSynthesis synthesize_scene(const SceneInput& input, const std::vector<SceneGraspType>& types,
                                const SceneSynthesisSettings& settings = {}, const SceneRequest& request = {});

}  // namespace graspmix
