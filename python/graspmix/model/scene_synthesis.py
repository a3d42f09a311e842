"""Synthesis on a scene: the cloud is segmented into its support plane and objects
(graspmix.segment_scene), grasps are sampled on the target objects only, and the collision expert sees
every object and the table, so that a grasp on one object never goes through its neighbour. The whole path runs
in one C++ call, _core.synthesize_scene (include/graspmix/grasp/scene_synthesis.hpp states it step by step); this
module gives it its input and settings and turns its result into the Scene and Grasps of the Python API.

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
from ..perception import CameraView, Scene, parse_target, segment_scene, segment_view
from .grasps import STAGES, grasps_from_columns
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


def object_surface(scene: Scene, index: int, features: FeatureScale):
    """The surface features of one segmented object as the synthesis computes them (_core.object_surface): its
    observed points, normals towards their cameras, then its completed points (scene.completed(index)), each
    completed point's normal turned outward as the completion says."""
    return _core.object_surface(scene.result, scene.viewpoints, scene.completions, index, radius=features.radius)


def query_weights(scene: Scene, index: int, surface, opts: SynthesisOptions):
    """Each surface point's prior weight in the query densities: 1 where observed, opts.query.completed_weight
    where completed (object_surface put the completed points after the observed ones); None without completion."""
    return _core.query_weights(surface, len(scene.objects[index].rows), opts.query.completed_weight)


def source_arguments(source) -> dict:
    """_core.synthesize_scene's input keywords of segment_query's source: a view's depth image (or its organized
    cloud) with its camera and pose, or a cloud's points and viewpoints."""
    if isinstance(source, CameraView):
        view = {"camera": source.camera, "T_world_camera": source.pose}
        if source.organized is not None:
            return {"organized": source.organized.reshape(-1, 3), **view}
        return {"depth": source.depth, **view}
    points, viewpoints = source
    return {"points": points, "viewpoints": viewpoints}


@dataclass
class SceneSynthesis:
    """What the synthesis on the targets of a scene produced: the scene, the targets, grasps best first (each with
    its object and type), the targets' surfaces, stage times, evaluations and rejected samples."""

    scene: Scene
    targets: list
    grasps: list
    surface: object
    timing: dict
    evaluations: int
    rejected: int


def synthesize_scene(
    model,
    source,
    plane,
    target,
    opts: SynthesisOptions,
    settings,
    *,
    approach_axis=None,
    reachable=None,
    experts=(),
    types=None,
) -> SceneSynthesis:
    """The whole path in one C++ call (_core.synthesize_scene; include/graspmix/grasp/scene_synthesis.hpp): the
    scene of `source` (segment_query's: a CameraView or (points, viewpoints)) with `plane` known or searched for,
    its objects completed (opts.completion), the `target` objects (Scene.select's forms), and on each the model's
    synthesiser per grasp type against the whole scene, all grasps ranked together. types: the model's grasp types
    to sample (default all), each sampling n_samples grasps of its own and optimising its own best (the stage times
    are sums over types and targets); in a model of several types each type's scores are made comparable by its
    reference score (graspmix.model.grasp_types). timing: the segmentation (the scene, completion and targets),
    the occupancy map when one was made, the synthesiser's stages."""
    types = model.types if types is None else types
    t = parse_target(target)
    several = len(model.types) > 1  # scores of several types made comparable (model.grasp_types)
    res = _core.synthesize_scene(
        [(ty.synthesizer, ty.name, ty.log_reference if several else None) for ty in types],
        **source_arguments(source),
        plane=plane,
        target=t.kind,
        target_index=t.index,
        target_point=t.point,
        approach_axis=None if approach_axis is None else np.asarray(approach_axis, float),
        reachable=reachable,
        experts=list(experts),
        segmentation=opts.segmentation_for(model.features.voxel_size),
        completion=opts.completion,
        features=_core.SurfaceFeatureSettings(radius=model.features.radius),
        synthesizer=settings,
        collision=opts.collision,
        occupancy=opts.occupancy,
        kinematic=opts.kinematic,
        axis_alignment=opts.axis_alignment,
        approach=opts.approach,
        contact_quality=opts.contact_quality,
        grasp_depth=opts.grasp_depth,
    )
    scene = Scene(res.scene, None, point_viewpoints=res.viewpoints)
    if opts.completion is not None:
        scene.take_completion(res.completion)
    times = res.timing
    objects = [{"index": o.index, "centroid": [float(x) for x in o.centroid]} for o in scene.objects]
    grasps = grasps_from_columns(res.columns(), res.term_names, model.hand, objects, [ty.name for ty in types])
    timing = {k: times[k] for k in STAGES}
    if times["occupancy"] is not None:
        timing["occupancy"] = times["occupancy"]
    timing["segmentation"] = times["segmentation"]
    surfaces = list(res.surfaces)
    surface = surfaces[0] if len(surfaces) == 1 else SurfaceUnion.of(surfaces)
    return SceneSynthesis(scene, list(res.targets), grasps, surface, timing, res.evaluations, res.rejected)
