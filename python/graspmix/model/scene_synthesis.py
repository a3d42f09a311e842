"""Synthesis on a scene: the cloud is segmented into its support plane and objects
(graspmix.segment_scene), grasps are sampled on the target objects only, and the collision expert sees
every object and the table, so that a grasp on one object never goes through its neighbour.

Each target object gets a synthesis of its own per grasp type of the model (its own query densities: a
mixture fitted over several objects would spread its few components between them), with the same
settings and seed; the grasps of all targets are then ranked together by their log-likelihood, which is
comparable between objects because the model and every expert are the same (between grasp types, by
each type's reference score: graspmix.model.grasp_types). One expert is added in a scene of several
objects: "clear_of_neighbours", hard, rejects a grasp whose hand, at the grasp or at its pre-grasp,
holds a point of another object (the paper's collision expert is soft: a finger 1 cm inside a neighbour
costs about 20 nats, less than the spread of the contact terms, and Bullet then starts in collision).
Each target and grasp type also gets, by default, the hard clear approach against the whole scene (its open hand
from the stand-off to its pre-grasp) and, last, the soft contact quality on the target's own surface.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _core
from ..perception import CameraView, Scene, segment_scene, segment_view
from .experts import (
    approach_collision,
    clear_approach_expert,
    collision_expert,
    constraint_experts,
    contact_quality_expert,
    occupancy_map,
    unseen_map,
)
from .grasp_types import REFERENCE_EXPERT
from .grasps import STAGES, grasps_from_result
from .options import SynthesisOptions
from .settings import FeatureScale


@dataclass
class SurfaceUnion:
    """The surfaces of several objects as one (points, normals, curvatures, frames): what a picture of a
    multi-object synthesis draws."""

    points: np.ndarray
    normals: np.ndarray
    curvatures: np.ndarray
    frames: np.ndarray

    def __len__(self):
        return len(self.points)

    @classmethod
    def of(cls, surfaces: list) -> "SurfaceUnion":
        return cls(*(np.vstack([np.asarray(getattr(s, k)) for s in surfaces]) for k in cls.__annotations__))


def segment_query(source, plane, opts: SynthesisOptions, features: FeatureScale) -> Scene:
    """The scene of a query: `source` one camera's view (a perception.CameraView, segmented in image space:
    perception.segment_view) or a cloud (points, viewpoints); the known plane (or the one found,
    opts.segmentation.find_plane), the objects above it, at the model's voxel size, each completed
    (opts.completion; Scene.complete)."""
    settings = opts.segmentation_for(features.voxel_size)
    if isinstance(source, CameraView):
        scene = segment_view(source, plane, settings)
    else:
        points, viewpoints = source
        scene = segment_scene(points, viewpoints=viewpoints, plane=plane, settings=settings)
    return scene if opts.completion is None else scene.complete(opts.completion)


def whole_cloud(source, scene: Scene) -> tuple:
    """(points, viewpoints) of the whole input, table included: a view's points of every return in the world frame
    and its camera; a cloud as given; the scene's own without a source."""
    if source is None:
        return scene.points, scene.viewpoints
    if isinstance(source, CameraView):
        return source.world_points(), source.position
    return source


# m: a completed point's normal is oriented towards a virtual viewpoint this far out along its outward normal
COMPLETED_VIEW_DISTANCE = 1.0


def object_surface(scene: Scene, index: int, features: FeatureScale):
    """The surface features of one segmented object, its normals oriented towards its viewpoints; with its
    completion (scene.completed(index)), the observed and completed points together, each completed point's
    normal turned outward as the completion says (towards a viewpoint on its outside)."""
    rows = scene.objects[index].rows
    vp = None if scene.viewpoints is None else scene.viewpoints[rows]
    points, normals = scene.completed(index)
    if len(points) == 0 or vp is None:
        return _core.compute_surface_features(scene.points[rows], radius=features.radius, viewpoints=vp)
    return _core.compute_surface_features(
        np.vstack([scene.points[rows], points]),
        radius=features.radius,
        viewpoints=np.vstack([vp, points + COMPLETED_VIEW_DISTANCE * normals]),
    )


def query_weights(scene: Scene, index: int, surface, opts: SynthesisOptions):
    """Each surface point's prior weight in the query densities: 1 where observed, opts.query.completed_weight
    where completed (object_surface put the completed points after the observed ones); None without completion."""
    n_observed = len(scene.objects[index].rows)
    completed = np.asarray(surface.indices) >= n_observed
    if not np.any(completed):
        return None
    return np.where(completed, opts.query.completed_weight, 1.0)


