"""describe_hand, plot_hand, hand_urdf_from_robot and `graspmix_cli hand`, against independent answers: the
URDFs' own numbers (the WSG 50's 0-110 mm), and pybullet's forward kinematics and closest-point distances
between the two fingertips (mimic joints driven explicitly)."""

import contextlib
import json

import matplotlib.image
import numpy as np
import pybullet as p
import pybullet_data
import pytest
from graspmix import Hand
from graspmix.cli import main
from graspmix.io import data_path
from graspmix.model.grasp_frames import opening_widths
from graspmix.model.hands import describe_hand, hand_urdf_from_robot
from graspmix.viz.hand import plot_hand
from scipy.spatial.transform import Rotation

PR2 = f"{pybullet_data.getDataPath()}/pr2_gripper.urdf"
XARM_ROBOT = f"{pybullet_data.getDataPath()}/xarm/xarm6_with_gripper.urdf"
PANDA_ROBOT = f"{pybullet_data.getDataPath()}/franka_panda/panda.urdf"
WSG50 = str(data_path("hands", "wsg50.urdf"))
PYBULLET_MARGIN = 2.5e-3  # m: pybullet's collision margins on convex shapes, and Euclidean vs across distance


@pytest.fixture(scope="module")
def xarm(tmp_path_factory):
    return str(hand_urdf_from_robot(XARM_ROBOT, "xarm_gripper_base_link", tmp_path_factory.mktemp("x") / "xg.urdf"))


@contextlib.contextmanager
def pybullet_posed(urdf, hand, q):
    """(client, body, link name -> index) of `urdf` in pybullet with the hand's joints (mimics too) at q."""
    c = p.connect(p.DIRECT)
    try:
        body = p.loadURDF(str(urdf), useFixedBase=True, physicsClientId=c)
        info = [p.getJointInfo(body, i, physicsClientId=c) for i in range(p.getNumJoints(body, physicsClientId=c))]
        joint = {x[1].decode(): x[0] for x in info}
        for name, value in hand.all_joint_values(q).items():
            p.resetJointState(body, joint[name], value, physicsClientId=c)
        yield c, body, {x[12].decode(): x[0] for x in info}
    finally:
        p.disconnect(c)


def pybullet_gap(urdf, link_a, link_b, q):
    """pybullet's closest distance between two links of the hand at configuration q."""
    with pybullet_posed(urdf, Hand.from_urdf(urdf), q) as (c, body, link):
        rows = p.getClosestPoints(body, body, 1.0, link[link_a], link[link_b], physicsClientId=c)
        return min(r[8] for r in rows)


def test_wsg50_is_its_urdf():
    d = describe_hand(WSG50)
    assert d["wrist"] == "palm" and d["independent_joints"] == ["finger_left_joint"]
    assert d["mimic"] == {"finger_right_joint": {"joint": "finger_left_joint", "multiplier": 1.0, "offset": 0.0}}
    assert d["closing"] == {"finger_left_joint": -1}  # the URDF: 0 closed, 0.055 open
    assert d["approach_axis"]["agrees"] and d["approach_axis"]["angle_deg"] < 1e-6
    assert d["fingers"] == [["finger_left"], ["finger_right"]]
    assert d["opening_width"]["lower"] == pytest.approx(0.0, abs=1e-9)
    assert d["opening_width"]["upper"] == pytest.approx(0.11, abs=1e-9)  # twice the 0.055 limit
    right = next(j for j in d["joints"] if j["name"] == "finger_right_joint")
    assert not right["independent"] and right["mimic"] == "finger_left_joint" and right["closing"] == -1


@pytest.mark.parametrize(
    "urdf, tips",
    [
        (WSG50, ("finger_left", "finger_right")),
        (PR2, ("left_tip", "right_tip")),
        ("xarm", ("left_finger", "right_finger")),
    ],
)
def test_opening_width_matches_pybullet(urdf, tips, xarm):
    urdf = xarm if urdf == "xarm" else urdf
    d = describe_hand(urdf)
    lim = np.array(Hand.from_urdf(urdf).joint_limits)
    for k, limit in enumerate(("lower", "upper")):
        assert d["opening_width"][limit] == pytest.approx(pybullet_gap(urdf, *tips, lim[:, k]), abs=PYBULLET_MARGIN)


def test_pr2_opening_widths_match_pybullet():
    """The gap demo and synthesize print (grasp_frames.opening_widths), for revolute fingers, against pybullet's
    closest distance between the fingertip links at the same joints (apart: at 0 rad the tips overlap)."""
    q = [[0.1, 0.1], [0.3, 0.3], [0.5, 0.3], [0.548, 0.548]]
    for w, qk in zip(opening_widths(Hand.from_urdf(PR2), q), q):
        assert w == pytest.approx(pybullet_gap(PR2, "left_tip", "right_tip", qk), abs=PYBULLET_MARGIN)


