"""Grasp execution in Bullet physics (the paper's "Experiments").

``execute`` runs one grasp in the C++ Bullet simulation (``graspmix._core.sim_execute``; see
``include/graspmix/sim.hpp`` for the protocol: start check, force-limited closing past the grasp joints,
a 20 cm lift, a hold, success if the object is still held). ``execute_pybullet`` runs the same protocol
in pybullet with the same URDFs: the independent reference the agreement test compares against.

The object stands where the acquisition put it (``rest_pose``), so grasps synthesised on an acquired
cloud are executed in the cloud's frame; every execution starts from that same pose.
"""

from __future__ import annotations

import functools
import math
from pathlib import Path
from typing import Any

import numpy as np

from .. import _core
from ..io import default_hand_path, resolve_object, resolve_path
from ..io.checks import MAX_SIM_TIME, check_float, check_input_file, check_int, quote
from ..model.grasps import Grasp, check_grasp, grasp_by_rank, load_grasps
from .acquisition import AcquisitionSettings, TableWorld

SimSettings = _core.SimSettings
SimResult = _core.SimResult
SimObject = _core.SimObject

# How an executed grasp closes. "full": the fingers close, force-limited, until they stop on the object or
# reach their closed limit, as a parallel gripper's grasp command does (the simulation's motor target is
# pushed past the grasp joints far enough to be clamped to the closed limit). "learnt": the simulation's
# default, a target 0.5 x (grasp - pregrasp) past the synthesised grasp joints; with a configuration
# model learnt from one 6 cm box, the fingers then stop about 4.4 cm apart and cannot hold anything
# narrower, whatever the method.
CLOSING = {"full": {"close_overshoot": 1000.0}, "learnt": {}}


def closing_overrides(closing: str) -> dict:
    """The SimSettings overrides of a closing rule (CLOSING); ValueError for an unknown one."""
    if not isinstance(closing, str) or closing not in CLOSING:
        raise ValueError(f"closing must be one of {', '.join(CLOSING)}, got {quote(closing)}")
    return dict(CLOSING[closing])


@functools.lru_cache(maxsize=16)
def _hand(path: str) -> _core.Hand:
    return _core.Hand.from_urdf(path)


@functools.lru_cache(maxsize=128)
def _object(path: str) -> SimObject:
    return SimObject.from_urdf(path)


def load_hand(hand=None) -> _core.Hand:
    """A Hand, a URDF path, or None for the bundled WSG 50 (loaded once per path)."""
    if isinstance(hand, _core.Hand):
        return hand
    return _hand(str(check_input_file(hand or default_hand_path(), "hand").resolve()))


def load_object(obj) -> SimObject:
    """A SimObject, or an object URDF path (a file, or relative to pybullet_data)."""
    if isinstance(obj, SimObject):
        return obj
    return _object(str(resolve_object(obj)))


def make_settings(settings: SimSettings | None = None, **overrides) -> SimSettings:
    """A copy of settings (or the defaults) with keyword overrides; unknown names are a ValueError."""
    s = SimSettings()
    if settings is not None:
        for name in _settings_names():
            setattr(s, name, getattr(settings, name))
    for name, value in overrides.items():
        if name not in _settings_names():
            raise ValueError(f"unknown simulation setting {quote(name)} (known: {', '.join(_settings_names())})")
        setattr(s, name, _checked_setting(name, value))
    check_settings(s)
    return s


# Settings that are durations (s) or that, over a speed, make one: each phase of the simulation is at most
# MAX_SIM_TIME simulated seconds, and a step at least MIN_TIME_STEP, so no setting makes the C++ step count
# overflow or the run last for hours.
MIN_TIME_STEP = 1e-4  # s


def _checked_setting(name: str, value):
    """A keyword override, its type checked before pybind11 casts it."""
    if name == "gravity":
        g = np.asarray(value, dtype=float) if not isinstance(value, str) else None
        if g is None or g.shape != (3,) or not np.all(np.isfinite(g)):
            raise ValueError(f"gravity must be 3 finite numbers (m/s^2), got {quote(value)}")
        return g
    if name == "solver_iterations":
        return check_int(value, name, 1, 10_000)
    return check_float(value, name)


