"""The grasp-execution protocol of graspmix's Bullet simulation, run in pybullet (DIRECT) with the same
URDFs: the independent reference the agreement test compares the C++ simulation against."""

from __future__ import annotations

import math
import tempfile
import xml.etree.ElementTree as ET
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from .. import _core
from ..model.grasps import Grasp
from .execution import SimSettings, grasp_arrays, load_hand, load_object, make_settings, rest_pose


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


def _load_world(p, kw: dict, s: SimSettings, h, o, pose, wrist) -> tuple[int, int, int]:
    """Plane, object at its pose (with the settings' friction and mass) and the lifted hand: their ids."""
    import pybullet_data

    with tempfile.TemporaryDirectory() as tmp:
        p.setGravity(*np.asarray(s.gravity), **kw)
        p.setTimeStep(s.time_step, **kw)
        p.setPhysicsEngineParameter(numSolverIterations=s.solver_iterations, **kw)
        plane = p.loadURDF(str(Path(pybullet_data.getDataPath()) / "plane.urdf"), **kw)
        p.changeDynamics(plane, -1, lateralFriction=s.support_friction, **kw)
        body = p.loadURDF(str(o.source), **kw)
        dyn = p.getDynamicsInfo(body, -1, **kw)
        com = _core.pose_multiply(pose[None], np.r_[dyn[3], dyn[4]][None])[0]
        p.resetBasePositionAndOrientation(body, com[:3], com[3:], **kw)
        friction = (
            s.object_friction if s.object_friction >= 0 else (o.lateral_friction if o.lateral_friction >= 0 else 0.5)
        )
        p.changeDynamics(
            body,
            -1,
            lateralFriction=friction,
            restitution=0.0,
            spinningFriction=0.0,
            rollingFriction=0.0,
            activationState=p.ACTIVATION_STATE_DISABLE_SLEEPING,
            **kw,
        )
        if s.object_mass >= 0:
            p.changeDynamics(body, -1, mass=s.object_mass, **kw)
        hid = p.loadURDF(str(_lifted_urdf(h, wrist, Path(tmp))), wrist[:3], wrist[3:], useFixedBase=True, **kw)
    return plane, body, hid


def _hand_drives(p, kw: dict, s: SimSettings, h, hid: int, pre, fin) -> tuple[dict, list]:
    """Sets the hand's joints to the pre-grasp; (joint ids by name, [(joint, target, speed)] of the closing)."""
    joints = {p.getJointInfo(hid, j, **kw)[1].decode(): j for j in range(p.getNumJoints(hid, **kw))}
    for j in joints.values():
        p.changeDynamics(
            hid, j, lateralFriction=s.hand_friction, restitution=0.0, spinningFriction=0.0, rollingFriction=0.0, **kw
        )
        p.setJointMotorControl2(hid, j, p.VELOCITY_CONTROL, force=0.0, **kw)
    start = h.all_joint_values(pre)
    goal = h.all_joint_values(fin)
    limits = {j["name"]: j["limits"] for j in h.joints}
    # The protocol's speed limits (the fingertips at close_speed m/s): the same numbers as the C++ simulation's.
    speeds = dict(zip((j["name"] for j in h.joints), _core.sim_closing_speeds(h, pre, fin, s)))
    drives = []
    for name, q0 in start.items():
        p.resetJointState(hid, joints[name], q0, **kw)
        target = goal[name] + s.close_overshoot * (goal[name] - q0)
        lo, hi = limits[name]
        if math.isfinite(lo) and math.isfinite(hi) and lo <= hi:
            target = min(max(target, lo), hi)
        drives.append((joints[name], target, float(speeds[name])))
    return joints, drives


def _run_protocol(p, kw: dict, s: SimSettings, plane: int, body: int, hid: int, lift: int, drives: list) -> dict:
    """Start check, closing, lift and hold: the result dictionary."""
    dt = s.time_step

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
        out.update(
            success=reason == "success",
            reason=reason,
            contact_count=n,
            lift_height=p.getBasePositionAndOrientation(body, **kw)[0][2] - z0,
        )
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


@contextmanager
def _world(obj, grasp: Grasp, hand, object_pose, settings: SimSettings | None):
    """A pybullet world (DIRECT) with the plane, the object at its pose and the hand at the grasp's wrist and
    pre-grasp: yields (pybullet, kw, settings, plane, body, hand id, joints, drives); disconnects after."""
    import pybullet as p

    s = make_settings(settings)
    h = load_hand(hand)
    o = load_object(obj)
    wrist, pre, fin = grasp_arrays(h, grasp)
    pose = rest_pose(o) if object_pose is None else np.asarray(object_pose, dtype=float)
    cid = p.connect(p.DIRECT)
    try:
        kw = {"physicsClientId": cid}
        plane, body, hid = _load_world(p, kw, s, h, o, pose, wrist)
        joints, drives = _hand_drives(p, kw, s, h, hid, pre, fin)
        yield p, kw, s, plane, body, hid, joints, drives
    finally:
        p.disconnect(cid)


def execute_pybullet(
    obj, grasp: Grasp, *, hand=None, object_pose=None, settings: SimSettings | None = None, **overrides
) -> dict:
    """The same protocol as execute, in pybullet (DIRECT) with the same URDFs: the reference for the
    agreement test. Returns {success, reason, lift_height, contact_count, start_penetration, steps}."""
    with _world(obj, grasp, hand, object_pose, make_settings(settings, **overrides)) as w:
        p, kw, s, plane, body, hid, joints, drives = w
        return _run_protocol(p, kw, s, plane, body, hid, joints["graspmix_lift"], drives)


def start_penetrations(
    obj, grasp: Grasp, *, hand=None, object_pose=None, settings: SimSettings | None = None
) -> dict[tuple[str, str], float]:
    """What a grasp's start (the hand at its pre-grasp) penetrates, in pybullet with the same URDFs as
    execute_pybullet: {(what, link): deepest penetration in m} for every hand link deeper than the settings'
    start_penetration, `what` being "object" or "plane"; empty when the grasp starts clear."""
    with _world(obj, grasp, hand, object_pose, settings) as w:
        p, kw, s, plane, body, hid = w[:6]
        p.performCollisionDetection(**kw)
        out: dict[tuple[str, str], float] = {}
        for c in p.getContactPoints(bodyA=hid, **kw):
            if -c[8] > s.start_penetration and c[2] in (body, plane):
                link = p.getJointInfo(hid, c[3], **kw)[12].decode() if c[3] >= 0 else "base"
                key = ("object" if c[2] == body else "plane", link)
                out[key] = max(out.get(key, 0.0), -c[8])
        return out
