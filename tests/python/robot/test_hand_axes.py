"""A hand's grasp axes (Hand.approach_axis, Hand.fingertips), inferred when its URDF is read or given by its
<graspmix> element, against pybullet's view of the same URDFs (link boxes at mid-range joints) and the URDFs'
own numbers; and the experts that use them."""

import numpy as np
import pybullet as p
import pybullet_data
import pytest
from graspmix import Hand, _core, data_path
from graspmix.cli import main
from graspmix.model.hands import hand_urdf_from_robot, write_hand_axes

PR2 = f"{pybullet_data.getDataPath()}/pr2_gripper.urdf"
XARM_ROBOT = f"{pybullet_data.getDataPath()}/xarm/xarm6_with_gripper.urdf"
WSG50 = str(data_path("hands", "wsg50.urdf"))


@pytest.fixture(scope="module")
def xarm(tmp_path_factory):
    return str(hand_urdf_from_robot(XARM_ROBOT, "xarm_gripper_base_link", tmp_path_factory.mktemp("x") / "xg.urdf"))


def pybullet_boxes(urdf, hand):
    """link name -> (AABB min, AABB max) in pybullet, the wrist at the origin, joints at mid-range (mimics too)."""
    c = p.connect(p.DIRECT)
    try:
        body = p.loadURDF(str(urdf), useFixedBase=True, physicsClientId=c)
        dyn = p.getDynamicsInfo(body, -1, physicsClientId=c)  # the base is placed by its inertial frame
        inv = p.invertTransform(dyn[3], dyn[4])
        p.resetBasePositionAndOrientation(body, inv[0], inv[1], physicsClientId=c)
        info = [p.getJointInfo(body, i, physicsClientId=c) for i in range(p.getNumJoints(body, physicsClientId=c))]
        q = np.array(hand.joint_limits).mean(axis=1)
        for name, value in hand.all_joint_values(q).items():
            p.resetJointState(body, next(x[0] for x in info if x[1].decode() == name), value, physicsClientId=c)
        return {x[12].decode(): np.array(p.getAABB(body, x[0], physicsClientId=c)) for x in info}
    finally:
        p.disconnect(c)


def test_wsg50_approaches_along_z_exactly():
    hand = Hand.from_urdf(WSG50)
    assert tuple(hand.approach_axis) == (0.0, 0.0, 1.0)  # bit for bit: the WSG 50's results stay as they were
    assert hand.fingertips == ["finger_left", "finger_right"] and hand.grasp_axes_source == "inferred"


def test_pr2_as_shipped_approaches_along_x():
    """pybullet_data's PR2 gripper: pole and fingers along +x; the tips (fixed to the fingers) are the fingertips,
    and the mean of their boxes in pybullet lies within the snap angle of +x."""
    hand = Hand.from_urdf(PR2)
    assert tuple(hand.approach_axis) == (1.0, 0.0, 0.0)
    assert hand.fingertips == ["left_tip", "right_tip"]
    boxes = pybullet_boxes(PR2, hand)
    mean = np.mean([boxes[n].mean(axis=0) for n in hand.fingertips], axis=0)
    snap = _core.HandLoadSettings().approach_snap_deg
    assert np.degrees(np.arccos(mean[0] / np.linalg.norm(mean))) < snap


def test_xarm_fingertips_are_the_pads_not_the_inner_knuckles(xarm):
    """The linkage's chains end in the inner knuckles and the fingers (pads); on each side the pad reaches
    further along the approach (pybullet's boxes), so the pads are the fingertips."""
    hand = Hand.from_urdf(xarm)
    assert hand.fingertips == ["left_finger", "right_finger"] and tuple(hand.approach_axis) == (0.0, 0.0, 1.0)
    boxes = pybullet_boxes(xarm, hand)
    for side in ("left", "right"):
        assert boxes[f"{side}_finger"][1, 2] > boxes[f"{side}_inner_knuckle"][1, 2] + 1e-3
    # Contact quality closes and scores these two, and nothing else.
    cloud = np.random.default_rng(0).uniform(-0.05, 0.05, (200, 3))
    config = _core.ConfigModel([0.0], [0.5], hand.joint_limits)
    cq = _core.ContactQualityExpert(hand, cloud, np.tile([0, 0, 1.0], (200, 1)), config)
    assert [hand.link_names[i] for i in cq.finger_links] == hand.fingertips


