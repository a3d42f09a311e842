"""One round of clutter removal: a scene, and observe -> plan -> execute -> remove until a rule ends it.

The loop (run_scene) takes its three stages as callables, so it is independent of the simulator:
    observe(spec, seed) -> an observation with .points (n, 3) and .viewpoints
    plan(observation, seed) -> Plan (the grasp to execute and the object it is on); ValueError or
        RuntimeError: no object or no grasp found (outcome "synthesis failed")
    execute(spec, grasp) -> a scene execution with .result (.success, .reason, .lift_height), .lifted
        (indices of the objects lifted), .moved (how far each object moved, m) and .remaining (the scene
        without what left the table: the next observation's scene)
run_round builds the real stages (graspmix.sim.scenes, graspmix.segment_scene, the methods' models and
the top-down baseline) for a (mode, scene, method) work unit in a worker process.
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass
from typing import Callable

from ..experiment.attempt import cached_model
from ..model.grasps import Grasp, check_grasp, infeasible_unwarned
from .protocol import MAX_CONSECUTIVE_FAILURES, ClutterProtocol, clutter_protocol_from_json


@dataclass
class Plan:
    """A planner's answer: the grasp to execute (a Grasp), the index of the
    segmented object it is on (None: unknown), how many objects the segmentation found (None: unknown),
    and the planner's own split of its time (s; None: not measured, the loop's total is synthesis)."""

    grasp: Grasp
    target: int | None = None
    seen: int | None = None
    t_segment: float | None = None
    t_synthesis: float | None = None


@dataclass
class Stages:
    observe: Callable
    plan: Callable
    execute: Callable


def _blank(v):
    return "" if v is None else v


def _attempt(spec, stages: Stages, seed_of: Callable, attempt: int) -> tuple[dict, object]:
    """One attempt on the scene spec: its row (without the round's columns) and the scene that remains."""
    row = {"attempt": attempt, "observe_seed": seed_of("observe", attempt), "before": len(spec.objects)}
    row["synthesis_seed"] = seed_of("synthesis", attempt)
    t0 = time.perf_counter()
    obs = stages.observe(spec, row["observe_seed"])
    t1 = time.perf_counter()
    row.update(t_observe=t1 - t0, n_points=len(obs.points), error="", grasp="", max_moved="", lift_height="")
    try:
        plan = stages.plan(obs, row["synthesis_seed"])
    except (ValueError, RuntimeError) as e:
        row.update(outcome="synthesis failed", success=0, lifted=0, after=row["before"], seen="", target="")
        row.update(error=" ".join(str(e).split()), t_segment="", t_synthesis=time.perf_counter() - t1, t_execution=0.0)
        return row, spec
    t2 = time.perf_counter()
    row.update(seen=_blank(plan.seen), target=_blank(plan.target), t_segment=_blank(plan.t_segment))
    row["t_synthesis"] = t2 - t1 if plan.t_synthesis is None else plan.t_synthesis
    grasp = check_grasp(plan.grasp, "the planner's grasp").to_dict(execution_only=True)
    row["grasp"] = json.dumps(grasp, separators=(",", ":"), default=float)
    ex = stages.execute(spec, plan.grasp)
    row["t_execution"] = time.perf_counter() - t2
    remaining = ex.remaining
    row.update(
        outcome=str(ex.result.reason),
        success=int(bool(ex.result.success)),
        lifted=len(ex.lifted),
        after=len(remaining.objects),
        max_moved=max((float(m) for m in ex.moved), default=0.0),
        lift_height=float(ex.result.lift_height),
    )
    if row["success"] and row["after"] >= row["before"]:
        raise RuntimeError(f"attempt {attempt}: the execution succeeded but no object left the scene")
    return row, remaining


def run_scene(spec, stages: Stages, seed_of: Callable, max_attempts: int = 0) -> list[dict]:
    """The attempts of one round on the scene spec (.objects), one row each, the last naming why the round
    ended (stop): "clear" (no object left), "no grasp" (the planner found none: VGN ends the round there;
    the attempt counts as a failure), "two failures" (MAX_CONSECUTIVE_FAILURES in a row), or "attempt
    limit" (max_attempts > 0 reached). seed_of(stage, attempt) -> the seed of a stage ("observe",
    "synthesis") of an attempt. Every success removes an object and no two failures follow each other, so
    a round has at most 2 N attempts (N objects placed) without a limit."""
    placed = len(spec.objects)
    if placed == 0:
        raise ValueError("the scene has no objects")
    rows, failures = [], 0
    while True:
        row, spec = _attempt(spec, stages, seed_of, len(rows))
        row["placed"] = placed
        row["stop"] = ""
        rows.append(row)
        failures = 0 if row["success"] else failures + 1
        if row["after"] == 0:
            row["stop"] = "clear"
        elif row["outcome"] == "synthesis failed":
            row["stop"] = "no grasp"
        elif failures >= MAX_CONSECUTIVE_FAILURES:
            row["stop"] = "two failures"
        elif max_attempts and len(rows) >= max_attempts:
            row["stop"] = "attempt limit"
        if row["stop"]:
            return rows


# ---- the real stages ------------------------------------------------------------------------------
def _observe(p: ClutterProtocol) -> Callable:
    from ..sim.scene_camera import acquire_scene

    def observe(spec, seed):
        return acquire_scene(spec, views=p.views, noise=p.noise, seed=seed)

    return observe


def _model_planner(p: ClutterProtocol, model_path: str) -> Callable:
    model = cached_model(model_path)

    def plan(obs, seed):
        with infeasible_unwarned():  # the protocol executes the best grasp whatever it scored
            grasps = p.synthesize(model, obs, p.synthesis.updated({"seed": seed}))
        if len(grasps) == 0:
            raise ValueError("synthesis returned no grasps")
        best, timing = grasps.best(), grasps.timing
        seg = timing["segmentation"]
        return Plan(best, best.object["index"], len(grasps.scene.objects), seg, timing["total"] - seg)

    return plan


def _topdown_planner() -> Callable:
    from ..perception import segment_scene
    from .topdown import plan_topdown

    def plan(obs, seed):
        t0 = time.perf_counter()
        scene = segment_scene(obs.points, viewpoints=obs.viewpoints)
        t1 = time.perf_counter()
        grasp, index = plan_topdown(scene)
        return Plan(grasp, index, len(scene.objects), t1 - t0, time.perf_counter() - t1)

    return plan


def _execute(p: ClutterProtocol) -> Callable:
    from ..sim.scenes import execute_in_scene

    def execute(spec, grasp):
        return execute_in_scene(spec, grasp, closing=p.closing)

    return execute


def real_stages(p: ClutterProtocol, method: str, model_paths: dict) -> Stages:
    plan = _topdown_planner() if method == "topdown" else _model_planner(p, model_paths[method])
    return Stages(_observe(p), plan, _execute(p))


def run_round(pdoc: dict, unit: tuple, todo=None) -> list[dict]:
    """The rows of one round (mode, scene, method): a pure function of the protocol and the unit (but the
    times). pdoc: ClutterProtocol.to_json() plus "model_paths" (method -> path); todo: unused (a round runs
    whole). Runs in worker processes (graspmix.experiment.executors)."""
    from ..sim.scenes import choose_objects, make_scene

    p = clutter_protocol_from_json(pdoc)
    mode, scene, method = unit[0], int(unit[1]), unit[2]
    scene_seed = p.scene_seed(mode, scene)
    spec = make_scene(choose_objects(p.object_list_path, p.objects, scene_seed), mode, scene_seed)
    stages = real_stages(p, method, pdoc.get("model_paths", {}))
    rows = run_scene(spec, stages, lambda stage, a: p.stage_seed(stage, mode, scene, a), p.attempt_limit)
    for r in rows:
        r.update(mode=mode, scene=scene, method=method, scene_seed=scene_seed)
    return rows
