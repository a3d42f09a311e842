"""Grasp execution in Bullet (C++): hand-made grasps with known outcomes, agreement with the same
protocol run in pybullet, determinism, errors and the CLI."""

import json
import math
from dataclasses import replace

import graspmix
import numpy as np
import pytest
from graspmix import cli, sim
from graspmix.model import Grasp

# Objects of several kinds: a 5 cm cube, small and large random_urdfs (convex decompositions of six
# parts each), tall ones, and the mug.
AGREEMENT_OBJECTS = [
    "cube_small.urdf",
    "random_urdfs/033/033.urdf",
    "random_urdfs/001/001.urdf",
    "random_urdfs/140/140.urdf",
    "random_urdfs/485/485.urdf",
    "random_urdfs/122/122.urdf",
    "objects/mug.urdf",
]


PR2 = graspmix.io.pybullet_data_path() / "pr2_gripper.urdf"


def object_box(obj):
    """World bounding box (lo, hi) of the object's collision geometry at its rest pose."""
    o = sim.load_object(obj)
    pose = sim.rest_pose(obj)
    v, _ = o.model.collision_mesh(o.model.link_names[0])
    from scipy.spatial.transform import Rotation

    w = Rotation.from_quat(pose[3:]).apply(v) + pose[:3]
    return w.min(0), w.max(0)


def agreement_grasps():
    """Good, marginal and deliberately bad top grasps (seeded), 9 per object."""
    rng = np.random.default_rng(6)
    out = []
    for obj in AGREEMENT_OBJECTS:
        lo, hi = object_box(obj)
        c = (lo[:2] + hi[:2]) / 2
        tip = max(0.01, hi[2] - 0.06)  # the palm clears the top of tall objects
        for _ in range(3):
            out.append(
                (
                    obj,
                    "good",
                    sim.top_grasp(c + rng.normal(0, 0.004, 2), 0.055, 0.0, yaw=rng.uniform(0, math.pi), tip_height=tip),
                )
            )
        out.append(
            (
                obj,
                "marginal",
                sim.top_grasp(c + rng.uniform(-0.03, 0.03, 2), 0.055, 0.0, yaw=rng.uniform(0, math.pi), tip_height=tip),
            )
        )
        out.append(
            (obj, "fingertips", sim.top_grasp(c, 0.055, 0.0, yaw=rng.uniform(0, math.pi), tip_height=hi[2] - 0.01))
        )
        out.append((obj, "too wide", sim.top_grasp(c, 0.055, 0.05, yaw=rng.uniform(0, math.pi), tip_height=tip)))
        out.append(
            (obj, "off the object", sim.top_grasp(c + [0.0, (hi[1] - lo[1]) / 2 + 0.05], 0.04, 0.0, tip_height=0.01))
        )
        out.append((obj, "in collision", sim.top_grasp(c, 0.004, 0.0, tip_height=tip)))
        out.append((obj, "weak", sim.top_grasp(c, 0.055, 0.0, yaw=rng.uniform(0, math.pi), tip_height=tip)))
    # Another hand: the PR2 gripper (two revolute fingers with STL meshes and fixed tips), pole pointing down.
    from scipy.spatial.transform import Rotation

    for obj, z, yaw, closed in [
        ("cube_small.urdf", 0.335, 0.0, 0.0),
        ("cube_small.urdf", 0.335, 1.5, 0.3),
        ("cube_small.urdf", 0.345, 0.0, 0.3),
        ("cube_small.urdf", 0.345, 1.5, 0.15),
        ("random_urdfs/033/033.urdf", 0.335, 0.5, 0.15),
        ("random_urdfs/033/033.urdf", 0.335, 0.5, 0.3),
        ("random_urdfs/033/033.urdf", 0.335, 0.0, 0.3),
        ("random_urdfs/033/033.urdf", 0.345, 1.5, 0.0),
    ]:
        q = (Rotation.from_euler("z", yaw) * Rotation.from_euler("y", math.pi / 2)).as_quat()
        out.append(
            (
                obj,
                "pr2 gripper",
                Grasp(
                    T_world_wrist=[0.0, 0.0, z, *q],
                    pregrasp_joints={"left_gripper_joint": 0.5, "right_gripper_joint": 0.5},
                    grasp_joints={"left_gripper_joint": closed, "right_gripper_joint": closed},
                ),
            )
        )
    return out


