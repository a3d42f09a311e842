"""Recording demonstrations that cannot lie: joint limits, the pre-grasp's penetration (measured against
the box's known size), a wrist inside the object vs a hand closing in the air, mimic joints driven
together (the xArm gripper's linkage: graspmix's FK of the recorded joints equals pybullet's links), the
bundled PR2 demonstration, and the CLI's errors."""

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pybullet_data
import pytest
from graspmix import _core, cli
from graspmix.io import data_path, relative_path, resolve_path
from graspmix.model import Demonstration
from graspmix.sim import demonstration
from graspmix.sim.demonstration import _check_outcome, record, record_demonstration
from scipy.spatial.transform import Rotation

BOX = str(data_path("objects", "box.urdf"))  # 60 x 100 x 140 mm on the table: top at z = 0.14
WSG = str(data_path("hands", "wsg50.urdf"))
TOP = [0.0, 0.0, 0.2185, 1.0, 0.0, 0.0, 0.0]  # the bundled demonstration's wrist: fingers along x, across 60 mm


def wsg(pre, close=0.0, wrist=TOP, **kw):
    return record(BOX, WSG, wrist, {"finger_left_joint": pre}, {"finger_left_joint": close}, **kw)


def test_a_good_top_grasp_stops_at_the_box_faces():
    r = wsg(0.05)
    # The WSG 50's finger faces are at +-finger_left_joint: they stop on the box's faces at +-30 mm.
    assert r.demonstration.grasp_joints["finger_left_joint"] == pytest.approx(0.030, abs=1.5e-3)
    assert r.touching_links == ["finger_left", "finger_right"]
    assert r.object_shift < 0.005


def test_a_flat_box_gripped_low_on_the_pads_records_the_same_grip(tmp_path, monkeypatch):
    # The bundled box cut to 30 mm tall, the fingertips 5 mm above the table (the wrist 112.5 mm above their ends):
    # the fingers squeeze it low on their pads, where they swing in a cycle of a few steps between two contact sets
    # instead of resting; that is a grip, and it is the same 60 mm one as on the tall box.
    flat = tmp_path / "flat.urdf"
    flat.write_text(Path(BOX).read_text().replace('size="0.06 0.10 0.14"', 'size="0.06 0.10 0.03"'))
    assert flat.read_text().count("0.06 0.10 0.03") == 2
    wrist = [0.0, 0.0, 0.1585, 1.0, 0.0, 0.0, 0.0]
    r = record(flat, WSG, wrist, {"finger_left_joint": 0.05}, {"finger_left_joint": 0.0})
    assert r.demonstration.grasp_joints["finger_left_joint"] == pytest.approx(0.030, abs=1.5e-3)
    assert r.touching_links == ["finger_left", "finger_right"]
    assert r.object_shift < 0.005
    # They did swing: with no band they never rest, and the error names the joints that moved and how far.
    monkeypatch.setattr(demonstration, "REST_BAND", 0.0)
    with pytest.raises(
        ValueError, match=r"did not come to rest within 2000 steps \(over the last 240 steps: finger_left"
    ):
        record(flat, WSG, wrist, {"finger_left_joint": 0.05}, {"finger_left_joint": 0.0})


def test_pregrasp_with_the_fingers_inside_the_box_is_refused_with_its_depth():
    with pytest.raises(ValueError, match="pre-grasp is in collision with the object") as e:
        wsg(0.02)
    msg = str(e.value)
    # Faces at +-20 mm in a box of half-width 30 mm: both fingers 10 mm deep; the palm is clear.
    for finger in ("finger_left", "finger_right"):
        depth = float(msg.split(f"{finger} (")[1].split(" mm")[0])
        assert depth == pytest.approx(10.0, abs=0.5)
    assert "palm" not in msg and "fingers are inside" in msg


def test_a_wrist_inside_the_object_is_not_a_hand_that_closed_in_the_air():
    # The palm (box of 146 x 50 x 72 mm below the wrist) pushed into the box's top.
    with pytest.raises(ValueError, match=r"wrist/palm \(palm\) is inside the object") as e:
        wsg(0.05, wrist=[0.0, 0.0, 0.10, 1.0, 0.0, 0.0, 0.0])
    assert "without touching" not in str(e.value)
    # Wrist 40 cm up: the fingertips end 26 cm above the box and touch nothing.
    with pytest.raises(ValueError, match="closed without touching the object"):
        wsg(0.05, wrist=[0.0, 0.0, 0.40, 1.0, 0.0, 0.0, 0.0])
    # A pre-grasp through the table is named as such.
    with pytest.raises(ValueError, match="collision with the table"):
        wsg(0.05, wrist=[0.2, 0.0, 0.05, 1.0, 0.0, 0.0, 0.0])


