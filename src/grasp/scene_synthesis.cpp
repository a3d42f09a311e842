#include "graspmix/grasp/scene_synthesis.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "core/parallel_rows.hpp"
#include "grasp/target_first.hpp"
#include "graspmix/core/plane.hpp"
#include "graspmix/grasp/topdown_seeds.hpp"
#include "graspmix/perception/depth_scene.hpp"

namespace graspmix {
namespace {

using Clock = std::chrono::steady_clock;
using ExpertPtr = std::shared_ptr<const Expert>;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

/// The scene's plane, or none.
std::optional<Eigen::Vector4d> plane_of(const Segmentation& s) {
  if (s.plane_found || s.plane_given) return s.plane;
  return std::nullopt;
}

/// The rows of `a` named by `rows`.
Vec3Array rows_of(const Vec3Array& a, const Eigen::VectorXi& rows) { return a(rows, Eigen::all); }

Vec3Array stacked(const Vec3Array& a, const Vec3Array& b) {
  Vec3Array out(a.rows() + b.rows(), 3);
  out << a, b;
  return out;
}

/// Each kept point's camera: the view's position, or the cloud's viewpoint(s) carried to the points kept.
Vec3Array point_viewpoints(const Segmentation& scene, const Vec3Array& viewpoints) {
  const Eigen::Index n = scene.points.rows();
  if (viewpoints.rows() == 0) return Vec3Array(0, 3);
  if (viewpoints.rows() == 1) return viewpoints.replicate(n, 1);
  return rows_of(viewpoints, scene.sources);
}

/// The scene of the input, and the cameras of its points as given (0, 1 or N rows).
std::pair<Segmentation, Vec3Array> segment_input(const SceneInput& input, const SegmentationSettings& s,
                                                 const std::optional<Eigen::Vector4d>& plane) {
  if (const auto* d = std::get_if<DepthView>(&input))
    return {segment_depth(d->depth, d->camera, d->T_world_camera, s, plane),
            d->T_world_camera.translation().transpose()};
  if (const auto* o = std::get_if<OrganizedView>(&input))
    return {segment_organized(o->points, o->camera, o->T_world_camera, s, plane),
            o->T_world_camera.translation().transpose()};
  const auto& c = std::get<CloudInput>(input);
  return {segment_scene(c.points, c.viewpoints, s, plane), c.viewpoints};
}

/// (points, viewpoints) of the whole input, table included, in the world frame: what OctoMap's rays are cast from.
std::pair<Vec3Array, Vec3Array> whole_cloud(const SceneInput& input) {
  const auto world = [](const Vec3Array& sensor, const Eigen::Isometry3d& T) {
    Vec3Array out(sensor.rows(), 3);
    Eigen::Index n = 0;
    for (Eigen::Index i = 0; i < sensor.rows(); ++i)
      if (sensor.row(i).allFinite()) out.row(n++) = (T * Eigen::Vector3d(sensor.row(i).transpose())).transpose();
    out.conservativeResize(n, 3);
    return std::make_pair(out, Vec3Array(T.translation().transpose()));
  };
  if (const auto* d = std::get_if<DepthView>(&input)) return world(d->camera.back_project(d->depth), d->T_world_camera);
  if (const auto* o = std::get_if<OrganizedView>(&input)) return world(o->points, o->T_world_camera);
  const auto& c = std::get<CloudInput>(input);
  return {c.points, c.viewpoints};
}

/// Object i's completion when it added points, else null.
const Completion* completed(const std::vector<std::optional<Completion>>& completions, int i) {
  const auto& c = completions[static_cast<std::size_t>(i)];
  return c && c->points.rows() > 0 ? &*c : nullptr;
}

/// Whether the target-first check runs (it needs the contact quality's closing).
bool target_first_on(const SceneSynthesisSettings& settings) {
  return settings.contact_quality && settings.contact_quality->target_first;
}

/// The objects' observed points and every completed point, but object `without`'s (-1: none left out).
Vec3Array solid_points(const Segmentation& scene, const std::vector<std::optional<Completion>>& completions,
                       int without = -1) {
  std::vector<const Completion*> added;
  Eigen::Index n = (scene.labels.array() != without).count();
  for (std::size_t k = 0; k < scene.objects.size(); ++k)
    if (const Completion* c = completed(completions, static_cast<int>(k)); c && static_cast<int>(k) != without) {
      added.push_back(c);
      n += c->points.rows();
    }
  Vec3Array out(n, 3);
  Eigen::Index r = 0;
  for (Eigen::Index i = 0; i < scene.points.rows(); ++i)
    if (scene.labels[i] != without) out.row(r++) = scene.points.row(i);
  for (const Completion* c : added) {
    out.middleRows(r, c->points.rows()) = c->points;
    r += c->points.rows();
  }
  return out;
}

/// W against `points` and the plane: the occupancy model on `occupancy` when given, else the surface model
/// (charging `unseen`'s unknown cells when given).
std::shared_ptr<CollisionExpert> collision_on(const std::shared_ptr<const Hand>& hand, const Vec3Array& points,
                                              const std::optional<Eigen::Vector4d>& plane, CollisionSettings s,
                                              const std::shared_ptr<OccupancyMap>& occupancy,
                                              const std::shared_ptr<OccupancyMap>& unseen = nullptr) {
  if (occupancy) return std::make_shared<CollisionExpert>(hand, occupancy, points, plane, s);
  s.model = CollisionModel::Surface;
  return std::make_shared<CollisionExpert>(hand, points, plane, s, unseen);
}

/// The standard experts every target shares, then the caller's: kinematic (on `table`, the scene's plane oriented so
/// the objects stand above it), approach axis, the request's.
std::vector<ExpertPtr> shared_experts(const std::shared_ptr<const Hand>& hand,
                                      const std::optional<Eigen::Vector4d>& table,
                                      const SceneSynthesisSettings& settings, const SceneRequest& request) {
  std::vector<ExpertPtr> out;
  if (settings.kinematic) {
    out.push_back(std::make_shared<KinematicFeasibilityExpert>(hand, table, *settings.kinematic, request.reachable));
  } else if (request.reachable) {
    throw std::invalid_argument(
        "reachable needs the kinematic expert (its settings are off: SynthesisOptions.kinematic is None)");
  }
  if (request.approach_axis)
    out.push_back(std::make_shared<AxisAlignmentExpert>(*request.approach_axis, settings.axis_alignment, hand.get()));
  out.insert(out.end(), request.experts.begin(), request.experts.end());
  return out;
}

void check_types(const std::vector<SceneGraspType>& types) {
  if (types.empty()) throw std::invalid_argument("synthesize_scene: no grasp type to sample");
  for (const auto& t : types) {
    if (!t.synthesizer) throw std::invalid_argument("synthesize_scene: grasp type '" + t.name + "' has no synthesiser");
    const Hand& h = t.synthesizer->hand();
    const Hand& first = types.front().synthesizer->hand();
    if (h.joint_names() != first.joint_names() || h.link_names() != first.link_names())
      throw std::invalid_argument("synthesize_scene: grasp type '" + t.name + "' has another hand than the first");
  }
}

/// What every target of a scene shares: the hand, the collision expert W, the clear approach's collision test and
/// the experts before each target's own.
struct Shared {
  std::shared_ptr<const Hand> hand;
  std::optional<Eigen::Vector4d> table;  ///< the scene's plane oriented so the objects stand above it (none: no plane)
  std::shared_ptr<CollisionExpert> collision, approach;
  std::vector<ExpertPtr> experts;
  Eigen::VectorXi dropped_owners;  ///< the target-first check's: detail::dropped_owners (empty when it is off)
};

Shared shared_part(const SceneInput& input, std::shared_ptr<const Hand> hand, const SceneSynthesisSettings& settings,
                   const SceneRequest& request, SceneSynthesis& out) {
  Shared shared;
  shared.hand = std::move(hand);
  const auto plane = plane_of(out.scene);
  if (plane) shared.table = orient_plane(*plane, out.scene.points, PlaneSide::Mean);
  std::shared_ptr<OccupancyMap> occupancy, unseen;
  if (settings.collision.model == CollisionModel::Occupancy) {
    const auto [points, viewpoints] = whole_cloud(input);
    if (viewpoints.rows() == 0)
      throw std::invalid_argument(
          "the occupancy collision model needs the cameras' positions: viewpoints= (or the PCD's VIEWPOINT, "
          "--viewpoint)");
    occupancy = std::make_shared<OccupancyMap>(points, viewpoints, out.scene.points, plane, settings.occupancy);
    out.timing.occupancy = occupancy->stats().seconds;
  } else if (settings.collision.unseen_weight > 0 && out.scene.visibility) {
    unseen = std::make_shared<OccupancyMap>(*out.scene.visibility, out.scene.points, plane, settings.occupancy);
    out.timing.occupancy = unseen->stats().seconds;
  }
  const auto t_experts = Clock::now();  // the map has its own stage: features counts the experts from here
  // observed and completed: the hand stays out of both
  const Vec3Array solid = solid_points(out.scene, out.completion.completions);
  // W's expert and the clear approach's, each on a thread of its own: each is milliseconds of serial work (the
  // solid volume, the grid of the points) on a scene of several objects.
  detail::parallel_rows<detail::NoState>(
      settings.approach ? 2 : 1,
      [&](detail::NoState&, std::int64_t i) {
        if (i == 0) {
          shared.collision = collision_on(shared.hand, solid, plane, settings.collision, occupancy, unseen);
          return;
        }
        CollisionSettings s = settings.collision;
        s.point_radius = settings.approach->clearance;
        shared.approach = collision_on(shared.hand, solid, plane, s, occupancy);
      },
      detail::RowOrder::AsThreadsFree);
  shared.experts = shared_experts(shared.hand, shared.table, settings, request);
  if (target_first_on(settings) && out.scene.objects.size() > 1)
    shared.dropped_owners = detail::dropped_owners(out.scene);
  out.timing.features += seconds_since(t_experts);
  return shared;
}

/// Object i's surface and, per grasp type, its own experts and the synthesiser's grasps, added to `out`.
void synthesize_target(int i, const std::vector<SceneGraspType>& types, const SceneSynthesisSettings& settings,
                       const Shared& shared, SceneSynthesis& out) {
  const auto t0 = Clock::now();
  SurfaceCloud surface = object_surface(out.scene, out.viewpoints, out.completion.completions, i, settings.features);
  const auto n_observed = static_cast<Eigen::Index>(out.scene.objects[static_cast<std::size_t>(i)].rows.size());
  const Eigen::VectorXd weights = query_weights(surface, n_observed, settings.synthesizer.query.completed_weight);
  std::shared_ptr<CollisionExpert> neighbours;
  // The other objects' observed points: the top-down seeds look for them near; target_first closes on them and on the
  // points the segmentation dropped that are not the target's.
  const bool seeded = settings.synthesizer.sampling.topdown_seeds && shared.table;
  const bool first_check = target_first_on(settings);
  Vec3Array others_seen(0, 3), others_met(0, 3);
  if (out.scene.objects.size() > 1) {
    neighbours = collision_on(shared.hand, solid_points(out.scene, out.completion.completions, i), std::nullopt,
                              settings.collision, nullptr);
    if (seeded || first_check)
      others_seen = solid_points(out.scene, std::vector<std::optional<Completion>>(out.scene.objects.size()), i);
    if (first_check) others_met = stacked(others_seen, detail::dropped_not_of(out.scene, shared.dropped_owners, i));
  }
  // The target's side of the check: its completed points on what the check counts as others' are not the target's.
  const double side_clearance = settings.completion ? settings.completion->observed_clearance : kTargetSideClearance;
  const Eigen::VectorXi mine =
      others_met.rows() > 0 ? target_side(surface, n_observed, others_met, side_clearance) : Eigen::VectorXi();
  out.timing.features += seconds_since(t0);
  for (std::size_t k = 0; k < types.size(); ++k) {
    const auto te = Clock::now();
    const ConfigModel& config = types[k].synthesizer->config_model();
    std::vector<ExpertPtr> experts = shared.experts;
    if (neighbours) experts.push_back(std::make_shared<CollisionFreeExpert>(neighbours, config, "clear_of_neighbours"));
    if (shared.approach)
      experts.push_back(std::make_shared<ClearApproachExpert>(shared.approach, config, *settings.approach));
    // The grasp depth before the contact quality: annealing skips the last expert where its bound shows a proposal
    // refused (Expert::max_log_value), and the contact quality is the expensive one.
    if (settings.grasp_depth)
      experts.push_back(std::make_shared<GraspDepthExpert>(shared.hand, surface.points, *settings.grasp_depth));
    std::shared_ptr<const ContactQualityExpert> quality, others;
    if (settings.contact_quality) {
      quality = std::make_shared<ContactQualityExpert>(shared.hand, surface.points, surface.normals, config,
                                                       *settings.contact_quality);
      experts.push_back(quality);
      if (others_met.rows() > 0) {
        ContactQualitySettings first = *settings.contact_quality;
        first.patch_points = 0;              // its closing only: no patch reference to measure
        Vec3Array up(others_met.rows(), 3);  // its closing only: the normals score, not the contacts
        up.rowwise() = Eigen::RowVector3d::UnitZ();
        others = std::make_shared<ContactQualityExpert>(shared.hand, others_met, up, config, first);
      }
    }
    out.timing.features += seconds_since(te);
    SeedGrasps seeds;
    if (seeded) seeds = topdown_seeds(*shared.hand, config, surface.points, *shared.table, others_seen);
    SynthesisResult res = types[k].synthesizer->synthesize(surface.frames, surface.curvatures, *shared.collision,
                                                           experts, settings.synthesizer, weights, &seeds);
    out.term_names[k] = res.term_names();
    const auto add_term = [](Grasp& g, double v) {
      g.log_experts.conservativeResize(g.log_experts.size() + 1);
      g.log_experts[g.log_experts.size() - 1] = v;
      g.log_likelihood += v;
    };
    if (others) {
      out.term_names[k].push_back(kTargetFirstTerm);
      const Eigen::VectorXd first =
          mine.size() == surface.points.rows()
              ? detail::target_first(*quality, *others, res.grasps)
              : detail::target_first(
                    ContactQualityExpert(shared.hand, rows_of(surface.points, mine), rows_of(surface.normals, mine),
                                         config, *settings.contact_quality),
                    *others, res.grasps);
      for (std::size_t j = 0; j < res.grasps.size(); ++j) add_term(res.grasps[j], first[static_cast<Eigen::Index>(j)]);
      std::stable_sort(res.grasps.begin(), res.grasps.end(),
                       [](const Grasp& a, const Grasp& b) { return a.log_likelihood > b.log_likelihood; });
    }
    const std::optional<double> reference = types[k].log_reference;
    if (reference) out.term_names[k].push_back(kTypeReferenceTerm);
    for (auto& g : res.grasps) {
      if (reference) add_term(g, -*reference);
      out.grasps.push_back({std::move(g), i, static_cast<int>(k)});
    }
    out.timing.query += res.timing.query;
    out.timing.sampling += res.timing.sampling;
    out.timing.optimisation += res.timing.optimisation;
    out.evaluations += res.evaluations;
    out.rejected += res.rejected;
  }
  out.surfaces.push_back(std::move(surface));
}

}  // namespace

SurfaceCloud object_surface(const Segmentation& scene, const Vec3Array& viewpoints,
                            const std::vector<std::optional<Completion>>& completions, int index,
                            const SurfaceFeatureSettings& settings) {
  if (index < 0 || index >= static_cast<int>(scene.objects.size()))
    throw std::invalid_argument("object_surface: no object " + std::to_string(index));
  if (completions.size() != scene.objects.size() || (viewpoints.rows() && viewpoints.rows() != scene.points.rows()))
    throw std::invalid_argument("object_surface: completions and viewpoints must match the scene's objects and points");
  const Eigen::VectorXi& rows = scene.objects[index].rows;
  const Vec3Array observed = rows_of(scene.points, rows);
  if (viewpoints.rows() == 0) return compute_surface_features(observed, settings);
  const Vec3Array vp = rows_of(viewpoints, rows);
  const Completion* c = completed(completions, index);
  if (c == nullptr) return compute_surface_features(observed, settings, {}, vp);
  const Vec3Array views = c->points + kCompletedViewDistance * c->normals;
  return compute_surface_features(stacked(observed, c->points), settings, {}, stacked(vp, views));
}

Eigen::VectorXd query_weights(const SurfaceCloud& surface, Eigen::Index n_observed, double completed_weight) {
  if ((surface.indices.array() < n_observed).all()) return {};
  return (surface.indices.array() >= n_observed)
      .select(Eigen::VectorXd::Constant(surface.indices.size(), completed_weight), 1.0);
}

SceneSynthesis synthesize_scene(const SceneInput& input, const std::vector<SceneGraspType>& types,
                                const SceneSynthesisSettings& settings, const SceneRequest& request) {
  check_types(types);
  const auto t0 = Clock::now();
  SceneSynthesis out;
  // 1. The scene, its completion and the targets.
  Vec3Array given_viewpoints;
  std::tie(out.scene, given_viewpoints) = segment_input(input, settings.segmentation, request.plane);
  out.viewpoints = point_viewpoints(out.scene, given_viewpoints);
  // A point names one object: its segment is tried again by the split rule below the size gate.
  if (request.target.kind == Target::Kind::Point && settings.segmentation.split_touching &&
      split_object_near(out.scene, out.viewpoints, request.target.point, settings.segmentation) > 0)
    out.viewpoints = point_viewpoints(out.scene, given_viewpoints);
  if (settings.completion)
    out.completion = complete_scene(out.scene, *settings.completion);
  else
    out.completion.completions.assign(out.scene.objects.size(), std::nullopt);
  out.targets = select_targets(out.scene, out.viewpoints, request.target);
  out.timing.segmentation = seconds_since(t0);
  // 2. What every target shares.
  const Shared shared = shared_part(input, types.front().synthesizer->hand_ptr(), settings, request, out);
  // 3. Per target and grasp type.
  out.term_names.assign(types.size(), {});
  for (const int i : out.targets) synthesize_target(i, types, settings, shared, out);
  // 4. All grasps ranked together.
  if (out.targets.size() > 1 || types.size() > 1)
    std::stable_sort(out.grasps.begin(), out.grasps.end(), [](const SceneGrasp& a, const SceneGrasp& b) {
      return a.grasp.log_likelihood > b.grasp.log_likelihood;
    });
  out.timing.total = seconds_since(t0);
  return out;
}

}  // namespace graspmix