def clear_of_neighbours(model, scene: Scene, target: int, opts: SynthesisOptions, config=None):
    """The hard expert that keeps a grasp on `target` out of every other object of the scene, at the grasp
    and at its pre-grasp (where the hand starts, by `config`: a grasp type's ConfigModel, default the
    model's first); None in a scene of one object."""
    if len(scene.objects) < 2:
        return None
    collision = collision_expert(model.hand, scene.solid_points(without=target), None, opts)
    config = model.synthesizer.config_model if config is None else config
    return _core.CollisionFreeExpert(collision, config, name="clear_of_neighbours")


@dataclass
class SceneSynthesis:
    """What the synthesis on the targets of a scene produced: grasps best first (each with its object),
    the targets' surfaces, summed stage times, evaluations and rejected samples."""

    grasps: list
    surface: object
    timing: dict
    evaluations: int
    rejected: int


def synthesize_targets(
    model,
    scene: Scene,
    targets: list[int],
    opts: SynthesisOptions,
    settings,
    *,
    approach_axis,
    reachable,
    experts,
    cloud=None,
    types=None,
) -> SceneSynthesis:
    """Runs the model's synthesiser on every target object against the whole scene and ranks all grasps.
    cloud: the scene's source (segment_query's: a CameraView or (points, viewpoints)): with collision="occupancy"
    the scene's OccupancyMap is built from its whole cloud (whole_cloud) once and shared by every target (its time:
    timing["occupancy"]); the surface model's unseen charge bakes the scene's visibility model instead (unseen_map,
    its time likewise).
    types: the model's grasp types to sample (default all); each samples n_samples grasps of its own and
    optimises its own best, so a synthesis of T types costs about T times one type's (the stage times are
    sums over types and targets)."""
    timing = dict.fromkeys(STAGES, 0.0)
    occupancy = None
    if opts.collision.model == "occupancy":
        points, viewpoints = whole_cloud(cloud, scene)
        occupancy = occupancy_map(points, viewpoints, scene.points, scene.plane, opts)
        timing["occupancy"] = occupancy.stats["seconds"]
    unseen = unseen_map(scene, opts)
    if unseen is not None:
        timing["occupancy"] = unseen.stats["seconds"]
    solid = scene.solid_points()  # observed and completed: the hand stays out of both
    collision = collision_expert(model.hand, solid, scene.plane, opts, occupancy, unseen=unseen)
    approach = approach_collision(model.hand, solid, scene.plane, opts, occupancy)
    # The same for every target; each target adds its own neighbours' expert at the end.
    shared = constraint_experts(
        model.hand, scene.points, scene.plane, opts, approach_axis=approach_axis, reachable=reachable, experts=experts
    )
    types = model.types if types is None else types
    grasps, surfaces, evaluations, rejected = [], [], 0, 0
    for i in targets:
        surface = object_surface(scene, i, model.features)
        on = {"index": int(i), "centroid": [float(x) for x in scene.objects[i].centroid]}
        for t in types:
            config = t.synthesizer.config_model
            own = (
                clear_of_neighbours(model, scene, i, opts, config),
                clear_approach_expert(approach, config, opts),
                contact_quality_expert(model.hand, surface, config, opts),
            )
            extra = shared + [e for e in own if e is not None]
            weights = query_weights(scene, i, surface, opts)
            res = t.synthesizer.synthesize(
                surface.frames, surface.curvatures, collision, extra, settings, weights=weights
            )
            for g in grasps_from_result(res, model.hand):
                g.object = on
                g.type = t.name
                if len(model.types) > 1:  # scores of several types made comparable (model.grasp_types)
                    g.experts[REFERENCE_EXPERT] = -t.log_reference
                    g.log_likelihood -= t.log_reference
                grasps.append(g)
            for k in STAGES:
                timing[k] += getattr(res.timing, k)
            evaluations += res.evaluations
            rejected += res.rejected
        surfaces.append(surface)
    if len(targets) > 1 or len(types) > 1:
        grasps.sort(key=lambda g: -g.log_likelihood)  # stable: equal scores keep the targets' and types' order
        for rank, g in enumerate(grasps, start=1):
            g.rank = rank
    surface = surfaces[0] if len(surfaces) == 1 else SurfaceUnion.of(surfaces)
    return SceneSynthesis(grasps, surface, timing, evaluations, rejected)
