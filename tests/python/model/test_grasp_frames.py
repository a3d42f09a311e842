"""What a robot stack gets of a grasp (graspmix.model.grasp_frames), against exact geometry: the WSG 50's
URDF (fingers' inner faces on their link origins, 73 mm box fingers from 8 mm above the palm's 72.5 mm
top) and scipy's rotations."""

import json

import numpy as np
import pytest
from graspmix import Hand, data_path
from graspmix.model import Grasp, GraspSet
from graspmix.model.grasp_frames import FRAME_KEYS, GraspFrameSettings, opening_widths
from scipy.spatial.transform import Rotation

WSG50 = data_path("hands", "wsg50.urdf")
# A wrist at a known pose: 20 cm above the origin, rotated 30 degrees about z after 180 about x (approach
# down and turned).
ROT = Rotation.from_euler("z", 30, degrees=True) * Rotation.from_euler("x", 180, degrees=True)
WRIST = [0.1, -0.05, 0.2, *ROT.as_quat()]
# Where the WSG 50's fingertip midpoint is in the wrist frame, from the URDF's numbers alone: on the
# centre plane, at the palm's top (0.0725) plus the finger's far end (0.0445 + 0.073 / 2).
TCP_IN_WRIST = np.array([0.0, 0.0, 0.0725 + 0.0445 + 0.073 / 2])


def _set(q=0.02, **settings):
    g = Grasp(
        list(WRIST),
        {"finger_left_joint": 0.05},
        {"finger_left_joint": q},
        rank=1,
        log_likelihood=-1.0,
        experts={"contact/palm": -1.0, "contact/finger_left": -2.0, "contact/finger_right": -3.0},
    )
    return GraspSet([g], WSG50, "gmm", "", {}, frame_settings=GraspFrameSettings(**settings))


@pytest.mark.parametrize("q", [0.0, 0.013, 0.055])
def test_frames_of_a_wsg50_grasp_are_the_urdf_geometry(q):
    g = _set(q).best()
    R = ROT.as_matrix()
    M = np.asarray(g.T_world_wrist_matrix)
    np.testing.assert_allclose(M[:3, :3], R, atol=1e-12)  # the quaternion's rotation
    np.testing.assert_allclose(M[:3, 3], WRIST[:3])
    np.testing.assert_array_equal(M[3], [0, 0, 0, 1])
    # The TCP: the fingertip midpoint at any opening, oriented like the wrist.
    np.testing.assert_allclose(g.T_world_tcp[:3], R @ TCP_IN_WRIST + WRIST[:3], atol=1e-12)
    np.testing.assert_allclose(g.T_world_tcp[3:], WRIST[3:])
    np.testing.assert_allclose(g.approach, R[:, 2], atol=1e-12)  # +z of the wrist
    np.testing.assert_allclose(g.closing, R[:, 0], atol=1e-12)  # from finger_left (-x) to finger_right
    assert g.opening_width == pytest.approx(2 * q, abs=1e-12)  # the URDF: "the opening is twice the value"
    np.testing.assert_allclose(g.T_world_pregrasp[:3], np.asarray(WRIST[:3]) - 0.10 * R[:, 2], atol=1e-12)
    np.testing.assert_allclose(g.T_world_retreat[:3], np.asarray(WRIST[:3]) - 0.10 * R[:, 2], atol=1e-12)
    assert g.T_world_pregrasp[3:] == g.T_world_retreat[3:] == list(WRIST[3:])


def test_tcp_is_the_fk_midpoint_of_the_fingertips():
    """Independently of grasp_frames: the far ends of the finger boxes from Hand.fk and the link-frame box."""
    hand = Hand.from_urdf(WSG50)
    q = 0.031
    links = hand.fk(np.asarray(WRIST), {"finger_left_joint": q})
    tips = []
    for name in ("finger_left", "finger_right"):
        pose = links[hand.link_names.index(name)]
        # the finger box's far-end face centre in its link frame: x -0.0115, z 0.0445 + 0.073 / 2
        tips.append(Rotation.from_quat(pose[3:]).apply([-0.0115, 0, 0.081]) + pose[:3])
    g = _set(q).best()
    np.testing.assert_allclose(g.T_world_tcp[:3], np.mean(tips, axis=0), atol=1e-12)
    assert np.linalg.norm(tips[1] - tips[0]) == pytest.approx(2 * q + 0.023, abs=1e-12)  # centres, not faces