def test_agreement_with_pybullet():
    grasps = agreement_grasps()
    assert len(grasps) >= 50
    same, same_reason, rows = 0, 0, []
    kinds = {}
    for obj, kind, g in grasps:
        settings = sim.make_settings(grip_force=0.5) if kind == "weak" else None
        hand = PR2 if kind == "pr2 gripper" else None
        ours = sim.execute(obj, g, settings=settings, hand=hand)
        ref = sim.execute_pybullet(obj, g, settings=settings, hand=hand)
        agree = ours.success == ref["success"]
        same += agree
        same_reason += ours.reason == ref["reason"]
        kinds.setdefault(ours.reason, 0)
        kinds[ours.reason] += 1
        rows.append(
            f"{obj:28s} {kind:15s} bullet-cpp {ours.reason:18s} {ours.lift_height:6.3f} m | "
            f"pybullet {ref['reason']:18s} {ref['lift_height']:6.3f} m{'' if agree else '  DISAGREE'}"
        )
    print("\n".join(rows))
    print(
        f"agreement with pybullet: {same}/{len(grasps)} = {same / len(grasps):.1%} on success, "
        f"{same_reason / len(grasps):.1%} on the reason; outcomes {kinds}"
    )
    # The set must hold both outcomes in numbers, or agreement would mean little.
    assert kinds.get("success", 0) >= 10 and len(grasps) - kinds.get("success", 0) >= 10
    assert same / len(grasps) >= 0.9


def test_cube_across_two_faces_succeeds_beside_fails_inside_is_start_in_collision():
    lo, hi = object_box("cube_small.urdf")
    c = (lo[:2] + hi[:2]) / 2
    half = (hi[0] - lo[0]) / 2
    r = sim.execute("cube_small.urdf", sim.top_grasp(c, half + 0.01, half - 0.01))
    assert r.success and r.reason == "success"
    assert r.lift_height == pytest.approx(0.2, abs=0.02)
    assert r.contact_count >= 2
    assert r.wall_time > 0 and r.simulated_time == pytest.approx(r.steps / 240.0)
    beside = sim.execute("cube_small.urdf", sim.top_grasp(c + [half + 0.08, 0.0], half + 0.01, half - 0.01))
    assert not beside.success and beside.reason == "no contact" and beside.contact_count == 0
    inside = sim.execute("cube_small.urdf", sim.top_grasp(c, half - 0.015, 0.0))
    assert not inside.success and inside.reason == "start in collision"
    assert inside.start_penetration > 0.005 and inside.steps == 0


def test_settings_change_the_outcome_as_physics_says():
    lo, hi = object_box("cube_small.urdf")
    c = (lo[:2] + hi[:2]) / 2
    g = sim.top_grasp(c, 0.04, 0.0)
    assert sim.execute("cube_small.urdf", g).success
    # Without friction nothing is held; a lower lift still counts as lifted.
    assert sim.execute("cube_small.urdf", g, hand_friction=0.0).reason == "not held"
    low = sim.execute("cube_small.urdf", g, lift_height=0.05)
    assert low.success and low.lift_height == pytest.approx(0.05, abs=0.01)
    with pytest.raises(ValueError, match="unknown simulation setting"):
        sim.execute("cube_small.urdf", g, grip=3)


def test_deterministic():
    g = sim.top_grasp([0.003, -0.002], 0.055, 0.0, yaw=0.4, tip_height=0.012)
    a = sim.execute("random_urdfs/122/122.urdf", g)
    b = sim.execute("random_urdfs/122/122.urdf", g)
    assert (a.reason, a.steps, a.contact_count, a.lift_height) == (b.reason, b.steps, b.contact_count, b.lift_height)
    np.testing.assert_array_equal(a.object_pose, b.object_pose)


