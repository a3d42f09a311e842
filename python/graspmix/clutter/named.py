"""The named-target task of the clutter protocol: in a scene of N objects, one object is named the way a
user clicks it (`point:x,y,z`, a point on its visible surface) and the planner is asked to lift it.

Per (mode, scene, method, pick) unit, on the protocol's scene (make_scene, the scene seed) and its first
observation (acquire_scene, the attempt-0 observation seed, shared by every pick and method):

- eligible objects (TARGET_RULE): the placed objects with at least MIN_TARGET_POINTS observed points whose
  highest observed point reaches within TOP_VISIBLE_TOLERANCE of the top of their true bounding box (from
  the collision mesh at the object's pose): an object whose top the camera does not see is not one a user
  would click on.
- the targets: `targets` of the eligible objects, drawn uniformly without replacement with a seed of the
  protocol's seed, the mode and the scene (choose_targets); pick k names the k-th. A pick beyond the
  eligible count is recorded as "no target" and is not an attempt.
- the named point (named_point): the target's observed point (the simulator's segmentation mask labels
  every point) nearest the centre of the top face of its true bounding box.
- the plan: a method's model synthesises with target "point:x,y,z" (Scene.select: the segmented object
  nearest the point, within 5 cm; else "synthesis failed"); topdown grasps the object that point selects.
- the execution of the best grasp on the untouched scene, classified by classify(): "success" (the target
  alone lifted), "wrong object" (one object lifted, not the target), or the simulation's reason.
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..experiment.log import CsvSchema
from ..experiment.protocol import derive_seed
from ..model.grasps import check_grasp, infeasible_unwarned
from .protocol import TIME_COLUMNS, clutter_protocol_from_json  # the same stages as a clearing round
from .rounds import Plan

MIN_TARGET_POINTS = 50  # observed points an object needs to be named (a few mm^2 of it are not a click)
TOP_VISIBLE_TOLERANCE = 0.01  # m: its highest observed point within this of its true top
TARGET_RULE = (
    f"uniformly among the placed objects with at least {MIN_TARGET_POINTS} observed points whose highest observed "
    f"point is within {100 * TOP_VISIBLE_TOLERANCE:g} cm of the top of their true bounding box (top visible)"
)
NAMED_OUTCOMES = (
    "success",
    "wrong object",
    "two objects lifted",
    "start in collision",
    "no contact",
    "not held",
    "synthesis failed",
)
NO_TARGET = "no target"  # a pick beyond the scene's eligible objects: not an attempt
NAMED_CSV_NAME = "named_attempts.csv"

KEY_COLUMNS = ("mode", "scene", "method", "pick")
RESULT_COLUMNS = (
    "scene_seed",
    "placed",
    "eligible",
    "target",  # index of the named object in the scene (make_scene's order)
    "target_urdf",
    "point",  # the named point "x,y,z" (m)
    "seen",  # objects the segmentation found
    "named",  # the segmented object the point selected (its index)
    "cluster",  # the scene object most of that segmented object's points lie on (-1: the table)
    "outcome",
    "success",
    "lifted",  # the scene objects lifted, ";"-separated
    "max_moved",
    "lift_height",
    "observe_seed",
    "synthesis_seed",
    "n_points",
    "grasp",
    "error",
)
_TEXT = frozenset({"mode", "method", "target_urdf", "point", "outcome", "lifted", "grasp", "error"})
_FLOAT = frozenset({"max_moved", "lift_height", *TIME_COLUMNS})
_ALL = KEY_COLUMNS + RESULT_COLUMNS + TIME_COLUMNS
NAMED_CSV = CsvSchema(_ALL, KEY_COLUMNS, frozenset(_ALL) - _TEXT - _FLOAT, _FLOAT, "named-target attempts")


# ---- the rule -------------------------------------------------------------------------------------
def object_tops(spec) -> np.ndarray:
    """(N, 3) per scene object the centre of the top face of its true (world, axis-aligned) bounding box:
    its collision mesh's vertices at its pose."""
    from scipy.spatial.transform import Rotation

    from ..sim.execution import load_object

    tops = []
    for o in spec.objects:
        model = load_object(o.urdf).model
        verts = np.asarray(model.collision_mesh(model.link_names[0])[0], dtype=float)
        world = Rotation.from_quat(o.pose[3:]).apply(verts) + o.pose[:3]
        lo, hi = world.min(0), world.max(0)
        tops.append([(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, hi[2]])
    return np.asarray(tops, dtype=float).reshape(-1, 3)


def eligible_objects(points, labels, tops) -> list[int]:
    """The scene objects (indices) a user could click (TARGET_RULE): points (n, 3) and labels (n,) of an
    observation (-1 the table, else the object's index), tops (N, 3) from object_tops."""
    points, labels = np.asarray(points, dtype=float), np.asarray(labels)
    out = []
    for i, top in enumerate(np.asarray(tops)):
        mine = points[labels == i]
        if len(mine) >= MIN_TARGET_POINTS and mine[:, 2].max() >= top[2] - TOP_VISIBLE_TOLERANCE:
            out.append(i)
    return out


def choose_targets(eligible: list[int], targets: int, seed: int) -> list[int]:
    """min(targets, len(eligible)) of the eligible indices, drawn uniformly without replacement (seeded)."""
    eligible = sorted(int(i) for i in eligible)
    rng = np.random.default_rng(seed)
    picks = rng.choice(len(eligible), min(targets, len(eligible)), replace=False) if eligible else []
    return [eligible[int(i)] for i in picks]


def named_point(points, labels, target: int, top) -> np.ndarray:
    """(3,) the target's observed point nearest `top` (its bounding box's top centre): where a user clicks."""
    mine = np.asarray(points, dtype=float)[np.asarray(labels) == target]
    if len(mine) == 0:
        raise ValueError(f"object {target} has no observed point to name it by")
    return mine[int(np.argmin(np.linalg.norm(mine - np.asarray(top, dtype=float), axis=1)))]


def point_target(point) -> str:
    """The --target text of a point: "point:x,y,z" to 0.1 mm."""
    return "point:" + ",".join(f"{float(v):.4f}" for v in point)


def classify(reason: str, lifted, target: int) -> str:
    """The named task's outcome of an execution: its reason (SimResult.reason), the scene objects lifted and
    the target's index. One object lifted is a success only if it is the target, else "wrong object"."""
    lifted = [int(i) for i in lifted]
    if reason == "success":
        if len(lifted) != 1:
            raise ValueError(f"a success lifts one object, got lifted {lifted}")
        return "success" if lifted[0] == target else "wrong object"
    if reason not in NAMED_OUTCOMES:
        raise ValueError(f"unknown execution outcome {reason!r}")
    return reason


# ---- one attempt ----------------------------------------------------------------------------------
@dataclass
class NamedStages:
    """plan(observation, target text, seed) -> (Plan, cluster: the scene object most of the selected
    segmented object's points lie on, or None); ValueError or RuntimeError: no object or no grasp.
    execute(spec, grasp) -> a scene execution (.result with .reason and .lift_height, .lifted, .moved)."""

    plan: Callable
    execute: Callable


def _blank(v):
    return "" if v is None else v


def named_attempt(spec, obs, target: int, point, stages: NamedStages, seed: int) -> dict:
    """The row fields of one attempt at lifting scene object `target`, named by `point` (3,), on the
    observation obs of the untouched scene spec."""
    text = point_target(point)
    row = {"target": target, "target_urdf": spec.objects[target].urdf, "point": text[len("point:") :]}
    row.update(synthesis_seed=seed, error="", grasp="", max_moved="", lift_height="", lifted="")
    t1 = time.perf_counter()
    try:
        plan, cluster = stages.plan(obs, text, seed)
    except (ValueError, RuntimeError) as e:
        row.update(outcome="synthesis failed", success=0, seen="", named="", cluster="", t_segment="")
        row.update(error=" ".join(str(e).split()), t_synthesis=time.perf_counter() - t1, t_execution=0.0)
        return row
    t2 = time.perf_counter()
    row.update(seen=_blank(plan.seen), named=_blank(plan.target), cluster=_blank(cluster))
    row.update(t_segment=_blank(plan.t_segment), t_synthesis=t2 - t1 if plan.t_synthesis is None else plan.t_synthesis)
    grasp = check_grasp(plan.grasp, "the planner's grasp").to_dict(execution_only=True)
    row["grasp"] = json.dumps(grasp, separators=(",", ":"), default=float)
    ex = stages.execute(spec, plan.grasp)
    row["t_execution"] = time.perf_counter() - t2
    outcome = classify(str(ex.result.reason), ex.lifted, target)
    row.update(
        outcome=outcome,
        success=int(outcome == "success"),
        lifted=";".join(str(int(i)) for i in ex.lifted),
        max_moved=max((float(m) for m in ex.moved), default=0.0),
        lift_height=float(ex.result.lift_height),
    )
    return row


# ---- the real stages and the work unit -------------------------------------------------------------
def cluster_of(scene, index: int, labels) -> int | None:
    """The scene object (label) most points of segmented object `index` come from (None: no labels)."""
    if labels is None:
        return None
    obj = next(o for o in scene.objects if o.index == index)
    values, counts = np.unique(np.asarray(labels)[scene.sources[obj.rows]], return_counts=True)
    return int(values[np.argmax(counts)])


def _model_planner(p, model_path: str) -> Callable:
    from ..experiment.attempt import cached_model

    model = cached_model(model_path)

    def plan(obs, target, seed):
        opts = p.synthesis.updated({"seed": seed})
        with infeasible_unwarned():  # the protocol executes the best grasp whatever it scored
            grasps = p.synthesize(model, obs, opts, target=target)
        if len(grasps) == 0:
            raise ValueError("synthesis returned no grasps")
        best, timing = grasps.best(), grasps.timing
        seg, index = timing["segmentation"], int(best.object["index"])
        out = Plan(best, index, len(grasps.scene.objects), seg, timing["total"] - seg)
        return out, cluster_of(grasps.scene, index, p.object_labels(obs))

    return plan


def _topdown_planner() -> Callable:
    from ..perception import segment_scene
    from .topdown import topdown_grasp

    def plan(obs, target, seed):
        t0 = time.perf_counter()
        scene = segment_scene(obs.points, viewpoints=obs.viewpoints)
        t1 = time.perf_counter()
        index = scene.select(target)[0]
        grasp = topdown_grasp(next(o for o in scene.objects if o.index == index).points, scene.plane)
        grasp.object = index
        out = Plan(grasp, index, len(scene.objects), t1 - t0, time.perf_counter() - t1)
        return out, cluster_of(scene, index, obs.labels)

    return plan


def named_stages(p, method: str, model_paths: dict) -> NamedStages:
    from ..sim.scenes import execute_in_scene

    plan = _topdown_planner() if method == "topdown" else _model_planner(p, model_paths[method])
    return NamedStages(plan, lambda spec, grasp: execute_in_scene(spec, grasp, closing=p.closing))


def target_seed(p, mode: str, scene: int) -> int:
    """The seed of a scene's draw of targets (shared by its methods and picks)."""
    return derive_seed(p.seed, "clutter named", mode, scene)


@dataclass
class NamedScene:
    """One scene of a named-target protocol as its attempts see it: the placed scene, its observation (and the
    seconds it took), the objects' true tops, the eligible objects and the targets drawn among them."""

    scene_seed: int
    observe_seed: int
    spec: object
    obs: object
    t_observe: float
    tops: np.ndarray
    eligible: list
    picks: list

    def point(self, target: int) -> np.ndarray:
        """The point that names scene object `target` (named_point)."""
        return named_point(self.obs.points, self.obs.labels, target, self.tops[target])


def named_scene(p, mode: str, scene: int) -> NamedScene:
    """Scene `scene` of `mode` of protocol p, placed, observed and its targets drawn (every attempt on it the same)."""
    from ..sim.scene_camera import acquire_scene
    from ..sim.scenes import choose_objects, make_scene

    scene_seed = p.scene_seed(mode, scene)
    spec = make_scene(choose_objects(p.object_list_path, p.objects, scene_seed), mode, scene_seed)
    observe_seed = p.stage_seed("observe", mode, scene, 0)
    t0 = time.perf_counter()
    obs = acquire_scene(spec, views=p.views, noise=p.noise, seed=observe_seed)
    t_observe = time.perf_counter() - t0
    tops = object_tops(spec)
    eligible = eligible_objects(obs.points, obs.labels, tops)
    picks = choose_targets(eligible, p.targets, target_seed(p, mode, scene))
    return NamedScene(scene_seed, observe_seed, spec, obs, t_observe, tops, eligible, picks)


def run_named(pdoc: dict, unit: tuple, todo=None) -> list[dict]:
    """The row of one named-target unit (mode, scene, method, pick): a pure function of the protocol and
    the unit (but the times). pdoc: ClutterProtocol.to_json() plus "model_paths"; todo: unused."""
    p = clutter_protocol_from_json(pdoc)
    mode, scene, method, pick = unit[0], int(unit[1]), unit[2], int(unit[3])
    ns = named_scene(p, mode, scene)
    row = {"mode": mode, "scene": scene, "method": method, "pick": pick, "scene_seed": ns.scene_seed}
    row.update(placed=len(ns.spec.objects), observe_seed=ns.observe_seed)
    row.update(t_observe=ns.t_observe, n_points=len(ns.obs.points), eligible=len(ns.eligible))
    seed = p.stage_seed("synthesis", mode, scene, pick)
    if pick >= len(ns.picks):
        blank = {c: "" for c in RESULT_COLUMNS + TIME_COLUMNS if c not in row}
        return [{**row, **blank, "outcome": NO_TARGET, "success": 0, "synthesis_seed": seed}]
    target = ns.picks[pick]
    stages = named_stages(p, method, pdoc.get("model_paths", {}))
    row.update(named_attempt(ns.spec, ns.obs, target, ns.point(target), stages, seed))
    return [row]


def done_named(path) -> set[tuple]:
    """The (mode, scene, method, pick) units the named log holds (one row each, written when it ends)."""
    from pathlib import Path

    from ..experiment.log import read_rows

    if not Path(path).is_file():
        return set()
    return {(r["mode"], r["scene"], r["method"], r["pick"]) for r in read_rows(path, NAMED_CSV)}


def named_rows(run_dir) -> list[dict]:
    """A named run's attempts (read_rows of NAMED_CSV): its named_attempts.csv, or the .csv.gz the repository keeps
    results as; ValueError when the folder has neither."""
    from pathlib import Path

    from ..experiment.log import read_rows

    path = Path(run_dir) / NAMED_CSV_NAME
    if not path.exists():
        path = path.with_name(NAMED_CSV_NAME + ".gz")
    if not path.exists():
        raise ValueError(f"{run_dir}: no {NAMED_CSV_NAME}(.gz): not a `clutter --task named` run")
    return read_rows(path, NAMED_CSV)
