"""The bundled three-finger hand (data/hands/three_finger.urdf) as graspmix reads it, against independent answers:
the URDF's own numbers read here with ElementTree, and pybullet's forward kinematics of the same file (mimic
joints set explicitly, as pybullet ignores them)."""

import math
import xml.etree.ElementTree as ET

import numpy as np
import pybullet as p
import pytest
from graspmix import Hand, pose_inverse, pose_multiply
from graspmix.io import data_path
from graspmix.model.grasp_frames import FrameMaker
from graspmix.model.hands import describe_hand
from graspmix.sim.demonstration import record
from scipy.spatial.transform import Rotation

URDF = data_path("hands", "three_finger.urdf")
FINGERS = ("finger_1", "finger_2", "finger_3")
IDENTITY = np.array([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0])


def urdf_numbers():
    """(lower, upper) of finger_1_joint, and each finger's inner-face point at its far end, in its link frame:
    the collision box reaching farthest along the finger's z, at its inner face (x = box centre + half size)."""
    root = ET.parse(URDF).getroot()
    limit = root.find("joint[@name='finger_1_joint']/limit")
    tips = {}
    for link in root.findall("link"):
        if link.get("name") not in FINGERS:
            continue
        boxes = []
        for c in link.findall("collision"):
            xyz = np.array([float(v) for v in c.find("origin").get("xyz").split()])
            size = np.array([float(v) for v in c.find("geometry/box").get("size").split()])
            boxes.append((xyz[2] + size[2] / 2, xyz[0] + size[0] / 2, xyz[1]))
        z, x, y = max(boxes)
        tips[link.get("name")] = np.array([x, y, z])
    return (float(limit.get("lower")), float(limit.get("upper"))), tips


def pybullet_link_frames(q):
    """{finger: its URDF link frame in the palm's frame (7,)} from pybullet with all three joints at q."""
    c = p.connect(p.DIRECT)
    try:
        body = p.loadURDF(str(URDF), useFixedBase=True, physicsClientId=c)
        info = [p.getJointInfo(body, j, physicsClientId=c) for j in range(p.getNumJoints(body, physicsClientId=c))]
        for i in info:
            p.resetJointState(body, i[0], q, physicsClientId=c)
        pos, orn = p.getBasePositionAndOrientation(body, physicsClientId=c)  # the palm's inertial frame
        dyn = p.getDynamicsInfo(body, -1, physicsClientId=c)
        T_world_palm = pose_multiply(np.r_[pos, orn], pose_inverse(np.r_[dyn[3], dyn[4]]))
        out = {}
        for i in info:
            s = p.getLinkState(body, i[0], computeForwardKinematics=True, physicsClientId=c)
            out[i[12].decode()] = pose_multiply(pose_inverse(T_world_palm), np.r_[s[4], s[5]])
        return out
    finally:
        p.disconnect(c)


def test_describe_hand_reads_the_urdf():
    (lower, upper), _ = urdf_numbers()
    d = describe_hand(URDF)
    assert d["wrist"] == "palm" and d["independent_joints"] == ["finger_1_joint"]
    assert set(d["mimic"]) == {"finger_2_joint", "finger_3_joint"}
    assert d["closing"] == {"finger_1_joint": -1}  # the joint value is the inner faces' distance from the axis
    assert d["approach_axis"]["axis"] == [0.0, 0.0, 1.0] and d["approach_axis"]["source"] == "inferred"
    assert d["approach_axis"]["angle_deg"] < 1e-6
    assert d["fingertips"] == list(FINGERS)
    assert d["fingers"] is None and d["opening_width"] is None  # not a two-sided gripper
    # The circle the three inner faces leave free: twice the joint value at each limit.
    assert d["opening_diameter"] == {
        "lower": pytest.approx(2 * lower, abs=1e-9),
        "upper": pytest.approx(2 * upper, abs=1e-9),
    }


@pytest.mark.parametrize("limit", [0, 1])
def test_fingertips_at_the_limits_match_pybullet(limit):
    """At each limit: graspmix's fk of every finger equals pybullet's link frame; pybullet's fingertips (the inner
    face's far end) lie at the joint value from the wrist's z axis, 120 degrees apart, all at one height; the
    grasp's TCP (FrameMaker) is on the axis at that height."""
    limits, tips = urdf_numbers()
    q = limits[limit]
    hand = Hand.from_urdf(str(URDF))
    poses = dict(zip(hand.link_names, hand.fk(IDENTITY, np.array([q]))))
    bullet = pybullet_link_frames(q)
    points = []
    for name in FINGERS:
        a, b = poses[name], bullet[name]
        assert np.linalg.norm(a[:3] - b[:3]) < 1e-6, name
        assert (Rotation.from_quat(a[3:]).inv() * Rotation.from_quat(b[3:])).magnitude() < 1e-6, name
        points.append(Rotation.from_quat(b[3:]).apply(tips[name]) + b[:3])
    points = np.array(points)
    assert np.hypot(points[:, 0], points[:, 1]) == pytest.approx([q] * 3, abs=1e-6)
    assert np.ptp(points[:, 2]) < 1e-9 and points[0, 2] > 0.1
    angles = np.degrees(np.arctan2(points[:, 1], points[:, 0]))
    off = (angles - [0.0, 120.0, 240.0] + 180.0) % 360.0 - 180.0  # pybullet keeps poses in single precision
    assert np.abs(off).max() < 1e-4
    tcp = FrameMaker(hand).frames(IDENTITY[None, :], np.array([[q]]))[0]["T_world_tcp"]
    assert np.asarray(tcp[:3]) == pytest.approx([0.0, 0.0, points[0, 2]], abs=1e-6)


def test_the_recipe_demonstration_closes_all_three_fingers_on_the_box():
    """docs/hands-and-frames.md's demonstration: finger_1 stops on the box's +y face (y = 0.05, the wrist at
    y = 0.01), so at 0.040; finger_2 and finger_3 meet its x faces there (inner edges at 0.866 q - 0.005 = 0.0296)."""
    rec = record(
        data_path("objects", "box.urdf"),
        URDF,
        [0.0, 0.01, 0.258, math.sqrt(0.5), math.sqrt(0.5), 0.0, 0.0],
        {"finger_1_joint": 0.065},
        {"finger_1_joint": 0.008},
    )
    assert rec.touching_links == list(FINGERS)
    assert rec.demonstration.grasp_joints["finger_1_joint"] == pytest.approx(0.040, abs=1.5e-3)
    assert rec.object_shift < 2e-3
