"""Experts of the product a grasp is ranked by: user-defined ones from Python functions, and the
standard set a synthesis builds (collision, kinematic feasibility, approach axis)."""

from __future__ import annotations

from typing import Callable, Iterable

import numpy as np

from .. import _core
from .options import SynthesisOptions


def expert(name: str, fn: Callable, kind: str = "probability") -> "_core.Expert":
    """A user-defined expert from a Python function of a batch: fn(wrists (N, 7), joints (N, D)) returning
    probabilities in [0, 1] (kind="probability"), booleans (kind="hard": False rejects), or log values
    (kind="log")."""
    if kind not in ("probability", "hard", "log"):
        raise ValueError(f"kind must be 'probability', 'hard' or 'log', got {kind!r}")

    def log_value(wrists, joints):
        v = np.asarray(fn(wrists, joints))
        if v.shape != (len(wrists),):
            raise ValueError(f"expert '{name}' returned shape {v.shape} for {len(wrists)} grasps")
        if kind == "log":
            return v.astype(float)
        if kind == "hard":
            return np.where(v.astype(bool), 0.0, -np.inf)
        v = v.astype(float)
        if np.any((v < 0) | (v > 1)) or np.any(np.isnan(v)):
            raise ValueError(f"expert '{name}' returned values outside [0, 1]")
        with np.errstate(divide="ignore"):
            return np.log(v)

    return _core.FunctionExpert(name, log_value)


def oriented_plane(plane, points):
    """The plane with its sign chosen so the object's points are on its positive side."""
    if plane is None:
        return None
    return _core.orient_plane(plane, points, "mean")  # the collision expert's rule (CollisionSettings.orient_plane)


def occupancy_map(points, viewpoints, objects, plane, opts: SynthesisOptions) -> "_core.OccupancyMap":
    """The occupancy of a scene from its whole cloud (table included: its rays clear the space around the
    objects) and each point's camera, over the objects' box grown by the map's margin (opts.occupancy)."""
    if viewpoints is None:
        raise ValueError(
            "the occupancy collision model needs the cameras' positions: viewpoints= (or the PCD's VIEWPOINT, "
            "--viewpoint)"
        )
    return _core.OccupancyMap(points, viewpoints, objects, plane, settings=opts.occupancy)


def unseen_map(scene, opts: SynthesisOptions):
    """The map whose unknown cells the surface model's soft unseen charge counts (opts.collision.unseen_weight):
    the scene's visibility model baked over its objects' box grown by opts.occupancy's margin; None when the charge
    is off, the occupancy model has its own map, or the scene has no view (no viewpoint: nothing is unseen)."""
    if opts.collision.unseen_weight <= 0 or opts.collision.model != "surface" or scene.visibility is None:
        return None
    return _core.OccupancyMap.from_visibility(scene.visibility, scene.points, scene.plane, settings=opts.occupancy)


def collision_expert(
    hand, points, plane, opts: SynthesisOptions, occupancy=None, point_radius: float | None = None, unseen=None
) -> "_core.CollisionExpert":
    """W on the query cloud and the support plane (and, with an OccupancyMap, on the space the cameras did not
    see free: the occupancy model), by opts.collision; point_radius (m) overrides its points' radius. Without a map
    it is the surface model whatever opts.collision.model says (a scene's neighbours' expert: their points only),
    charging the unknown cells of `unseen` (unseen_map) softly."""
    extra = {} if point_radius is None else {"point_radius": point_radius}
    if occupancy is None:
        extra["model"] = "surface"
    return _core.CollisionExpert(
        hand, points, plane=plane, occupancy=occupancy, unseen=unseen, settings=opts.collision, **extra
    )


def approach_collision(hand, points, plane, opts: SynthesisOptions, occupancy=None):
    """What the clear approach keeps clear of: the scene's points (observed and completed) as balls of
    opts.approach.clearance, its plane and occupancy; None when the clear approach is off."""
    if opts.approach is None:
        return None
    return collision_expert(hand, points, plane, opts, occupancy, point_radius=opts.approach.clearance)


def clear_approach_expert(collision, config, opts: SynthesisOptions):
    """The hard clear-approach expert of one grasp type (its ConfigModel opens the hand) against `collision`
    (approach_collision); None when there is none."""
    if collision is None:
        return None
    return _core.ClearApproachExpert(collision, config, settings=opts.approach)


def contact_quality_expert(hand, surface, config, opts: SynthesisOptions):
    """The soft contact-quality expert of one target object (its surface: points and normals) and grasp type (its
    ConfigModel opens the hand); None when opts.contact_quality is None."""
    if opts.contact_quality is None:
        return None
    return _core.ContactQualityExpert(hand, surface.points, surface.normals, config, settings=opts.contact_quality)


def constraint_experts(
    hand,
    points,
    plane,
    opts: SynthesisOptions,
    *,
    approach_axis=None,
    reachable: Callable | None = None,
    experts: Iterable = (),
) -> list:
    """The kinematic expert (joint limits, support plane, reachability), the approach-axis expert, then
    the caller's experts, in this order."""
    out = []
    if opts.kinematic is not None:
        out.append(
            _core.KinematicFeasibilityExpert(
                hand, plane=oriented_plane(plane, points), reachable=reachable, settings=opts.kinematic
            )
        )
    elif reachable is not None:
        raise ValueError("reachable needs the kinematic expert (SynthesisOptions.kinematic is None)")
    if approach_axis is not None:
        out.append(_core.AxisAlignmentExpert(np.asarray(approach_axis, float), settings=opts.axis_alignment, hand=hand))
    out.extend(experts)
    return out
