"""Experts of the product a grasp is ranked by: user-defined ones from Python functions, and the collision expert
and occupancy map of a scene as the synthesis makes them (the whole standard set is built in C++ by
_core.synthesize_scene: include/graspmix/grasp/scene_synthesis.hpp)."""

from __future__ import annotations

from typing import Callable

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


def occupancy_map(points, viewpoints, objects, plane, opts: SynthesisOptions) -> "_core.OccupancyMap":
    """The occupancy of a scene from its whole cloud (table included: its rays clear the space around the
    objects) and each point's camera, over the objects' box grown by the map's margin (opts.occupancy)."""
    if viewpoints is None:
        raise ValueError(
            "the occupancy collision model needs the cameras' positions: viewpoints= (or the PCD's VIEWPOINT, "
            "--viewpoint)"
        )
    return _core.OccupancyMap(points, viewpoints, objects, plane, settings=opts.occupancy)


def collision_expert(
    hand, points, plane, opts: SynthesisOptions, occupancy=None, point_radius: float | None = None, unseen=None
) -> "_core.CollisionExpert":
    """W on the query cloud and the support plane (and, with an OccupancyMap, on the space the cameras did not
    see free: the occupancy model), by opts.collision; point_radius (m) overrides its points' radius. Without a map
    it is the surface model whatever opts.collision.model says (a scene's neighbours' expert: their points only),
    charging the unknown cells of `unseen` (OccupancyMap.from_visibility) softly."""
    extra = {} if point_radius is None else {"point_radius": point_radius}
    if occupancy is None:
        extra["model"] = "surface"
    return _core.CollisionExpert(
        hand, points, plane=plane, occupancy=occupancy, unseen=unseen, settings=opts.collision, **extra
    )