def test_pr2_fingers_lie_along_x_its_approach_axis():
    d = describe_hand(PR2)
    assert d["independent_joints"] == ["left_gripper_joint", "right_gripper_joint"] and d["mimic"] == {}
    assert np.dot(d["approach_axis"]["fingers_direction"], [1, 0, 0]) > 0.99  # the pole and fingers run along +x
    assert d["approach_axis"]["axis"] == [1.0, 0.0, 0.0] and d["approach_axis"]["source"] == "inferred"
    assert d["approach_axis"]["agrees"] and d["fingertips"] == ["left_tip", "right_tip"]
    assert d["closing"] == {"left_gripper_joint": -1, "right_gripper_joint": -1}
    assert d["opening_width"]["upper"] > d["opening_width"]["lower"]


def test_xarm_mimic_linkage(xarm):
    d = describe_hand(xarm)
    assert d["independent_joints"] == ["drive_joint"] and len(d["mimic"]) == 5
    assert d["closing"] == {"drive_joint": 1}  # 0 open, 0.85 closed
    assert d["opening_width"]["lower"] > d["opening_width"]["upper"]
    assert all(j["closing"] == 1 for j in d["joints"] if j["mimic"])


def test_cut_hand_keeps_the_robot_fk(xarm):
    """The cut hand's links, posed from its wrist, are the robot's links posed from link6 (pybullet's fk of
    the whole robot, the hand frame removed)."""
    hand = Hand.from_urdf(xarm)
    q = np.array([0.4])
    with pybullet_posed(XARM_ROBOT, hand, q) as (c, body, link):
        world = {
            n: p.getLinkState(body, link[n], computeForwardKinematics=True, physicsClientId=c) for n in hand.link_names
        }
    wrist = world[hand.link_names[0]]
    inv = p.invertTransform(wrist[4], wrist[5])
    ours = hand.fk(np.array([0, 0, 0, 0, 0, 0, 1.0]), q)
    for name, pose in zip(hand.link_names, ours):
        pos, _ = p.multiplyTransforms(inv[0], inv[1], world[name][4], world[name][5])
        np.testing.assert_allclose(pose[:3], pos, atol=1e-6)


def test_plot_hand_draws_both_limits(tmp_path):
    out = tmp_path / "h.png"
    info = plot_hand(WSG50, out)
    img = matplotlib.image.imread(out)
    assert info["name"] == "wsg50" and img.shape[1] > 1.5 * img.shape[0]  # two panels side by side
    assert img[..., :3].std() > 0.05  # not blank