def test_joint_values_beyond_the_limits_are_refused_before_simulating():
    with pytest.raises(ValueError, match=r"pregrasp: finger_left_joint = 0.06 is outside its limits \[0, 0.055\]"):
        wsg(0.06)
    with pytest.raises(ValueError, match=r"close_to: finger_left_joint = -0.01 is outside its limits"):
        wsg(0.05, close=-0.01)
    with pytest.raises(ValueError, match="max_steps"):
        wsg(0.05, max_steps=0)


def test_a_grasp_wider_than_its_pregrasp_is_refused():
    hand = _core.Hand.from_urdf(WSG)
    with pytest.raises(ValueError, match=r"wider than the pre-grasp \(finger_left_joint 0.03 -> 0.04"):
        _check_outcome(hand, np.array([0.03]), np.array([0.0]), np.array([0.04]), ["finger_left"], 0.0)
    # Closing towards the open end (a hand whose joints open with growing values) is the same rule reversed.
    with pytest.raises(ValueError, match="wider than the pre-grasp"):
        _check_outcome(hand, np.array([0.03]), np.array([0.055]), np.array([0.02]), ["finger_left"], 0.0)
    _check_outcome(hand, np.array([0.05]), np.array([0.0]), np.array([0.03]), ["finger_left"], 0.0)
    with pytest.raises(ValueError, match="pushed the object 30 mm away"):
        _check_outcome(hand, np.array([0.05]), np.array([0.0]), np.array([0.03]), [], 0.03)


def xarm_gripper_urdf(folder: Path) -> Path:
    """A hand-only URDF of pybullet_data's xArm gripper: the subtree of xarm6_with_gripper.urdf below
    xarm_gripper_base_link, its meshes referred to by absolute paths (nothing copied)."""
    src = Path(pybullet_data.getDataPath()) / "xarm" / "xarm6_with_gripper.urdf"
    robot = ET.parse(src).getroot()
    keep, joints = {"xarm_gripper_base_link"}, []
    for j in robot.findall("joint"):  # parents before children in this file
        if j.find("parent").get("link") in keep:
            keep.add(j.find("child").get("link"))
            joints.append(j)
    hand = ET.Element("robot", name="xarm_gripper")
    for link in robot.findall("link"):
        if link.get("name") in keep:
            for mesh in link.iter("mesh"):
                mesh.set("filename", str(src.parent / mesh.get("filename").removeprefix("package://")))
            hand.append(link)
    hand.extend(joints)
    path = folder / "xarm_gripper.urdf"
    ET.ElementTree(hand).write(path)
    return path


def test_xarm_linkage_gripper_records_and_its_joints_match_fk(tmp_path):
    urdf = xarm_gripper_urdf(tmp_path)
    hand = _core.Hand.from_urdf(str(urdf))
    assert hand.joint_names == ["drive_joint"] and len(hand.mimic_joints) == 5
    # Fingers along world x (across the box's 60 mm), approaching from above.
    q = (Rotation.from_euler("z", np.pi / 2) * Rotation.from_euler("x", np.pi)).as_quat()
    wrist = np.r_[0.0, 0.0, 0.30, q]
    r = record(BOX, urdf, wrist, {"drive_joint": 0.0}, {"drive_joint": 0.85})
    drive = r.demonstration.grasp_joints["drive_joint"]
    assert 0.1 < drive < 0.8  # stopped on the box, neither open nor fully closed
    assert set(r.touching_links) == {"left_finger", "right_finger"}
    fk = hand.fk(wrist, r.demonstration.grasp_joints)
    for name, pose in zip(hand.link_names, fk):
        # The fingertip: the finger mesh's vertex furthest along the link's z, placed by both poses.
        V, _ = hand.collision_mesh(name)
        tip = V[np.argmax(V[:, 2])]
        ours = _core.pose_multiply(pose[None], np.r_[tip, 0, 0, 0, 1.0][None])[0, :3]
        theirs = _core.pose_multiply(r.link_poses[name][None], np.r_[tip, 0, 0, 0, 1.0][None])[0, :3]
        assert np.linalg.norm(ours - theirs) < 1.5e-3, name
    # The fingertips did close: FK of the open hand puts them centimetres away.
    i = hand.link_names.index("left_finger")
    assert np.linalg.norm(hand.fk(wrist, [0.0])[i, :3] - r.link_poses["left_finger"][:3]) > 0.01


