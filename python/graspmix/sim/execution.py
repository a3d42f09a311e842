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
import json
import math
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from . import _core
from .acquisition import AcquisitionSettings, Scene, resolve_object
from .model import GRASPS_FORMAT, _read_json, _resolve

SimSettings = _core.SimSettings
SimResult = _core.SimResult
SimObject = _core.SimObject

DATA = Path(__file__).resolve().parent / "data"


def default_hand_path() -> Path:
    """The bundled WSG 50 URDF."""
    return DATA / "hands" / "wsg50.urdf"


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
    return _hand(str(Path(hand or default_hand_path()).resolve()))


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
            raise ValueError(f"unknown simulation setting {name!r} (known: {', '.join(_settings_names())})")
        setattr(s, name, value)
    return s


def _settings_names() -> list[str]:
    return [n for n in dir(SimSettings) if not n.startswith("_")]


@functools.lru_cache(maxsize=128)
def _object_pose_cached(path: str, position: tuple, orientation: tuple) -> tuple:
    s = AcquisitionSettings(cameras=[], object_position=position, object_orientation=orientation)
    import pybullet as p

    with Scene(path, s) as scene:
        com = scene.object_pose()
        dyn = p.getDynamicsInfo(scene.body, -1, physicsClientId=scene.client)
    T_link_com = np.r_[dyn[3], dyn[4]]
    return tuple(_core.pose_multiply(com[None], _core.pose_inverse(T_link_com[None]))[0])


def rest_pose(obj, settings: AcquisitionSettings | None = None) -> np.ndarray:
    """The object's link pose (7,) in the world as the acquisition places it: at settings' position and
    orientation, lifted to rest on the plane z = 0 (pybullet's bounding box)."""
    s = settings or AcquisitionSettings()
    path = str(resolve_object(obj.source if isinstance(obj, SimObject) else obj))
    return np.array(_object_pose_cached(path, tuple(map(float, s.object_position)), tuple(map(float, s.object_orientation))))


# ---- grasps.json ------------------------------------------------------------------------------

def load_grasps(path) -> dict:
    """Reads and checks a grasps.json (format graspmix.grasps/1); grasps come back sorted by rank."""
    doc = _read_json(Path(path), "grasps")
    if doc.get("format") != GRASPS_FORMAT:
        raise ValueError(f"{path}: expected format {GRASPS_FORMAT!r}, got {doc.get('format')!r}")
    grasps = doc.get("grasps")
    if not isinstance(grasps, list) or not grasps:
        raise ValueError(f"{path}: no grasps")
    for i, g in enumerate(grasps):
        for key in ("T_world_wrist", "pregrasp_joints", "grasp_joints"):
            if key not in g:
                raise ValueError(f"{path}: grasp {i} has no {key!r}")
        g.setdefault("rank", i + 1)
    doc["grasps"] = sorted(grasps, key=lambda g: g["rank"])
    return doc


def grasp_by_rank(doc: Mapping, rank: int = 1) -> dict:
    for g in doc["grasps"]:
        if g["rank"] == rank:
            return g
    raise ValueError(f"no grasp of rank {rank} (ranks {doc['grasps'][0]['rank']}..{doc['grasps'][-1]['rank']})")


def _doc_hand_file(doc_hand: str | None, grasps_path) -> Path | None:
    """The grasps file's hand URDF if it exists (as given, or relative to the grasps file)."""
    if not doc_hand:
        return None
    p = _resolve(doc_hand, Path(grasps_path).resolve().parent)  # package://graspmix/..., absolute or relative
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


def _grasp_arrays(hand: _core.Hand, grasp: Mapping) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    wrist = np.asarray(grasp["T_world_wrist"], dtype=float)
    if wrist.shape != (7,):
        raise ValueError(f"T_world_wrist: expected 7 values [x, y, z, qx, qy, qz, qw], got shape {wrist.shape}")
    try:
        pre = hand.joints_array(grasp["pregrasp_joints"])
        fin = hand.joints_array(grasp["grasp_joints"])
    except ValueError as e:
        raise ValueError(f"the grasp does not fit hand {hand.name!r} (joints {hand.joint_names}): {e}") from None
    return wrist, pre, fin


def execute(obj, grasp: Mapping | None = None, *, hand=None, T_world_wrist=None, pregrasp_joints=None,
            grasp_joints=None, object_pose=None, settings: SimSettings | None = None, **overrides) -> SimResult:
    """Executes one grasp in Bullet (C++) and returns a SimResult (success, reason, lift_height,
    contact_count, steps, simulated_time, wall_time).

    obj: an object URDF (path or relative to pybullet_data) or a SimObject. grasp: one entry of a
    grasps.json (T_world_wrist, pregrasp_joints, grasp_joints), or give those three as keywords.
    hand: a Hand or URDF path (default: the bundled WSG 50). object_pose: the object's link pose (7,);
    default: where the acquisition places it (rest_pose). settings/overrides: SimSettings fields.
    """
    h = load_hand(hand)
    o = load_object(obj)
    if grasp is None:
        grasp = {"T_world_wrist": T_world_wrist, "pregrasp_joints": pregrasp_joints, "grasp_joints": grasp_joints}
        if any(v is None for v in grasp.values()):
            raise ValueError("give a grasp, or T_world_wrist, pregrasp_joints and grasp_joints")
    wrist, pre, fin = _grasp_arrays(h, grasp)
    pose = rest_pose(o) if object_pose is None else np.asarray(object_pose, dtype=float)
    return _core.sim_execute(h, o, pose, wrist, pre, fin, make_settings(settings, **overrides))