def test_stand_off_distances_and_approach_axis_are_settings():
    g = _set(0.02, pregrasp_distance=0.05, retreat_distance=0.2, approach_axis=(0, 0, 2)).best()
    R = ROT.as_matrix()
    np.testing.assert_allclose(g.T_world_pregrasp[:3], np.asarray(WRIST[:3]) - 0.05 * R[:, 2], atol=1e-12)
    np.testing.assert_allclose(g.T_world_retreat[:3], np.asarray(WRIST[:3]) - 0.2 * R[:, 2], atol=1e-12)
    for bad in ({"approach_axis": (0, 0, 0)}, {"pregrasp_distance": -1.0}, {"retreat_distance": float("nan")}):
        with pytest.raises(ValueError):
            _set(0.02, **bad)
    with pytest.raises(ValueError, match="not a link"):
        _set(0.02, fingertip_links=("thumb",))


def test_frames_take_the_hands_approach_axis_and_fingertips():
    """Without settings of their own the frames use Hand.approach_axis and Hand.fingertips, and the file records
    the axis they were made with."""
    grasps = _set(0.02)
    hand = Hand.from_urdf(WSG50)
    assert grasps.frame_settings.approach_axis == tuple(hand.approach_axis) == (0.0, 0.0, 1.0)
    assert grasps.fingertips == list(hand.fingertips) == ["finger_left", "finger_right"]


def test_grasps_json_keeps_the_old_keys_first(tmp_path):
    grasps = _set(0.02)
    grasps.save(tmp_path / "g.json")
    doc = json.loads((tmp_path / "g.json").read_text())
    old = ["rank", "T_world_wrist", "pregrasp_joints", "grasp_joints", "log_likelihood", "experts"]
    assert list(doc["grasps"][0]) == old + list(FRAME_KEYS)
    assert list(doc)[:6] == ["format", "hand", "method", "cloud", "timing_s", "grasps"]
    assert doc["frames"]["fingertip_links"] == ["finger_left", "finger_right"]
    assert doc["grasps"][0]["opening_width"] == pytest.approx(0.04)


def test_synthesize_table_prints_the_opening_in_metres(capsys):
    from graspmix.cli.grasp_commands import print_grasps

    grasps = _set(0.0123)
    print_grasps(grasps, 5)
    head, row = capsys.readouterr().out.splitlines()
    assert head.endswith("opening: finger gap (m)")
    assert row.split()[-1] == "0.0246"  # twice the joint value, in metres
    # A hand that is no two-finger gripper: the joints, named, in the URDF's units.
    print_grasps(_set(0.0123, fingertip_links=("finger_left",)), 5)
    head, row = capsys.readouterr().out.splitlines()
    assert head.endswith("grasp joints (m or rad)") and row.endswith("finger_left_joint=0.0123")


def test_opening_widths_are_the_exports_gap():
    """What demo prints: the WSG 50's gap is twice its joint value (the URDF), whatever form the joints take, and
    the gap a grasps file exports at the same joints; bad joints are a ValueError naming them."""
    hand = Hand.from_urdf(WSG50)
    q = [0.0, 0.0123, 0.055]
    widths = opening_widths(hand, [{"finger_left_joint": q[0]}, {"finger_left_joint": q[1]}, np.array([q[2]])])
    np.testing.assert_allclose(widths, 2 * np.array(q), atol=1e-12)
    assert widths[1] == pytest.approx(_set(q[1]).best().opening_width, abs=1e-12)  # at another wrist
    assert opening_widths(hand, []) == []
    with pytest.raises(ValueError, match="unknown joint 'nope'"):
        opening_widths(hand, [{"nope": 0.01}])
    with pytest.raises(ValueError, match="'finger_left_joint' has a non-finite value"):
        opening_widths(hand, [{"finger_left_joint": float("nan")}])


def test_frames_of_mesh_fingertips_follow_the_rule_vertex_by_vertex(tmp_path):
    """pybullet_data's Panda hand (mesh fingers): the TCP and the opening from every mesh vertex placed in the
    world by Hand.fk, by the rule of grasp_frames' docstring, at several wrists and openings."""
    import pybullet_data
    from graspmix.model.grasp_frames import FrameMaker
    from graspmix.model.hands import hand_urdf_from_robot

    urdf = hand_urdf_from_robot(
        f"{pybullet_data.getDataPath()}/franka_panda/panda.urdf", "panda_hand", tmp_path / "p.urdf"
    )
    hand = Hand.from_urdf(urdf)
    tips = ["panda_leftfinger", "panda_rightfinger"]
    rng = np.random.default_rng(5)
    wrists = np.c_[rng.uniform(-0.1, 0.1, (6, 3)), Rotation.random(6, random_state=rng).as_quat()]
    joints = rng.uniform(0.0, 0.04, (6, 1))
    frames = FrameMaker(hand, GraspFrameSettings(fingertip_links=tuple(tips))).frames(wrists, joints)
    for w, q, f in zip(wrists, joints, frames):
        links = hand.fk(w, q)
        R = Rotation.from_quat(w[3:])
        pts, tip_points = [], []
        for name in tips:
            pose = links[hand.link_names.index(name)]
            vertices = np.asarray(hand.collision_mesh(name)[0])  # link frame (the right finger's mesh is turned)
            world = Rotation.from_quat(pose[3:]).apply(vertices) + pose[:3]
            L = R.inv().apply(world - w[:3])
            near = L[L[:, 2] >= L[:, 2].max() - GraspFrameSettings().fingertip_tolerance]
            tip_points.append(R.apply((near.min(axis=0) + near.max(axis=0)) / 2) + w[:3])
            pts.append(world)
        np.testing.assert_allclose(f["T_world_tcp"][:3], np.mean(tip_points, axis=0), atol=1e-12)
        c = (tip_points[1] - tip_points[0]) / np.linalg.norm(tip_points[1] - tip_points[0])
        np.testing.assert_allclose(f["closing"], c, atol=1e-9)
        assert f["opening_width"] == pytest.approx((pts[1] @ c).min() - (pts[0] @ c).max(), abs=1e-12)