def test_bundled_pr2_demonstration_loads_portably_and_records_again():
    path = data_path("demos", "pr2_cube_small.json")
    assert '"hand": "pybullet_data://pr2_gripper.urdf"' in path.read_text()
    demo = Demonstration.load(path)
    pr2 = Path(pybullet_data.getDataPath()) / "pr2_gripper.urdf"
    assert demo.hand_path == pr2
    assert relative_path(pr2, Path("/somewhere/else")) == "pybullet_data://pr2_gripper.urdf"
    assert resolve_path("pybullet_data://pr2_gripper.urdf", Path("/")) == pr2
    again = record_demonstration(
        "cube_small.urdf", pr2, demo.T_world_wrist, demo.pregrasp_joints, {n: 0.0 for n in demo.grasp_joints}
    )
    for name, value in demo.grasp_joints.items():
        assert again.grasp_joints[name] == pytest.approx(value, abs=2e-3)


def cli_error(capsys, argv):
    assert cli.main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "error:" in err
    return err


def test_cli_demo(tmp_path, capsys):
    base = [
        "demo",
        "--wrist",
        "0,0,0.2185,1,0,0,0",
        "--close",
        "finger_left_joint=0",
        "--out",
        str(tmp_path / "d.json"),
    ]
    ok = base + ["--pregrasp", "finger_left_joint=0.05"]
    assert "outside its limits" in cli_error(capsys, base + ["--pregrasp", "finger_left_joint=0.07"])
    assert "finger_left (10.0 mm deep)" in cli_error(capsys, base + ["--pregrasp", "finger_left_joint=0.02"])
    assert "--max-steps" in cli_error(capsys, ok + ["--max-steps", "0"])
    assert "did not come to rest within 5 steps" in cli_error(capsys, ok + ["--max-steps", "5"])
    assert "--wrist" in cli_error(
        capsys, ["demo", "--wrist", "0,0,1", "--pregrasp", "a=1", "--close", "a=0", "--out", "x.json"]
    )
    assert not (tmp_path / "d.json").exists()
    png = tmp_path / "d.png"
    capsys.readouterr()
    assert cli.main(ok + ["--png", str(png), "--max-steps", "3000"]) == 0
    assert png.stat().st_size > 10_000 and png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    q = Demonstration.load(tmp_path / "d.json").grasp_joints["finger_left_joint"]
    assert q == pytest.approx(0.03, abs=1.5e-3)
    # The opening first, in synthesize's quantity and words: the WSG 50's finger gap, twice its joint value (the
    # URDF), which the fingers closed to the box's 60 mm; then the joints, labelled.
    out = capsys.readouterr().out.splitlines()
    assert out[1].strip().startswith("opening: finger gap (m): ") and out[2].strip().startswith(
        "grasp joints (m or rad)"
    )
    gap, pre = (float(x.split()[0]) for x in out[1].split(": ")[2].split(", "))
    assert gap == pytest.approx(2 * q, abs=1e-4) and gap == pytest.approx(0.060, abs=3e-3)
    assert pre == pytest.approx(2 * 0.05, abs=1e-4)
    assert f"finger_left_joint={q:.4f}" in out[2]


def test_aim_hint_names_the_quaternion_order_and_the_approach_axis():
    """The PR2 gripper approaches along its +x: above an object, x,y,z,w = (0, s, 0, s) turns +x down; the same
    numbers a w-first user means as (s, 0, s, 0) point +x up, and the hint names the order; a wrist turned so
    that +x lies flat is told to turn."""
    import pybullet_data
    from graspmix import Hand
    from graspmix.sim.demonstration import aim_hint

    hand = Hand.from_urdf(f"{pybullet_data.getDataPath()}/pr2_gripper.urdf")
    s, target = np.sqrt(0.5), np.array([0.0, 0.0, 0.0])
    assert aim_hint(hand, np.array([0, 0, 0.3, 0, s, 0, s]), target) == ""
    w_first = aim_hint(hand, np.array([0, 0, 0.3, s, 0, s, 0]), target)
    assert "180 deg off" in w_first and "meant w-first, write it as 0,0.707107,0,0.707107" in w_first
    flat = aim_hint(hand, np.array([0, 0, 0.3, 0, 0, 0, 1.0]), target)
    assert "90 deg off" in flat and flat.endswith("turn the wrist so that the approach axis points at the object")
