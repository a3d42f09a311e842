"""A named target among several objects: what a user does most (click one object, ask for it to be lifted).

Per scene of the clutter protocol (make_scene with its scene seeds, pile or packed, one 640x480 camera): the
target is drawn, with the scene's seed, among the placed objects the camera sees (at least MIN_VISIBLE_POINTS
points of the cloud lie on it: a hidden object cannot be named); it is named as a user clicks it, by a point of
its visible surface: of its points in the cloud (the renderer's per-point object ids), those in its top tenth by
height, the one nearest their centroid. The synthesis gets `target="point:x,y,z"` (graspmix.Scene.select: the
segmented object nearest the point) and the best grasp is executed among all the objects.

Outcomes: "success" (the target rose, alone), "wrong object" (another object rose instead), "two objects
lifted" (the target with another), "start in collision", "no contact", "not held" (as the executor says),
"synthesis failed" (the point named no object, or no grasp came back).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .confusion import MIN_VISIBLE_POINTS

OUTCOMES = (
    "success",
    "wrong object",
    "two objects lifted",
    "start in collision",
    "no contact",
    "not held",
    "synthesis failed",
)
TOP_FRACTION = 0.1  # of the target's points by height: where a user clicks an object seen from above


def choose_target(labels: np.ndarray, n_objects: int, seed: int) -> int | None:
    """The target: one of the objects with at least MIN_VISIBLE_POINTS points (labels: each point's object, -1
    the table), drawn with `seed`; None when the camera sees none."""
    counts = np.bincount(labels[labels >= 0], minlength=n_objects)
    visible = np.flatnonzero(counts >= MIN_VISIBLE_POINTS)
    if len(visible) == 0:
        return None
    return int(np.random.default_rng(seed).choice(visible))


def named_point(points: np.ndarray, labels: np.ndarray, target: int) -> np.ndarray:
    """The point a user would click on the target: among its points in its top TOP_FRACTION by height (z), the one
    nearest their centroid."""
    own = points[labels == target]
    if len(own) == 0:
        raise ValueError(f"object {target} has no point in the cloud")
    top = own[own[:, 2] >= np.quantile(own[:, 2], 1.0 - TOP_FRACTION)]
    return top[np.argmin(np.linalg.norm(top - top.mean(axis=0), axis=1))]


def outcome_of(reason: str, lifted: list[int], target: int) -> str:
    """The named-target outcome of an execution: the executor's reason and the objects that rose."""
    if lifted == [target]:
        return "success"
    if len(lifted) > 1:
        return "two objects lifted" if target in lifted else "wrong object"
    if lifted:
        return "wrong object"
    return reason if reason in OUTCOMES else "not held"


@dataclass
class NamedAttempt:
    mode: str
    scene: int
    scene_seed: int
    target: int
    target_urdf: str
    point: list
    outcome: str
    lifted: list
    error: str = ""

    def to_dict(self) -> dict:
        return dict(self.__dict__)


def attempt(model, spec, acq, target: int, options, mode: str, scene: int, scene_seed: int) -> NamedAttempt:
    """Names the target by its point, synthesises on it, executes the best grasp among all the objects."""
    from ..sim.scenes import execute_in_scene

    point = named_point(acq.points, acq.labels, target)
    row = NamedAttempt(mode, scene, scene_seed, target, spec.objects[target].urdf, point.tolist(), "", [])
    try:
        grasps = model.synthesize(
            acq.points, options, viewpoints=acq.viewpoints, target="point:" + ",".join(f"{v:.6f}" for v in point)
        )
        if len(grasps) == 0:
            raise ValueError("no grasp came back")
    except ValueError as e:
        row.outcome, row.error = "synthesis failed", str(e)
        return row
    ex = execute_in_scene(spec, grasps.best(), hand=model.hand_path)
    row.lifted = list(ex.lifted)
    row.outcome = outcome_of(ex.outcome, row.lifted, target)
    return row


def summarise(rows: list[NamedAttempt]) -> dict:
    """Success rate with its Wilson 95% interval and the count of every outcome, per mode and overall."""
    from ..experiment.stats import wilson_ci

    def of(rs):
        n = len(rs)
        k = sum(r.outcome == "success" for r in rs)
        lo, hi = wilson_ci(k, n) if n else (float("nan"), float("nan"))
        return {
            "attempts": n,
            "success": k,
            "rate": k / n if n else float("nan"),
            "ci95": [lo, hi],
            "outcomes": {o: sum(r.outcome == o for r in rs) for o in OUTCOMES},
        }

    modes = sorted({r.mode for r in rows})
    return {"all": of(rows), **{m: of([r for r in rows if r.mode == m]) for m in modes}}