@pytest.mark.parametrize("n", [1, 2, 3, 37, 200, 201])
def test_vertex_products_in_blocks_are_the_one_product_bit_for_bit(n, monkeypatch):
    """The fingertips' products taken in blocks of grasps (so that BLAS keeps them on the calling thread) give the
    values of the one product, exactly, however the blocks fall (down to blocks of two rows)."""
    from graspmix.model import grasp_frames

    rng = np.random.default_rng(n)
    V = rng.normal(scale=0.03, size=(2426, 3))
    b = rng.normal(size=(n, 3))
    one = V @ b.T
    for madds in (2**18, 1000, 1):
        monkeypatch.setattr(grasp_frames, "BLAS_SERIAL_MADDS", madds)
        np.testing.assert_array_equal(grasp_frames.vertex_products(V, b), one)


def test_fingertip_vertices_are_gathered_once_per_hand():
    """A hand's fingertip vertices are read once (the same read-only array for every FrameMaker of that hand) and
    are the distinct vertices of its collision mesh; another hand object reads its own."""
    from graspmix.model.grasp_frames import FrameMaker, link_vertices

    hand = Hand.from_urdf(WSG50)
    a, b = FrameMaker(hand), FrameMaker(hand)
    assert all(x is y for x, y in zip(a.vertices, b.vertices)) and not a.vertices[0].flags.writeable
    V, T = hand.collision_mesh(a.tips[0])
    np.testing.assert_array_equal(
        np.unique(np.asarray(V)[np.unique(np.asarray(T))], axis=0), np.unique(a.vertices[0], axis=0)
    )
    other = Hand.from_urdf(WSG50)
    assert link_vertices(other, a.tips[0]) is not a.vertices[0]
    np.testing.assert_array_equal(link_vertices(other, a.tips[0]), a.vertices[0])


@pytest.mark.parametrize("tolerance", [0.0, 0.002, 0.01])
def test_frames_of_the_deciding_vertices_are_those_of_all_bit_for_bit(tolerance, tmp_path, monkeypatch):
    """The xArm gripper's pads (2,426 distinct vertices each): the frames from the vertices that can decide them
    (FrameMaker.deciding, fewer) equal, bit for bit, those from every vertex, at random wrists and openings (wrists
    far from the origin too) and at several fingertip tolerances; the near-coincident fingertips of a shut gripper
    included."""
    import pybullet_data
    from graspmix.model import grasp_frames
    from graspmix.model.hands import hand_urdf_from_robot

    urdf = hand_urdf_from_robot(
        f"{pybullet_data.getDataPath()}/xarm/xarm6_with_gripper.urdf", "xarm_gripper_base_link", tmp_path / "x.urdf"
    )
    settings = GraspFrameSettings(fingertip_tolerance=tolerance)
    rng = np.random.default_rng(11)
    n = 300
    wrists = np.c_[rng.uniform(-0.3, 0.3, (n, 3)), Rotation.random(n, random_state=rng).as_quat()]
    wrists[: n // 3, :3] += 25.0  # larger world coordinates, larger rounding
    hand = Hand.from_urdf(urdf)
    lo, hi = np.asarray(hand.joint_limits).reshape(-1, 2).T
    joints = rng.uniform(lo, hi, (n, len(lo)))
    joints[:10] = hi  # shut
    maker = grasp_frames.FrameMaker(hand, settings)
    assert all(len(d) < len(v) for d, v in zip(maker.deciding, maker.vertices))
    fast = maker.frames(wrists, joints)
    monkeypatch.setattr(grasp_frames, "MANY_VERTICES", 10**9)  # another hand object: every vertex decides
    every = grasp_frames.FrameMaker(Hand.from_urdf(urdf), settings)
    assert all(len(d) == len(v) for d, v in zip(every.deciding, every.vertices))
    assert fast == every.frames(wrists, joints)