def test_the_urdf_element_gives_the_axes_and_pybullet_still_loads_it(tmp_path):
    out = write_hand_axes(PR2, tmp_path / "pr2.urdf", approach_axis=(0, 2, 0), fingertips=["left_gripper"])
    hand = Hand.from_urdf(out)
    assert tuple(hand.approach_axis) == (0.0, 1.0, 0.0) and hand.fingertips == ["left_gripper"]
    assert hand.grasp_axes_source == "urdf"
    c = p.connect(p.DIRECT)
    try:
        assert p.getNumJoints(p.loadURDF(str(out), physicsClientId=c), physicsClientId=c) == hand.n_links - 1
    finally:
        p.disconnect(c)
    # One attribute alone: the other is inferred from it.
    only_axis = write_hand_axes(PR2, tmp_path / "a.urdf", approach_axis=(1, 0, 0))
    assert Hand.from_urdf(only_axis).fingertips == ["left_tip", "right_tip"]


@pytest.mark.parametrize(
    "element, message",
    [
        ('<graspmix approach_axis="0 0"/>', "approach_axis must be three finite numbers"),
        ('<graspmix approach_axis="0 0 0"/>', "not all zero"),
        ('<graspmix fingertips="gripper_pole"/>', "'gripper_pole' is not moved by any joint"),
        ('<graspmix fingertips="thumb"/>', "'thumb' is not a link"),
        ('<graspmix approach="0 0 1"/>', "unknown attribute 'approach'"),
    ],
)
def test_a_bad_element_is_an_error_naming_it(tmp_path, element, message):
    text = open(PR2).read().replace('filename="', f'filename="{pybullet_data.getDataPath()}/')
    (tmp_path / "h.urdf").write_text(text.replace("</robot>", element + "</robot>"))
    with pytest.raises(ValueError, match=message):
        Hand.from_urdf(tmp_path / "h.urdf")


def test_set_grasp_axes_and_the_experts_follow_the_hand():
    hand = Hand.from_urdf(PR2)
    with pytest.raises(ValueError, match="not moved by any joint"):
        hand.set_grasp_axes([0, 0, 1], ["gripper_pole"])
    # The approach-axis expert without a hand_axis takes the hand's: +x of a wrist turned so +x points down.
    wrist = np.array([[0, 0, 0.3, 0, np.sqrt(0.5), 0, np.sqrt(0.5)]])  # +x of the wrist -> world -z
    e = _core.AxisAlignmentExpert([0, 0, -1], hand=hand)
    assert e.log_value(wrist, np.zeros((1, 2)))[0] == pytest.approx(0.0, abs=1e-12)
    assert _core.AxisAlignmentExpert([0, 0, -1]).log_value(wrist, np.zeros((1, 2)))[0] < -1.0  # no hand: +z
    hand.set_grasp_axes([0, 0, 1], ["left_tip", "right_tip"])
    assert hand.grasp_axes_source == "set"
    assert _core.AxisAlignmentExpert([0, 0, -1], hand=hand).log_value(wrist, np.zeros((1, 2)))[0] < -1.0


def test_cli_hand_writes_the_axes(tmp_path, capsys):
    out = tmp_path / "pr2y.urdf"
    assert main(["hand", "--urdf", PR2, "--approach-axis", "0,1,0", "--fingertips", "left_tip,right_tip",
                 "--out", str(out)]) == 0  # fmt: skip
    text = capsys.readouterr().out
    assert "approach axis: [0, 1, 0] of the wrist frame (given by the URDF's <graspmix> element)" in text
    assert Hand.from_urdf(out).fingertips == ["left_tip", "right_tip"]
    assert main(["hand", "--urdf", PR2, "--approach-axis", "0,1"]) == 2
    assert capsys.readouterr().err.startswith("graspmix_cli hand: ")


def test_cli_urdf_options_take_the_prefixes_files_use(tmp_path, capsys):
    """`--urdf` / `--hand` take pybullet_data://... and package://graspmix/... as the files graspmix writes name
    them (before: "pybullet_data:/pr2_gripper.urdf: no such urdf file"); the same description as the plain path."""
    assert main(["hand", "--urdf", PR2, "--json"]) == 0
    plain = capsys.readouterr().out
    assert main(["hand", "--urdf", "pybullet_data://pr2_gripper.urdf", "--json"]) == 0
    assert capsys.readouterr().out == plain
    assert main(["hand", "--urdf", "package://graspmix/hands/wsg50.urdf", "--json"]) == 0
    bundled = capsys.readouterr().out
    assert main(["hand", "--urdf", str(data_path("hands", "wsg50.urdf")), "--json"]) == 0
    assert capsys.readouterr().out == bundled
    assert main(["hand", "--urdf", "pybullet_data://no_such_hand.urdf"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "no_such_hand.urdf" in err