def execute_file(obj, grasps_path, rank: int = 1, hand=None, settings: SimSettings | None = None, **overrides) -> SimResult:
    """Executes the grasp of the given rank from a grasps.json. hand: a Hand or URDF; None: the file's
    hand if it can be found (as given or relative to the grasps file), else the bundled WSG 50; either way
    the file's hand must be the one used (ValueError otherwise)."""
    doc = load_grasps(grasps_path)
    if hand is None:
        hand = _doc_hand_file(doc.get("hand"), grasps_path)
    h = load_hand(hand)
    _check_hand_matches(h, doc.get("hand"), grasps_path)
    return execute(obj, grasp_by_rank(doc, rank), hand=h, settings=settings, **overrides)


# ---- the pybullet reference ---------------------------------------------------------------------

def _lifted_urdf(hand: _core.Hand, T_world_wrist: np.ndarray, out_dir: Path) -> Path:
    """The hand's URDF under a fixed base at the wrist with a prismatic 'lift' joint along world +z,
    the same structure the C++ simulation builds."""
    tree = ET.parse(hand.source)
    robot = tree.getroot()
    # The copy lives elsewhere: visuals go (nothing is rendered) and every collision mesh gets the file
    # graspmix resolved for it (relative and package:// paths alike), in the same order.
    for link in robot.findall("link"):
        for vis in link.findall("visual"):
            link.remove(vis)
        shapes = iter(hand.collision_shapes(link.get("name")))
        for col in link.findall("collision"):
            geom = col.find("geometry")
            if geom is None or len(geom) == 0:
                continue
            shape = next(shapes)
            mesh = geom.find("mesh")
            if mesh is not None:
                mesh.set("filename", shape["file"])
    from scipy.spatial.transform import Rotation

    axis = Rotation.from_quat(T_world_wrist[3:]).inv().apply([0.0, 0.0, 1.0])
    base = ET.SubElement(robot, "link", name="graspmix_lift_base")
    inertial = ET.SubElement(base, "inertial")  # a fixed base: its mass is never used
    ET.SubElement(inertial, "mass", value="0.001")
    ET.SubElement(inertial, "inertia", ixx="1e-6", ixy="0", ixz="0", iyy="1e-6", iyz="0", izz="1e-6")
    joint = ET.SubElement(robot, "joint", name="graspmix_lift", type="prismatic")
    ET.SubElement(joint, "parent", link="graspmix_lift_base")
    ET.SubElement(joint, "child", link=hand.root_link)
    ET.SubElement(joint, "origin", xyz="0 0 0", rpy="0 0 0")
    ET.SubElement(joint, "axis", xyz=" ".join(repr(float(a)) for a in axis))
    ET.SubElement(joint, "limit", lower="-10", upper="10", effort="1e6", velocity="100")
    out = out_dir / "lifted_hand.urdf"
    tree.write(out)
    return out