def test_cli_hand(tmp_path, capsys, xarm):
    assert main(["hand", "--urdf", xarm, "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["independent_joints"] == ["drive_joint"]
    assert main(["hand", "--urdf", PR2, "--png", str(tmp_path / "p.png")]) == 0
    text = capsys.readouterr().out
    assert "left_gripper_joint, right_gripper_joint" in text and "approach axis: [1, 0, 0] of the wrist frame" in text
    assert (tmp_path / "p.png").stat().st_size > 0


def test_a_cut_hand_loads_after_it_is_moved(tmp_path, capsys):
    """`hand --wrist-link --out` writes mesh paths that do not depend on where the file is: moved two folders
    deeper (where a path relative to the first folder would miss), graspmix reads the robot's own meshes for
    each link, and pybullet's boxes around the links are those of graspmix's collision vertices, posed alike."""
    written = tmp_path / "a" / "hand.urdf"
    written.parent.mkdir()
    assert main(["hand", "--urdf", PANDA_ROBOT, "--wrist-link", "panda_hand", "--out", str(written)]) == 0
    moved = tmp_path / "b" / "c" / "d" / "hand.urdf"
    moved.parent.mkdir(parents=True)
    written.rename(moved)
    capsys.readouterr()
    assert main(["hand", "--urdf", str(moved), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["fingertips"] == ["panda_leftfinger", "panda_rightfinger"]
    hand, robot = Hand.from_urdf(moved), Hand.from_urdf(PANDA_ROBOT)
    for name in hand.link_names:
        np.testing.assert_array_equal(hand.collision_mesh(name)[0], robot.collision_mesh(name)[0])
    q = np.array([0.03])
    poses = hand.fk(np.array([0, 0, 0, 0, 0, 0, 1.0]), q)
    with pybullet_posed(moved, hand, q) as (c, body, link):
        link[hand.root_link] = -1
        for i, name in enumerate(hand.link_names):
            V = np.asarray(hand.collision_mesh(name)[0])
            if len(V):
                W = Rotation.from_quat(poses[i][3:]).apply(V) + poses[i][:3]
                lo, hi = p.getAABB(body, link[name], physicsClientId=c)
                np.testing.assert_allclose(lo, W.min(axis=0), atol=2 * PYBULLET_MARGIN)
                np.testing.assert_allclose(hi, W.max(axis=0), atol=2 * PYBULLET_MARGIN)


@pytest.mark.parametrize(
    "args",
    [
        ["--urdf", "{bad}"],
        ["--urdf", "{missing}"],
        ["--urdf", XARM_ROBOT, "--wrist-link", "nope", "--out", "{out}"],
        ["--urdf", XARM_ROBOT, "--wrist-link", "link6"],
        ["--urdf", "{no_mesh}", "--wrist-link", "a", "--out", "{out}"],
    ],
)
def test_cli_hand_bad_input_is_one_line(tmp_path, capsys, args):
    bad = tmp_path / "bad.urdf"
    bad.write_text("<robot name='x'><link name='a'>")
    no_mesh = tmp_path / "no_mesh.urdf"
    no_mesh.write_text(
        "<robot name='x'><link name='a'><collision><geometry><mesh filename='gone.stl'/></geometry>"
        "</collision></link></robot>"
    )
    names = {"bad": bad, "missing": tmp_path / "none.urdf", "out": tmp_path / "o.urdf", "no_mesh": no_mesh}
    assert main(["hand"] + [a.format(**names) for a in args]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("graspmix_cli hand: ")


def test_a_rotated_root_turns_the_pr2_fingers_onto_the_convention(tmp_path):
    """The recipe of docs/hands-and-frames.md: a new root link and a fixed joint rotating the old root by -90 deg
    about y turn +x into +z; the opening (a distance between fingertips) does not change."""
    text = open(PR2).read().replace('filename="', f'filename="{pybullet_data.getDataPath()}/')
    root = (
        '<robot name="pr2z"><link name="wrist"/><joint name="to_pole" type="fixed"><parent link="wrist"/>'
        '<child link="gripper_pole"/><origin rpy="0 -1.5707963267948966 0" xyz="0 0 0"/></joint>'
    )
    (tmp_path / "pr2z.urdf").write_text(text.replace('<robot name="physics">', root))
    d, before = describe_hand(tmp_path / "pr2z.urdf"), describe_hand(PR2)
    assert d["wrist"] == "wrist" and d["approach_axis"]["agrees"]
    assert np.dot(d["approach_axis"]["fingers_direction"], [0, 0, 1]) > 0.99
    for limit in ("lower", "upper"):
        assert d["opening_width"][limit] == pytest.approx(before["opening_width"][limit], abs=1e-9)


def test_a_joint_that_turns_a_fingertip_about_the_approach_neither_opens_nor_closes(tmp_path):
    urdf = tmp_path / "spin.urdf"
    urdf.write_text(
        '<robot name="spin"><link name="a"><collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
        '</link><link name="b"><collision><origin xyz="0 0 0.1"/><geometry><sphere radius="0.01"/></geometry>'
        '</collision></link><joint name="c" type="continuous"><parent link="a"/><child link="b"/>'
        '<axis xyz="0 0 1"/></joint></robot>'
    )
    d = describe_hand(urdf)
    assert d["closing"] == {"c": 0} and d["opening_width"] is None
    c = d["joints"][0]
    assert c["lower"] is None and c["upper"] is None and c["independent"]


def test_xarm_grasps_export_the_opening_between_the_pads(xarm):
    """A grasps file of the linkage gripper has a closing direction and an opening: the gap between its pads (the
    fingertips), as pybullet measures it between the same links, at several drive values."""
    from graspmix.model import Grasp, GraspSet

    q = [0.1, 0.4, 0.7]
    rows = [
        Grasp([0, 0, 0.3, 1.0, 0, 0, 0], {"drive_joint": 0.0}, {"drive_joint": v}, rank=i + 1) for i, v in enumerate(q)
    ]
    grasps = GraspSet(rows, xarm, "gmm", "", {})
    assert grasps.fingertips == ["left_finger", "right_finger"]
    for g, v in zip(grasps, q):
        assert g.opening_width == pytest.approx(
            pybullet_gap(xarm, "left_finger", "right_finger", [v]), abs=PYBULLET_MARGIN
        )
        assert abs(np.dot(g.closing, g.approach)) < 0.05  # across the approach
