"""Recording a grasp demonstration in simulation (pybullet, DIRECT mode).

The object rests on a plane; its cloud is acquired by the simulated depth cameras; the hand is placed at
the demonstrated wrist pose with its pre-grasp joints and closes with force-limited position motors
until its joints stop; the joints it stops at are the demonstrated grasp. The result is a
Demonstration (the file format of the design guide).

A recording refuses what it cannot record honestly: joint values beyond the URDF limits, a pre-grasp
whose links penetrate the object or the table (found after pybullet's collision detection has run),
fingers that end wider than they started, a hand that pushed the object away, and a hand that closed
in the air. pybullet does not enforce URDF mimic joints, so every mimic joint gets its own motor whose
target follows its master joint (multiplier * master + offset) at every step: linkage grippers record.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .. import _core
from ..io.checks import MAX_ITERATIONS, check_float, check_input_file, check_int, check_seed
from ..model import Demonstration
from ..model.demonstration import DEMO_GRIP_FORCE, DEMO_MAX_STEPS
from ..model.grasp_frames import rotation_matrices
from .acquisition import AcquisitionSettings, TableWorld, acquire

PENETRATION_TOLERANCE = 1e-3  # m: a pre-grasp link deeper than this in the object or the table is refused
OBJECT_PUSHED = 0.01  # m: an object that moved further while the hand closed was pushed, not grasped
# degrees: an approach axis further off the direction from the wrist to the object is named in a failed recording's
# message (a top grasp of a box aims within a few degrees; 60 leaves room for side and edge grasps)
AIM_OFF_DEG = 60.0
# A mimic joint is a mechanical linkage, not a second motor: its motor (MIMIC_STIFFNESS times the grip force)
# holds it on its master's value, so the grip force acts once, as in the real mechanism.
MIMIC_STIFFNESS = 10.0
OPENED_TOLERANCE = 1e-3  # m or rad: a joint that ends further open than its pre-grasp by more was pushed open
# Joints that never rest by their speed but swing in a band narrower than this (m or rad) over the last REST_WINDOW
# steps are at rest too: fingers squeezing a small object low on their pads can settle into a cycle of a few steps
# between two contact sets (the WSG 50 on a 30 mm box, fingertips 10 mm above the table: 0.6 mm at 0.13 m/s).
REST_BAND = 1e-3
REST_WINDOW = 240


@dataclass
class Recording:
    """A recorded demonstration and what pybullet saw at its end: the URDF frame of every hand link
    (name -> [x, y, z, qx, qy, qz, qw], world), the links touching the object, and how far the object moved."""

    demonstration: Demonstration
    link_poses: dict = field(default_factory=dict)
    touching_links: list = field(default_factory=list)
    object_shift: float = 0.0


def record_demonstration(*args, **kwargs) -> Demonstration:
    """record(...)'s demonstration: the hand closed from `pregrasp` towards `close_to` around the object,
    with the joints where the fingers stopped. Arguments and errors as for `record`."""
    return record(*args, **kwargs).demonstration


def record(
    object_path: str | Path,
    hand_path: str | Path,
    T_world_wrist,
    pregrasp: dict,
    close_to: dict,
    *,
    grip_force: float = DEMO_GRIP_FORCE,
    max_steps: int = DEMO_MAX_STEPS,
    settings: AcquisitionSettings | None = None,
    seed: int = 0,
) -> Recording:
    """Closes the hand from `pregrasp` towards `close_to` (name -> value, independent joints) around the
    object; returns the demonstration with the joints where the fingers stopped, and pybullet's view of
    the end of the recording (a Recording). ValueError (with the joints or links at fault) for joints
    beyond their limits, a pre-grasp in collision, a hand that did not end holding the object, or joints
    that never came to rest within `max_steps`."""
    import pybullet as p

    check_float(grip_force, "grip_force", gt=0.0)
    check_int(max_steps, "max_steps", 1, MAX_ITERATIONS)
    check_seed(seed)
    hand = _core.Hand.from_urdf(str(check_input_file(hand_path, "hand")))
    wrist = np.asarray(T_world_wrist, dtype=float)
    if wrist.shape != (7,) or not np.all(np.isfinite(wrist)):
        raise ValueError("T_world_wrist must be 7 finite numbers [x, y, z, qx, qy, qz, qw]")
    q_pre = hand.joints_array(pregrasp)
    q_close = hand.joints_array(close_to)
    check_joint_limits(hand, q_pre, "pregrasp")
    check_joint_limits(hand, q_close, "close_to")
    settings = settings or AcquisitionSettings()
    cloud = acquire(object_path, noise=False, seed=seed, settings=settings)
    with TableWorld(object_path, settings) as scene:
        c = scene.client
        p.setGravity(0, 0, -9.81, physicsClientId=c)
        body, joints = _place_hand(p, c, hand_path, wrist)
        links = _link_names(p, c, body, hand.root_link)
        for name, value in hand.all_joint_values(q_pre).items():
            p.resetJointState(body, joints[name], value, physicsClientId=c)
        start = scene.object_pose()
        aim = aim_hint(hand, wrist, start[:3])
        _check_pregrasp_collision(p, scene, body, links, _palm_links(hand), aim)
        reached = _close(p, c, hand, body, joints, q_close, grip_force, max_steps)
        p.performCollisionDetection(physicsClientId=c)
        touching = sorted({links[pt[3]] for pt in p.getContactPoints(body, scene.body, physicsClientId=c)})
        shift = float(np.linalg.norm(scene.object_pose()[:3] - start[:3]))
        poses = _link_poses(p, c, body, links, wrist)
    q_grasp = hand.joints_array(reached)
    _check_outcome(hand, q_pre, q_close, q_grasp, touching, shift, aim)
    demo = Demonstration(
        hand_path=Path(hand_path).resolve(),
        cloud=cloud.points,
        T_world_wrist=wrist,
        pregrasp_joints={n: float(v) for n, v in zip(hand.joint_names, q_pre)},
        grasp_joints={n: float(v) for n, v in zip(hand.joint_names, q_grasp)},
    )
    return Recording(demo, poses, touching, shift)


def check_joint_limits(hand, q: np.ndarray, what: str) -> None:
    """ValueError naming every independent joint of `q` (joint_names order) outside its URDF limits, and
    every mimic joint that its master's value drives outside the mimic joint's own limits."""
    bad = []
    for name, value, (lo, hi) in zip(hand.joint_names, q, hand.joint_limits):
        if not lo - 1e-9 <= value <= hi + 1e-9:
            bad.append(f"{name} = {value:g} is outside its limits [{lo:g}, {hi:g}]")
    if not bad:
        values = hand.all_joint_values(q)
        for j in hand.joints:
            if j["mimic"] is not None:
                lo, hi = j["limits"]
                v = values[j["name"]]
                if not lo - 1e-9 <= v <= hi + 1e-9:
                    bad.append(
                        f"mimic joint {j['name']} (of {j['mimic']}) = {v:g} is outside its limits [{lo:g}, {hi:g}]"
                    )
    if bad:
        raise ValueError(f"{what}: " + "; ".join(bad))


def _palm_links(hand) -> set:
    """The links rigidly attached to the wrist (through fixed joints only): the palm, not the fingers."""
    palm = {hand.root_link}
    for j in hand.joints:  # parents before children
        if j["type"] == "fixed" and j["parent"] in palm:
            palm.add(j["child"])
    return palm


def _angle_deg(a, b) -> float:
    return float(np.degrees(np.arccos(np.clip(np.dot(a, b) / (np.linalg.norm(a) * np.linalg.norm(b)), -1.0, 1.0))))


def aim_hint(hand, wrist: np.ndarray, target: np.ndarray) -> str:
    """What a wrist pose does with the hand's approach axis (Hand.approach_axis): where it points in the world
    and how far off the target it is; when the pose's quaternion read w-first (as [qw, qx, qy, qz] would be
    given) points the approach much nearer the target, the quaternion order is named as the likely mistake.
    Empty when the approach points within AIM_OFF_DEG of the target."""
    axis = np.asarray(hand.approach_axis, dtype=float)
    to_target = np.asarray(target, dtype=float) - wrist[:3]
    if not np.linalg.norm(to_target) > 1e-9:
        return ""
    q = wrist[3:] / np.linalg.norm(wrist[3:])
    points = rotation_matrices(q[None])[0] @ axis
    off = _angle_deg(points, to_target)
    if off <= AIM_OFF_DEG:
        return ""
    hint = (
        f"the hand's approach axis {_vec(axis)} (wrist frame) points {_vec(points)} in the world, {off:.0f} deg "
        f"off the direction from the wrist to the object {_vec(to_target / np.linalg.norm(to_target))}"
    )
    w_first = np.r_[q[1:], q[0]]  # the same four numbers meant as w, x, y, z
    off_w = _angle_deg(rotation_matrices(w_first[None])[0] @ axis, to_target)
    if off_w <= AIM_OFF_DEG:
        given = ",".join(f"{v:g}" for v in wrist[3:])
        meant = ",".join(f"{v:g}" for v in w_first)
        return (
            f"{hint}; the wrist quaternion is read x,y,z,w: if {given} was meant w-first, write it as {meant} "
            f"(the approach then points {off_w:.0f} deg off the object)"
        )
    return f"{hint}; turn the wrist so that the approach axis points at the object"


def _vec(v) -> str:
    return "[" + ", ".join(f"{x + 0.0:.2f}" for x in v) + "]"


def _check_pregrasp_collision(p, scene: TableWorld, body: int, links: dict, palm: set, aim: str = "") -> None:
    """ValueError naming the hand links that penetrate the object or the table at the pre-grasp (with `aim`,
    aim_hint's words on where the approach points, when the palm is inside)."""
    c = scene.client
    p.performCollisionDetection(physicsClientId=c)
    for other, what in ((scene.body, "the object"), (scene.plane, "the table")):
        depth: dict = {}
        for pt in p.getClosestPoints(body, other, 0.0, physicsClientId=c):
            if pt[8] < -PENETRATION_TOLERANCE:
                name = links[pt[3]]
                depth[name] = max(depth.get(name, 0.0), -pt[8])
        if not depth:
            continue
        named = ", ".join(f"{n} ({1000 * d:.1f} mm deep)" for n, d in sorted(depth.items()))
        inside = sorted(set(depth) & palm)
        hint = (
            f"the wrist/palm ({', '.join(inside)}) is inside {what}: move the wrist back along the approach"
            + (f"; {aim}" if aim else "")
            if inside
            else "the fingers are inside it: open the pre-grasp further or move the wrist"
        )
        raise ValueError(f"the pre-grasp is in collision with {what}: {named}; {hint}")


def _check_outcome(hand, q_pre, q_close, q_grasp, touching: list, shift: float, aim: str = "") -> None:
    """ValueError for a recording that is not a grasp: a joint pushed open, the object pushed away, or a
    hand that closed without touching the object (with `aim`, aim_hint's words on where the approach points)."""
    direction = np.sign(q_close - q_pre)
    opened = (q_grasp - q_pre) * direction < -OPENED_TOLERANCE
    if np.any(opened):
        bad = ", ".join(f"{n} {a:g} -> {b:g}" for n, a, b, o in zip(hand.joint_names, q_pre, q_grasp, opened) if o)
        raise ValueError(
            f"the grasp is wider than the pre-grasp ({bad}, away from the closing target): "
            "something pushed the fingers open; check the pre-grasp for collisions"
        )
    if shift > OBJECT_PUSHED:
        where = f" and ended touching {', '.join(touching)}" if touching else " and lost it"
        raise ValueError(
            f"the hand pushed the object {1000 * shift:.0f} mm away while closing{where}: "
            "the wrist or palm is probably too deep; move the wrist back along the approach"
        )
    if not touching:
        raise ValueError("the hand closed without touching the object: " + (aim or "move the wrist or close further"))


def _place_hand(p, c: int, hand_path, wrist: np.ndarray):
    """(body, joint name -> index) of the hand loaded with its wrist at `wrist`."""
    body = p.loadURDF(str(Path(hand_path).resolve()), useFixedBase=True, physicsClientId=c)
    # pybullet places a base by its inertial frame: T_world_com = T_world_wrist o T_link_com.
    dyn = p.getDynamicsInfo(body, -1, physicsClientId=c)
    T_world_com = _core.pose_multiply(wrist[None], np.r_[dyn[3], dyn[4]][None])[0]
    p.resetBasePositionAndOrientation(body, T_world_com[:3], T_world_com[3:], physicsClientId=c)
    joints = {
        p.getJointInfo(body, j, physicsClientId=c)[1].decode(): j
        for j in range(p.getNumJoints(body, physicsClientId=c))
    }
    return body, joints


def _link_names(p, c: int, body: int, root: str) -> dict:
    """pybullet link index -> URDF link name (-1: the root)."""
    names = {-1: root}
    for j in range(p.getNumJoints(body, physicsClientId=c)):
        names[j] = p.getJointInfo(body, j, physicsClientId=c)[12].decode()
    return names


def _link_poses(p, c: int, body: int, links: dict, wrist: np.ndarray) -> dict:
    """URDF link frames in the world, as pybullet has them (the root is the wrist)."""
    poses = {links[-1]: wrist.copy()}
    for j, name in links.items():
        if j >= 0:
            s = p.getLinkState(body, j, computeForwardKinematics=True, physicsClientId=c)
            poses[name] = np.r_[s[4], s[5]]
    return poses


def _close(p, c: int, hand, body: int, joints: dict, q_close, force: float, max_steps: int) -> dict:
    """Position motors drive the independent joints to q_close (at most `force`); each mimic joint's
    motor follows its master's current value every step (a stiff linkage). Steps until the joints have rested for 20
    steps and returns where the independent joints are (name -> value). Joints still moving after max_steps but
    within REST_BAND over the last REST_WINDOW steps rest there too (their mean over the window is returned);
    ValueError if they do neither."""
    for name, value in zip(hand.joint_names, q_close):
        p.setJointMotorControl2(
            body,
            joints[name],
            p.POSITION_CONTROL,
            targetPosition=value,
            force=force,
            maxVelocity=0.2,
            physicsClientId=c,
        )
    mimics = [(joints[m], joints[master], k, off) for m, (master, k, off) in hand.mimic_joints.items()]
    names = list(hand.joint_names) + list(hand.mimic_joints)  # the independent joints first
    moving = [joints[n] for n in names]
    still = 0
    window = np.zeros((min(REST_WINDOW, max_steps), len(moving)))
    for step in range(max_steps):
        for j, master, k, off in mimics:
            q = p.getJointState(body, master, physicsClientId=c)[0]
            p.setJointMotorControl2(
                body,
                j,
                p.POSITION_CONTROL,
                targetPosition=k * q + off,
                force=MIMIC_STIFFNESS * force,
                positionGain=1.0,
                physicsClientId=c,
            )
        p.stepSimulation(physicsClientId=c)
        states = [p.getJointState(body, j, physicsClientId=c)[:2] for j in moving]
        window[step % len(window)] = [s[0] for s in states]
        # Two position motors pushing against each other through the object never quite settle (the
        # object creeps), so a few mm/s counts as stopped.
        still = still + 1 if max(abs(s[1]) for s in states) < 5e-3 else 0
        if still >= 20:
            return {n: p.getJointState(body, joints[n], physicsClientId=c)[0] for n in hand.joint_names}
    band = np.ptp(window, axis=0)
    if max_steps >= REST_WINDOW and np.all(band < REST_BAND):
        mean = window.mean(axis=0)
        return {n: float(mean[i]) for i, n in enumerate(hand.joint_names)}
    moved = ", ".join(f"{n} {1000 * b:.1f}" for n, b in zip(names, band) if b >= REST_BAND)
    moved = f" (over the last {len(window)} steps: {moved} mm or mrad)" if moved else ""
    raise ValueError(
        f"the hand's joints did not come to rest within {max_steps} steps{moved}; "
        "raise max_steps (--max-steps) or check the object and the closing target"
    )
