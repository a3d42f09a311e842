"""Recording a grasp demonstration in simulation (pybullet, DIRECT mode).

The object rests on a plane; its cloud is acquired by the simulated depth cameras; the hand is placed at
the demonstrated wrist pose with its pre-grasp joints and closes with force-limited position motors
until its joints stop; the joints it stops at are the demonstrated grasp. The result is a
Demonstration (the file format of the design guide).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .. import _core
from ..io.checks import MAX_ITERATIONS, check_float, check_input_file, check_int, check_seed
from ..model import Demonstration
from .acquisition import AcquisitionSettings, Scene, acquire

DEMO_GRIP_FORCE = 20.0  # N (N m): the demonstrating hand's motor force limit (execution's SimSettings: 40)


def record_demonstration(
    object_path: str | Path,
    hand_path: str | Path,
    T_world_wrist,
    pregrasp: dict,
    close_to: dict,
    *,
    grip_force: float = DEMO_GRIP_FORCE,
    max_steps: int = 2000,
    settings: AcquisitionSettings | None = None,
    seed: int = 0,
) -> Demonstration:
    """Closes the hand from `pregrasp` towards `close_to` (name -> value, independent joints) around the
    object and returns the demonstration with the joints where the fingers stopped."""
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
    settings = settings or AcquisitionSettings()
    cloud = acquire(object_path, noise=False, seed=seed, settings=settings)
    with Scene(object_path, settings) as scene:
        c = scene.client
        p.setGravity(0, 0, -9.81, physicsClientId=c)
        body, joints = _place_hand(p, c, hand_path, wrist)
        start = hand.all_joint_values(q_pre)
        target = hand.all_joint_values(q_close)
        for name, value in start.items():
            p.resetJointState(body, joints[name], value, physicsClientId=c)
        if p.getContactPoints(body, scene.body, physicsClientId=c):
            raise ValueError("the hand's pre-grasp pose is in collision with the object")
        for name, value in target.items():
            p.setJointMotorControl2(
                body,
                joints[name],
                p.POSITION_CONTROL,
                targetPosition=value,
                force=grip_force,
                maxVelocity=0.2,
                physicsClientId=c,
            )
        _close_until_still(p, c, body, [joints[n] for n in target], max_steps)
        reached = {n: p.getJointState(body, joints[n], physicsClientId=c)[0] for n in hand.joint_names}
        touching = bool(p.getContactPoints(body, scene.body, physicsClientId=c))
    if not touching:
        raise ValueError("the hand closed without touching the object: move the wrist or close further")
    demo = Demonstration(
        hand_path=Path(hand_path).resolve(),
        cloud=cloud.points,
        T_world_wrist=wrist,
        pregrasp_joints={n: float(v) for n, v in zip(hand.joint_names, q_pre)},
        grasp_joints={n: float(v) for n, v in reached.items()},
    )
    return demo


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


def _close_until_still(p, c: int, body: int, moving: list, max_steps: int) -> None:
    """Steps until the moving joints have rested for 20 steps; ValueError if they never do."""
    still = 0
    for _ in range(max_steps):
        p.stepSimulation(physicsClientId=c)
        v = max(abs(p.getJointState(body, j, physicsClientId=c)[1]) for j in moving)
        # Two position motors pushing against each other through the object never quite settle (the
        # object creeps), so a few mm/s counts as stopped.
        still = still + 1 if v < 5e-3 else 0
        if still >= 20:
            return
    raise ValueError(
        f"the hand's joints did not come to rest within {max_steps} steps; "
        "raise max_steps or check the object and the closing target"
    )