def check_settings(s: SimSettings) -> None:
    """Every SimSettings number finite, every phase at most MAX_SIM_TIME s, the step in [1e-4, 0.1] s."""
    for name in _settings_names():
        if name not in ("gravity", "solver_iterations"):
            check_float(getattr(s, name), f"SimSettings.{name}")
    check_float(s.time_step, "SimSettings.time_step", MIN_TIME_STEP, 0.1)
    for name in ("close_time", "hold_time"):
        check_float(getattr(s, name), f"SimSettings.{name}", 0.0, MAX_SIM_TIME)
    speed = check_float(s.lift_speed, "SimSettings.lift_speed", gt=0.0)
    if abs(s.lift_height) / speed > MAX_SIM_TIME:
        raise ValueError(
            f"SimSettings.lift_height / lift_speed = {abs(s.lift_height) / speed:g} s: the lift would "
            f"take longer than {MAX_SIM_TIME:g} s simulated"
        )


def _settings_names() -> list[str]:
    return [n for n in dir(SimSettings) if not n.startswith("_")]


@functools.lru_cache(maxsize=128)
def _object_pose_cached(path: str, position: tuple, orientation: tuple) -> tuple:
    s = AcquisitionSettings(cameras=[], object_position=position, object_orientation=orientation)
    import pybullet as p

    with TableWorld(path, s) as scene:
        com = scene.object_pose()
        dyn = p.getDynamicsInfo(scene.body, -1, physicsClientId=scene.client)
    T_link_com = np.r_[dyn[3], dyn[4]]
    return tuple(_core.pose_multiply(com[None], _core.pose_inverse(T_link_com[None]))[0])


def rest_pose(obj, settings: AcquisitionSettings | None = None) -> np.ndarray:
    """The object's link pose (7,) in the world as the acquisition places it: at settings' position and
    orientation, lifted to rest on the plane z = 0 (pybullet's bounding box)."""
    s = settings or AcquisitionSettings()
    path = str(resolve_object(obj.source if isinstance(obj, SimObject) else obj))
    return np.array(
        _object_pose_cached(path, tuple(map(float, s.object_position)), tuple(map(float, s.object_orientation)))
    )


# ---- grasps.json ------------------------------------------------------------------------------


def _doc_hand_file(doc_hand: str | None, grasps_path) -> Path | None:
    """The grasps file's hand URDF if it exists (as given, or relative to the grasps file)."""
    if not doc_hand:
        return None
    p = resolve_path(doc_hand, Path(grasps_path).resolve().parent)  # package://graspmix/..., absolute or relative
    return p if p.is_file() else None


def _check_hand_matches(hand: _core.Hand, doc_hand: str | None, grasps_path="."):
    """A grasps file names its hand; a grasp for another hand is an error, not a silent misfire."""
    if not doc_hand:
        return
    name = Path(doc_hand).stem
    found = _doc_hand_file(doc_hand, grasps_path)
    try:
        other = _core.Hand.from_urdf(found).name if found else None
    except ValueError:
        other = None
    if other is not None and other != hand.name:
        raise ValueError(f"the grasps are for hand {other!r} ({doc_hand}), not {hand.name!r}")
    if other is None and name not in (hand.name, Path(hand.source).stem):
        raise ValueError(f"the grasps are for hand {doc_hand!r}, not {hand.name!r} ({hand.source})")