def test_errors(tmp_path):
    g = sim.top_grasp([0, 0], 0.04, 0.0)
    with pytest.raises(ValueError, match="no_such_object.urdf"):
        sim.execute("no_such_object.urdf", g)
    # A grasp for another hand (the panda's finger joints).
    other = replace(g, pregrasp_joints={"panda_finger_joint1": 0.04}, grasp_joints={"panda_finger_joint1": 0.0})
    with pytest.raises(ValueError, match="does not fit hand 'wsg50'"):
        sim.execute("cube_small.urdf", other)
    with pytest.raises(ValueError, match="T_world_wrist"):
        sim.execute("cube_small.urdf", replace(g, T_world_wrist=[0, 0, 1]))
    with pytest.raises(ValueError, match="grasp: expected a Grasp .*got dict"):
        sim.execute("cube_small.urdf", g.to_dict())
    # grasps.json made for another hand, with a wrong format, without grasps.
    path = tmp_path / "grasps.json"
    panda = graspmix.io.pybullet_data_path() / "franka_panda" / "panda.urdf"
    path.write_text(
        json.dumps({"format": "graspmix.grasps/1", "hand": str(panda), "grasps": [dict(g.to_dict(), rank=1)]})
    )
    with pytest.raises(ValueError, match="grasps are for hand"):
        sim.execute_file("cube_small.urdf", path, hand=graspmix.io.default_hand_path())
    # Without a hand given, the file's hand is used, and the WSG 50's joints do not fit it.
    with pytest.raises(ValueError, match="does not fit hand 'panda'"):
        sim.execute_file("cube_small.urdf", path)
    path.write_text(json.dumps({"format": "something/2", "grasps": []}))
    with pytest.raises(ValueError, match="expected format"):
        graspmix.model.load_grasps(path)
    with pytest.raises(ValueError, match="no such grasps file"):
        graspmix.model.load_grasps(tmp_path / "missing.json")


def write_grasps(path, grasps, hand="wsg50.urdf"):
    doc = {
        "format": "graspmix.grasps/1",
        "hand": hand,
        "method": "manual",
        "cloud": "",
        "grasps": [dict(g.to_dict(), rank=i + 1) for i, g in enumerate(grasps)],
    }
    path.write_text(json.dumps(doc))