def execute_pybullet(obj, grasp: Mapping, *, hand=None, object_pose=None, settings: SimSettings | None = None,
                     **overrides) -> dict:
    """The same protocol as execute, in pybullet (DIRECT) with the same URDFs: the reference for the
    agreement test. Returns {success, reason, lift_height, contact_count, start_penetration, steps}."""
    import pybullet as p
    import pybullet_data

    s = make_settings(settings, **overrides)
    h = load_hand(hand)
    o = load_object(obj)
    wrist, pre, fin = _grasp_arrays(h, grasp)
    pose = rest_pose(o) if object_pose is None else np.asarray(object_pose, dtype=float)
    dt = s.time_step
    cid = p.connect(p.DIRECT)
    try:
        with tempfile.TemporaryDirectory() as tmp:
            kw = {"physicsClientId": cid}
            p.setGravity(*np.asarray(s.gravity), **kw)
            p.setTimeStep(dt, **kw)
            p.setPhysicsEngineParameter(numSolverIterations=s.solver_iterations, **kw)
            plane = p.loadURDF(str(Path(pybullet_data.getDataPath()) / "plane.urdf"), **kw)
            p.changeDynamics(plane, -1, lateralFriction=s.support_friction, **kw)
            body = p.loadURDF(str(o.source), **kw)
            dyn = p.getDynamicsInfo(body, -1, **kw)
            com = _core.pose_multiply(pose[None], np.r_[dyn[3], dyn[4]][None])[0]
            p.resetBasePositionAndOrientation(body, com[:3], com[3:], **kw)
            friction = s.object_friction if s.object_friction >= 0 else (o.lateral_friction if o.lateral_friction >= 0 else 0.5)
            p.changeDynamics(body, -1, lateralFriction=friction, restitution=0.0, spinningFriction=0.0, rollingFriction=0.0,
                             activationState=p.ACTIVATION_STATE_DISABLE_SLEEPING, **kw)
            if s.object_mass >= 0:
                p.changeDynamics(body, -1, mass=s.object_mass, **kw)
            hid = p.loadURDF(str(_lifted_urdf(h, wrist, Path(tmp))), wrist[:3], wrist[3:], useFixedBase=True, **kw)
        joints = {p.getJointInfo(hid, j, **kw)[1].decode(): j for j in range(p.getNumJoints(hid, **kw))}
        for j in joints.values():
            p.changeDynamics(hid, j, lateralFriction=s.hand_friction, restitution=0.0, spinningFriction=0.0,
                             rollingFriction=0.0, **kw)
            p.setJointMotorControl2(hid, j, p.VELOCITY_CONTROL, force=0.0, **kw)
        start = h.all_joint_values(pre)
        goal = h.all_joint_values(fin)
        limits = {j["name"]: j["limits"] for j in h.joints}
        drives = []
        for name, q0 in start.items():
            p.resetJointState(hid, joints[name], q0, **kw)
            target = goal[name] + s.close_overshoot * (goal[name] - q0)
            lo, hi = limits[name]
            if math.isfinite(lo) and math.isfinite(hi) and lo <= hi:
                target = min(max(target, lo), hi)
            speed = max(s.close_speed, 2.0 * abs(goal[name] - q0) / max(s.close_time, dt))
            drives.append((joints[name], target, speed))
        lift = joints["graspmix_lift"]

        def contacts(below):
            n, deepest = 0, 0.0
            for c in p.getContactPoints(bodyA=hid, **kw):
                if c[2] not in (body, plane):
                    continue
                deepest = max(deepest, -c[8])
                if c[2] == body and c[8] < below:
                    n += 1
            return n, deepest

        out = {"steps": 0}

        def finish(reason, n=0):
            out.update(success=reason == "success", reason=reason, contact_count=n,
                       lift_height=p.getBasePositionAndOrientation(body, **kw)[0][2] - z0)
            return out

        z0 = p.getBasePositionAndOrientation(body, **kw)[0][2]
        p.performCollisionDetection(**kw)
        _, deepest = contacts(s.contact_distance)
        out["start_penetration"] = max(0.0, deepest)
        if deepest > s.start_penetration:
            return finish("start in collision")
        state = {"lift": 0.0}

        def step():
            for j, target, speed in drives:
                err = target - p.getJointState(hid, j, **kw)[0]
                v = min(max(s.position_gain * err, -speed), speed)
                p.setJointMotorControl2(hid, j, p.VELOCITY_CONTROL, targetVelocity=v, force=s.grip_force, **kw)
            err = state["lift"] - p.getJointState(hid, lift, **kw)[0]
            v = min(max(s.position_gain * err, -s.lift_speed), s.lift_speed)
            p.setJointMotorControl2(hid, lift, p.VELOCITY_CONTROL, targetVelocity=v, force=s.lift_force, **kw)
            p.stepSimulation(**kw)
            out["steps"] += 1

        def n_steps(seconds):
            return int(math.ceil(seconds / dt - 1e-9))

        for _ in range(n_steps(s.close_time)):
            step()
        n, _ = contacts(s.contact_distance)
        if n == 0:
            return finish("no contact")
        state["lift"] = s.lift_height
        for _ in range(n_steps(s.lift_height / s.lift_speed + 0.1) + n_steps(s.hold_time)):
            step()
        n, _ = contacts(s.contact_distance)
        rise = p.getBasePositionAndOrientation(body, **kw)[0][2] - z0
        return finish("success" if n > 0 and rise >= s.success_fraction * s.lift_height else "not held", n)
    finally:
        p.disconnect(cid)


def top_grasp(center, opening: float, closing: float, yaw: float = 0.0, tip_height: float = 0.01,
              hand=None) -> dict:
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
    return {"T_world_wrist": wrist, "pregrasp_joints": {name: opening}, "grasp_joints": {name: closing}}


def result_dict(r: SimResult) -> dict[str, Any]:
    return {"success": r.success, "reason": r.reason, "lift_height": r.lift_height, "contact_count": r.contact_count,
            "start_penetration": r.start_penetration, "steps": r.steps, "simulated_time": r.simulated_time,
            "wall_time": r.wall_time}


def test_objects(path=None) -> list[str]:
    """The paper's 60 test objects (data/objects/test60.txt): paths relative to pybullet_data."""
    p = Path(path) if path else DATA / "objects" / "test60.txt"
    if not p.is_file():
        raise ValueError(f"{p}: no such object list")
    return [line.split("#")[0].strip() for line in p.read_text().splitlines() if line.split("#")[0].strip()]