def grasp_arrays(hand: _core.Hand, grasp: Grasp) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(wrist (7,), pre-grasp joints, grasp joints) of a Grasp, checked against the hand."""
    grasp = check_grasp(grasp)
    try:
        wrist = np.asarray(grasp.T_world_wrist, dtype=float)
    except (TypeError, ValueError):
        wrist = None
    if wrist is None or wrist.shape != (7,):
        raise ValueError(
            f"T_world_wrist: expected 7 numbers [x, y, z, qx, qy, qz, qw], got {quote(grasp.T_world_wrist)}"
        )
    joints = []
    for name in ("pregrasp_joints", "grasp_joints"):
        try:
            joints.append(hand.joints_array(getattr(grasp, name)))
        except ValueError as e:
            raise ValueError(
                f"{name}: the grasp does not fit hand {hand.name!r} (joints {hand.joint_names}): {e}"
            ) from None
    return wrist, joints[0], joints[1]


def execute(
    obj,
    grasp: Grasp | None = None,
    *,
    hand=None,
    T_world_wrist=None,
    pregrasp_joints=None,
    grasp_joints=None,
    object_pose=None,
    settings: SimSettings | None = None,
    **overrides,
) -> SimResult:
    """Executes one grasp in Bullet (C++) and returns a SimResult (success, reason, lift_height,
    contact_count, steps, simulated_time, wall_time).

    obj: an object URDF (path or relative to pybullet_data) or a SimObject. grasp: a Grasp (its
    T_world_wrist, pregrasp_joints and grasp_joints), or give those three as keywords.
    hand: a Hand or URDF path (default: the bundled WSG 50). object_pose: the object's link pose (7,);
    default: where the acquisition places it (rest_pose). settings/overrides: SimSettings fields.
    """
    settings = make_settings(settings, **overrides)  # checked before anything is loaded
    h = load_hand(hand)
    o = load_object(obj)
    if grasp is None:
        if any(v is None for v in (T_world_wrist, pregrasp_joints, grasp_joints)):
            raise ValueError("give a grasp, or T_world_wrist, pregrasp_joints and grasp_joints")
        grasp = Grasp(T_world_wrist, pregrasp_joints, grasp_joints)
    wrist, pre, fin = grasp_arrays(h, grasp)
    pose = rest_pose(o) if object_pose is None else np.asarray(object_pose, dtype=float)
    return _core.sim_execute(h, o, pose, wrist, pre, fin, settings)


def grasps_and_hand(grasps_path, hand=None) -> tuple[dict, _core.Hand]:
    """A grasps.json and its hand: the given Hand or URDF; None: the file's hand if it can be found (as given
    or relative to the grasps file), else the bundled WSG 50; either way the file's hand must be the one
    used (ValueError otherwise)."""
    doc = load_grasps(grasps_path)
    if hand is None:
        hand = _doc_hand_file(doc.get("hand"), grasps_path)
    h = load_hand(hand)
    _check_hand_matches(h, doc.get("hand"), grasps_path)
    return doc, h


def execute_file(
    obj, grasps_path, rank: int = 1, hand=None, settings: SimSettings | None = None, **overrides
) -> SimResult:
    """Executes the grasp of the given rank from a grasps.json (its hand: see grasps_and_hand)."""
    rank = check_int(rank, "rank", 1)
    doc, h = grasps_and_hand(grasps_path, hand)
    return execute(obj, grasp_by_rank(doc, rank), hand=h, settings=settings, **overrides)


def top_grasp(center, opening: float, closing: float, yaw: float = 0.0, tip_height: float = 0.01, hand=None) -> Grasp:
    """A WSG 50-style top grasp (palm z pointing down) over `center` (x, y), fingertips `tip_height` above
    the plane, pre-grasp finger distance `opening`, grasp `closing` (each finger's distance from the
    centre, m), fingers moving along the direction at angle `yaw` about world z. For tests and examples."""
    from scipy.spatial.transform import Rotation

    h = load_hand(hand)
    # Palm top at 72.5 mm above the flange, fingertips 81 mm above the palm top (data/hands/wsg50.urdf).
    reach = 0.0725 + 0.081
    q = (Rotation.from_euler("z", yaw) * Rotation.from_euler("x", math.pi)).as_quat()
    wrist = [float(center[0]), float(center[1]), tip_height + reach, *q]
    name = h.joint_names[0]
    return Grasp(wrist, {name: opening}, {name: closing})


def result_dict(r: SimResult) -> dict[str, Any]:
    return {
        "success": r.success,
        "reason": r.reason,
        "lift_height": r.lift_height,
        "contact_count": r.contact_count,
        "start_penetration": r.start_penetration,
        "steps": r.steps,
        "simulated_time": r.simulated_time,
        "wall_time": r.wall_time,
    }