def test_cli_execute(tmp_path, capsys):
    lo, hi = object_box("cube_small.urdf")
    c = (lo[:2] + hi[:2]) / 2
    path = tmp_path / "grasps.json"
    write_grasps(path, [sim.top_grasp(c, 0.04, 0.0), sim.top_grasp(c + [0.2, 0], 0.04, 0.0)])
    assert cli.main(["execute", "--object", "cube_small.urdf", "--grasps", str(path)]) == 0
    out = capsys.readouterr().out
    assert "success" in out
    assert cli.main(["execute", "--object", "cube_small.urdf", "--grasps", str(path), "--rank", "2", "--json"]) == 0
    res = json.loads(capsys.readouterr().out)
    assert res["reason"] == "no contact" and res["success"] is False
    assert cli.main(["execute", "--object", "nothing.urdf", "--grasps", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "nothing.urdf" in err
    assert cli.main(["execute", "--object", "cube_small.urdf", "--grasps", str(path), "--rank", "7"]) == 2
    assert "rank 7" in capsys.readouterr().err


def test_test_object_list():
    """data/objects/test60.txt: 60 distinct objects that load, none of them a box like the demonstration."""
    from pathlib import Path

    listed = graspmix.io.test_objects()
    assert len(listed) == 60 and len(set(listed)) == 60
    assert not any(Path(p).name.startswith(("cube", "block")) for p in listed)
    for p in listed[::10]:
        assert sim.load_object(p).mass > 0


def test_start_penetrations_name_the_links_and_depths():
    """cube_small (5 cm): a wide top grasp starts clear; fingers opened less than the cube is wide start inside
    it; fingertips 1 cm below the plane start 1 cm deep in it (pybullet's depth, to its margin)."""
    from graspmix.sim.pybullet_reference import start_penetrations

    assert start_penetrations("cube_small.urdf", sim.top_grasp((0, 0), 0.05, 0.0)) == {}
    inside = start_penetrations("cube_small.urdf", sim.top_grasp((0, 0), 0.01, 0.0))
    assert {k for k in inside if k[0] == "object"} >= {("object", "finger_left"), ("object", "finger_right")}
    below = start_penetrations("cube_small.urdf", sim.top_grasp((0, 0), 0.05, 0.0, tip_height=-0.01))
    assert set(below) == {("plane", "finger_left"), ("plane", "finger_right")}
    for depth in below.values():
        assert depth == pytest.approx(0.01, abs=0.002)


def _fingertip_speeds_in_pybullet(urdf, hand, q_all, qd_all):
    """Each fingertip point's speed (m/s), by pybullet's kinematics of the hand's URDF at joint values q_all
    and joint speeds qd_all (name -> value); the point is the centre of the box around the link's collision
    vertices, as graspmix defines it."""
    import pybullet as p

    cid = p.connect(p.DIRECT)
    try:
        kw = {"physicsClientId": cid}
        hid = p.loadURDF(str(urdf), useFixedBase=True, **kw)
        index = {p.getJointInfo(hid, j, **kw)[1].decode(): j for j in range(p.getNumJoints(hid, **kw))}
        links = {p.getJointInfo(hid, j, **kw)[12].decode(): j for j in range(p.getNumJoints(hid, **kw))}
        for name, q in q_all.items():
            p.resetJointState(hid, index[name], q, targetVelocity=qd_all[name], **kw)
        out = {}
        for tip in hand.fingertips:
            v, _ = hand.collision_mesh(tip)
            centre = (v.min(0) + v.max(0)) / 2
            st = p.getLinkState(hid, links[tip], computeLinkVelocity=1, computeForwardKinematics=1, **kw)
            from scipy.spatial.transform import Rotation

            point = np.asarray(st[4]) + Rotation.from_quat(st[5]).apply(centre)  # link frame -> world
            vel = np.asarray(st[6]) + np.cross(st[7], point - np.asarray(st[0]))  # COM velocity + w x r
            out[tip] = float(np.linalg.norm(vel))
        return out
    finally:
        p.disconnect(cid)


@pytest.mark.parametrize("close_speed", [0.2, 0.05])
def test_closing_speeds_move_every_fingertip_at_close_speed(close_speed):
    # A revolute finger turns at close_speed / its lever, a prismatic one slides at close_speed (m/s), as
    # pybullet's kinematics of the same URDFs measures; a long travel is still covered in close_time / 2.
    s = sim.make_settings(close_speed=close_speed)
    for urdf in (PR2, graspmix.io.default_hand_path()):
        hand = sim.load_hand(urdf)
        names = hand.joint_names
        pre = {"left_gripper_joint": 0.5, "right_gripper_joint": 0.5} if urdf == PR2 else {names[0]: 0.04}
        # A grasp a hair from the pre-grasp, so that the travel does not set the speed.
        fin = {n: v - 1e-4 for n, v in pre.items()}
        qp = np.array([pre[n] for n in names])
        speeds = graspmix._core.sim_closing_speeds(hand, qp, np.array([fin[n] for n in names]), s)
        joint_names = [j["name"] for j in hand.joints]
        q_all = hand.all_joint_values(qp)
        qd_all = {n: float(v) for n, v in zip(joint_names, speeds) if n in q_all}
        for n in q_all:  # each joint moves its way: closing, as a mimic's multiplier turns it
            qd_all[n] *= np.sign(hand.all_joint_values(np.array([fin[m] for m in names]))[n] - q_all[n]) or 1.0
        tips = _fingertip_speeds_in_pybullet(urdf, hand, q_all, qd_all)
        assert len(tips) == 2
        for tip, v in tips.items():
            assert v == pytest.approx(close_speed, rel=1e-4), (urdf.name, tip)
    # The PR2's left tip: a box centred at (0.105, -0.005, 0) in the finger's frame, whose z is the joint axis.
    hand = sim.load_hand(PR2)
    far = graspmix._core.sim_closing_speeds(hand, np.array([0.5, 0.5]), np.array([0.5, 0.5]), s)
    left = [j["name"] for j in hand.joints].index("left_gripper_joint")
    assert far[left] == pytest.approx(close_speed / math.hypot(0.105, 0.005), rel=1e-6)
    # Travel: 0.5 rad in close_time / 2 = 0.25 s needs 2 rad/s.
    travel = graspmix._core.sim_closing_speeds(hand, np.array([0.5, 0.5]), np.array([0.0, 0.0]), s)
    assert travel[left] == pytest.approx(max(2.0, close_speed / math.hypot(0.105, 0.005)))
