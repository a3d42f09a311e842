"""One work unit of the experiment (runs in a worker): one (object, trial, noise) acquisition and every
attempt that shares it, each a synthesis and the execution of its best grasp, as attempts.csv rows."""

from __future__ import annotations

import dataclasses
import json
import time
from typing import Callable, Iterable

from ..model import GraspModel
from ..model.grasp_types import REFERENCE_EXPERT
from ..model.grasps import infeasible_unwarned
from ..sim import execute, rest_pose
from ..sim.acquisition import Acquisition, acquire
from .protocol import CLOSING, CONDITIONS, SUPPORT_PLANE, Protocol, protocol_from_json

_MODELS: dict = {}


def cached_model(path: str) -> GraspModel:
    """Each process loads a model once."""
    if path not in _MODELS:
        _MODELS[path] = GraspModel.load(path)
    return _MODELS[path]


def crop_above_plane(min_height: float) -> Callable:
    """The clean-up of an acquired cloud: drop points at most min_height above the support plane z = 0 (the
    synthesis' table clearance, so both keep the same points). The noise model's lateral shift gives object
    pixels the depth of the plane beside them, a fringe of points on the plane around the object; the
    segmentation mask keeps the rest of the plane out."""

    def cleanup(acq: Acquisition) -> Acquisition:
        keep = acq.points[:, 2] > min_height
        return dataclasses.replace(
            acq, points=acq.points[keep], viewpoints=acq.viewpoints[keep], camera_index=acq.camera_index[keep]
        )

    return cleanup


def synthesize_on(model: GraspModel, acq: Acquisition, p: Protocol, obj: str, trial: int, condition: str):
    """The synthesis of one attempt on an acquisition: the protocol's options for the attempt
    (Protocol.attempt_options), the known support plane; the camera's depth image, intrinsics and pose (cloud
    "image"), or the points with the cameras' positions."""
    opts, plane = p.attempt_options(obj, trial, condition), list(SUPPORT_PLANE)
    with infeasible_unwarned():  # the protocol executes the best grasp whatever it scored
        if p.cloud == "image":
            return model.synthesize(**acq.view_input(), options=opts, plane=plane)
        return model.synthesize(acq.points, opts, viewpoints=acq.viewpoints, plane=plane)


def acquire_unit(p: Protocol, obj: str, trial: int, noise: bool) -> Acquisition:
    """The cloud of one (object, trial, noise) unit: the protocol's cameras, noise model and seed; an object
    cloud's table fringe cropped (crop_above_plane), a scene cloud whole (the synthesis drops the table)."""
    return acquire(
        obj,
        noise=noise,
        seed=p.acquisition_seed(obj, trial),
        settings=p.acquisition_settings(),
        postprocess=crop_above_plane(p.synthesis.segmentation.table_clearance) if p.cloud == "object" else None,
    )


def _unit_order(p: Protocol, keys: list, acq_seed: int) -> list:
    # The first synthesis after an acquisition runs a little slower (cold caches, sleeping OpenMP threads):
    # every other unit runs the methods in the other order, so neither method always pays it.
    if acq_seed % 2:
        keys.sort(key=lambda k: (p.conditions.index(k[2]), -p.methods.index(k[3])))
    return keys


def _failed(row: dict, error: Exception, t_synthesis: float) -> dict:
    """A failed synthesis is a failed attempt (nothing to execute), recorded with its reason."""
    row.update(
        success=0,
        reason="synthesis failed",
        lift_height=0.0,
        contact_count=0,
        log_likelihood="",
        grasp="",
        evaluations=0,
        rejected=0,
        error=" ".join(str(error).split()),
        t_features="",
        t_query="",
        t_sampling="",
        t_optimisation="",
        t_synthesis=t_synthesis,
        t_execution=0.0,
    )
    return row


def _executed_grasp(best) -> dict:
    """The executed grasp as the log keeps it: its pose and joints, and its type when the model has several
    (a one-type model's rows stay those of a single-demonstration model)."""
    entry = best.to_dict(execution_only=True)
    if REFERENCE_EXPERT in (best.experts or {}):
        entry["type"] = best.type
    return entry


def _executed(row: dict, grasps, result, t_exec: float) -> dict:
    best, tm = grasps.best(), grasps.timing
    row.update(
        success=int(bool(result.success)),
        reason=result.reason,
        lift_height=float(result.lift_height),
        contact_count=int(result.contact_count),
        log_likelihood=float(best.log_likelihood),
        grasp=json.dumps(_executed_grasp(best), separators=(",", ":")),
        evaluations=int(grasps.evaluations),
        rejected=int(grasps.rejected),
        # The paper's "features" stage: everything before the synthesiser's own stages (the segmentation, i.e. the
        # clean-up, and the surface features), as every run in results/ recorded it.
        t_features=tm["segmentation"] + tm["features"],
        t_query=tm["query"],
        t_sampling=tm["sampling"],
        t_optimisation=tm["optimisation"],
        t_synthesis=tm["total"],
        t_execution=t_exec,
    )
    return row


def run_attempt(
    p: Protocol, model_path: str, key: tuple, noise: bool, acq: Acquisition, acq_seed: int, t_acq: float, pose
) -> dict:
    """One attempt: synthesise on the unit's cloud, execute the best grasp at the object's rest pose."""
    obj, trial, cond, method = key
    c = CONDITIONS[cond]
    model = cached_model(model_path)
    seed = p.synthesis_seed(obj, trial, cond)
    row = {
        "object": obj,
        "trial": trial,
        "condition": cond,
        "method": method,
        "noise": int(noise),
        "optimise": int(c.optimise),
        "acquisition_seed": acq_seed,
        "synthesis_seed": seed,
        "n_points": len(acq.points),
        "t_acquisition": t_acq,
        "error": "",
    }
    t1 = time.perf_counter()
    try:
        grasps = synthesize_on(model, acq, p, obj, trial, cond)
        if len(grasps) == 0:
            raise ValueError("synthesis returned no grasps")
    except (ValueError, RuntimeError) as e:
        return _failed(row, e, time.perf_counter() - t1)
    t2 = time.perf_counter()
    r = execute(obj, grasps.best(), hand=model.hand, object_pose=pose, **CLOSING[p.closing])
    return _executed(row, grasps, r, time.perf_counter() - t2)


def run_unit(protocol: dict, unit: tuple, todo: Iterable[tuple] | None = None) -> list[dict]:
    """The attempts of one (object, trial, noise) unit: acquire once, then per condition and method
    synthesise, execute the best grasp, and return one row per attempt. A pure function of its input.

    protocol: Protocol.to_json() plus "model_paths" (method -> path). todo: the attempt keys to run
    (default: all of the unit's)."""
    p = protocol_from_json(protocol)
    obj, trial, noise = unit[0], int(unit[1]), bool(unit[2])
    keys = [tuple(k) for k in (todo if todo is not None else p.attempts((obj, trial, noise)))]
    acq_seed = p.acquisition_seed(obj, trial)
    keys = _unit_order(p, keys, acq_seed)
    t0 = time.perf_counter()
    acq = acquire_unit(p, obj, trial, noise)
    t_acq = time.perf_counter() - t0
    pose = rest_pose(obj)
    return [
        run_attempt(p, protocol["model_paths"][k[3]], (obj, trial, k[2], k[3]), noise, acq, acq_seed, t_acq, pose)
        for k in keys
    ]
