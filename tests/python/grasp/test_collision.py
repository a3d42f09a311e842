"""The collision expert W(h) against analytic depths and an independent numpy implementation."""

from pathlib import Path

import graspmix
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

WSG50 = graspmix.data_path("hands", "wsg50.urdf")
IDENTITY = np.array([0, 0, 0, 0, 0, 0, 1.0])
EXACT = 1e-9  # these tests measure exact depths: no contact tolerance (the default is 1 mm)


def box_surface(lo, hi, step=0.002):
    """Points on the faces of the axis-aligned box [lo, hi] on a grid (the grid includes the faces)."""
    axes = [np.linspace(a, b, int(round((b - a) / step)) + 1) for a, b in zip(lo, hi)]
    X, Y, Z = np.meshgrid(*axes, indexing="ij")
    P = np.c_[X.ravel(), Y.ravel(), Z.ravel()]
    on_face = np.zeros(len(P), bool)
    for k in range(3):
        on_face |= np.isclose(P[:, k], lo[k]) | np.isclose(P[:, k], hi[k])
    return P[on_face]


def numpy_box_depths(hand, T_world_wrist, q, cloud, radius=0.0):
    """Per link: max over points of max(0, r - sd) with sd the exact box signed distance (numpy)."""
    poses = hand.fk(T_world_wrist, q)
    out = np.zeros(hand.n_links)
    for li, link in enumerate(hand.link_names):
        for shape in hand.collision_shapes(link):
            assert shape["type"] == "box"
            T = graspmix.pose_multiply(poses[li], shape["origin"])
            local = Rotation.from_quat(T[3:]).inv().apply(cloud - T[:3])
            qd = np.abs(local) - 0.5 * np.asarray(shape["size"])
            sd = np.linalg.norm(np.maximum(qd, 0), axis=1) + np.minimum(qd.max(axis=1), 0)
            out[li] = max(out[li], np.max(np.maximum(0.0, radius - sd)))
    return out


@pytest.fixture(scope="module")
def wsg():
    return graspmix.Hand.from_urdf(WSG50)


def test_finger_depth_grows_with_penetration_and_is_zero_when_clear(wsg):
    q = 0.05  # fingers' inner faces at x = -0.05 and +0.05, from 8 to 81 mm above the palm's top
    depths = [-0.001, 0.0, 0.001, 0.002, 0.004, 0.006, 0.008]
    got = []
    for d in depths:
        # A 3 cm wide box whose -x face is d behind the left finger's inner face.
        cloud = box_surface([-q - d, -0.05, 0.09], [-q - d + 0.03, 0.05, 0.2])
        expert = graspmix.CollisionExpert(wsg, cloud, contact_tolerance=EXACT)
        r = expert.evaluate(IDENTITY, [q])
        got.append(r.cloud_depth[1])
        assert r.cloud_depth[0] == 0.0 and r.cloud_depth[2] == 0.0  # palm and right finger are clear
        assert r.collision_free == (d <= 0.0)
        assert r.log_w == pytest.approx(-expert.beta * r.total_depth)
        assert r.w == pytest.approx(np.exp(r.log_w))
    np.testing.assert_allclose(got, np.maximum(depths, 0.0), atol=1e-12)
    assert np.all(np.diff(got) >= 0)


def test_matches_independent_numpy_depths(wsg):
    rng = np.random.default_rng(5)
    cloud = box_surface([-0.03, -0.04, 0.0], [0.03, 0.04, 0.1], step=0.004)
    for radius in (0.0, 0.003):
        expert = graspmix.CollisionExpert(wsg, cloud, point_radius=radius, contact_tolerance=EXACT)
        n = 150
        # Wrists below the box, approaching it from underneath with random tilt and offset.
        tilt = Rotation.from_rotvec(rng.normal(scale=0.4, size=(n, 3)))
        wrists = np.c_[rng.uniform(-0.04, 0.04, (n, 2)), rng.uniform(-0.16, -0.04, n), tilt.as_quat()]
        joints = rng.uniform(0.0, 0.055, (n, 1))
        batch = expert.evaluate_batch(wrists, joints)
        for i in range(n):
            expected = numpy_box_depths(wsg, wrists[i], joints[i], cloud, radius)
            np.testing.assert_allclose(batch.cloud_depth[i], expected, atol=1e-12)
            assert batch.collision_free[i] == (expected.sum() == 0.0)
        assert 0.2 < batch.collision_free.mean() < 0.9  # the sample exercises both cases
        np.testing.assert_allclose(expert.log_w(wrists, joints), -expert.beta * batch.total_depth)
        np.testing.assert_array_equal(expert.collision_free(wrists, joints), batch.collision_free)


def test_collision_free_expert_is_the_numpy_verdict_at_grasp_and_pregrasp(wsg):
    """CollisionFreeExpert (what keeps a grasp clear of a scene's other objects) against the numpy depths of the
    hand at the grasp and at its pre-grasp (ConfigModel.pregrasp_for)."""
    rng = np.random.default_rng(11)
    cloud = box_surface([-0.03, -0.04, 0.0], [0.03, 0.04, 0.1], step=0.004)
    collision = graspmix.CollisionExpert(wsg, cloud, contact_tolerance=EXACT)
    config = graspmix.ConfigModel([0.05], [0.02], [[0.0, 0.055]])
    n = 120
    tilt = Rotation.from_rotvec(rng.normal(scale=0.4, size=(n, 3)))
    wrists = np.c_[rng.uniform(-0.05, 0.05, (n, 2)), rng.uniform(-0.16, -0.06, n), tilt.as_quat()]
    joints = rng.uniform(0.0, 0.055, (n, 1))
    got = graspmix.CollisionFreeExpert(collision, config, name="clear").log_value(wrists, joints)
    for i in range(n):
        pre = config.pregrasp_for(joints[i])
        free = not numpy_box_depths(wsg, wrists[i], joints[i], cloud).any()
        free &= not numpy_box_depths(wsg, wrists[i], pre, cloud).any()
        assert got[i] == (0.0 if free else -np.inf), i
    assert 0.1 < np.mean(got == 0) < 0.9
    with pytest.raises(ValueError, match="collision"):
        graspmix.CollisionFreeExpert(None, config)
    with pytest.raises(ValueError, match="joints"):
        graspmix.CollisionFreeExpert(collision, graspmix.ConfigModel([0.05, 0.0], [0.02, 0.0], [[0, 1], [0, 1]]))


def test_support_plane_blocks_a_hand_below_the_table(wsg):
    cloud = box_surface([-0.02, -0.02, 0.0], [0.02, 0.02, 0.1])
    # The plane's sign does not matter: it is oriented so that the cloud lies above it.
    expert = graspmix.CollisionExpert(wsg, cloud, plane=[0, 0, -3.0, 0], contact_tolerance=EXACT)
    np.testing.assert_allclose(expert.plane, [0, 0, 1, 0], atol=1e-15)
    down = Rotation.from_euler("x", np.pi).as_quat()  # approach along -z, fingertips 0.1535 m below the wrist
    beside = np.array([0.3, 0.0])
    clear = expert.evaluate(np.r_[beside, 0.16, down], [0.03])
    assert clear.collision_free and clear.total_depth == 0.0
    for h in (0.15, 0.12, 0.09):
        r = expert.evaluate(np.r_[beside, h, down], [0.03])
        # Each finger's tip goes 0.1535 - h below the table; the palm (72.5 mm) stays above.
        np.testing.assert_allclose(r.plane_depth, [0.0, 0.1535 - h, 0.1535 - h], atol=1e-9)
        assert not r.collision_free and r.w < 1.0
    # A whole hand below the table.
    r = expert.evaluate(np.r_[beside, -0.2, IDENTITY[3:]], [0.03])
    assert r.plane_depth[0] == pytest.approx(0.2, abs=1e-9)
    assert r.w < 1e-50
    # A margin keeps the hand that much above the table.
    raised = graspmix.CollisionExpert(wsg, cloud, plane=[0, 0, 1, 0], plane_margin=0.02, contact_tolerance=EXACT)
    assert not raised.evaluate(np.r_[beside, 0.16, down], [0.03]).collision_free


def test_mesh_links_use_their_convex_hull(tmp_path):
    # A cube mesh (OBJ, scaled to 2 x 4 x 6 cm) must give the depths of the equivalent box.
    verts = [[(i & 1) - 0.5, ((i >> 1) & 1) - 0.5, ((i >> 2) & 1) - 0.5] for i in range(8)]
    faces = [
        (0, 2, 1),
        (1, 2, 3),
        (4, 5, 6),
        (5, 7, 6),
        (0, 1, 4),
        (1, 5, 4),
        (2, 6, 3),
        (3, 6, 7),
        (0, 4, 2),
        (2, 4, 6),
        (1, 3, 5),
        (3, 7, 5),
    ]
    (tmp_path / "cube.obj").write_text(
        "".join(f"v {x} {y} {z}\n" for x, y, z in verts) + "".join(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in faces)
    )
    (tmp_path / "m.urdf").write_text(
        '<robot name="m"><link name="cube"><collision><origin xyz="0.01 0 0"/><geometry>'
        '<mesh filename="cube.obj" scale="0.02 0.04 0.06"/></geometry></collision></link></robot>'
    )
    (tmp_path / "b.urdf").write_text(
        '<robot name="b"><link name="cube"><collision><origin xyz="0.01 0 0"/><geometry>'
        '<box size="0.02 0.04 0.06"/></geometry></collision></link></robot>'
    )
    mesh_hand = graspmix.Hand.from_urdf(tmp_path / "m.urdf")
    box_hand = graspmix.Hand.from_urdf(tmp_path / "b.urdf")
    cloud = box_surface([0.0, -0.05, -0.05], [0.1, 0.05, 0.05], step=0.0025)
    rng = np.random.default_rng(2)
    wrists = np.c_[rng.uniform(-0.03, 0.03, (100, 3)), Rotation.random(100, random_state=rng).as_quat()]
    for plane in (None, [0, 0, 1, 0.04]):
        a = graspmix.CollisionExpert(mesh_hand, cloud, plane=plane, contact_tolerance=EXACT).evaluate_batch(
            wrists, np.zeros((100, 0))
        )
        b = graspmix.CollisionExpert(box_hand, cloud, plane=plane, contact_tolerance=EXACT).evaluate_batch(
            wrists, np.zeros((100, 0))
        )
        np.testing.assert_allclose(a.cloud_depth, b.cloud_depth, atol=1e-12)
        np.testing.assert_allclose(a.plane_depth, b.plane_depth, atol=1e-9)
        assert 0 < a.collision_free.sum() < 100


def test_bad_input_is_a_value_error(wsg):
    cloud = box_surface([0, 0, 0], [0.05, 0.05, 0.05])
    with pytest.raises(ValueError, match="cloud"):
        graspmix.CollisionExpert(wsg, cloud[:, :2])
    with pytest.raises(ValueError, match="plane"):
        graspmix.CollisionExpert(wsg, cloud, plane=[0, 0, 1])
    with pytest.raises(ValueError, match="point_radius"):
        graspmix.CollisionExpert(wsg, cloud, point_radius=-0.1)
    expert = graspmix.CollisionExpert(wsg, cloud, contact_tolerance=EXACT)
    with pytest.raises(ValueError, match="'thumb'"):
        expert.evaluate(IDENTITY, {"thumb": 0.1})
    with pytest.raises(ValueError, match="joints"):
        expert.evaluate_batch(np.tile(IDENTITY, (3, 1)), np.zeros((2, 1)))


def test_plane_depth_of_pybullet_panda_meshes_matches_their_lowest_vertex():
    """FCL's half-space depth for mesh links (as hulls) = how far the lowest mesh vertex is below the plane."""
    import pybullet_data

    hand = graspmix.Hand.from_urdf(Path(pybullet_data.getDataPath()) / "franka_panda" / "panda.urdf")
    expert = graspmix.CollisionExpert(hand, np.zeros((0, 3)), plane=[0, 0, 1, -0.3])
    rng = np.random.default_rng(4)
    lim = hand.joint_limits
    for _ in range(10):
        T = np.r_[rng.uniform(-0.2, 0.2, 3), Rotation.random(random_state=rng).as_quat()]
        q = rng.uniform(lim[:, 0], lim[:, 1])
        r = expert.evaluate(T, q)
        poses = hand.fk(T, q)
        for li, link in enumerate(hand.link_names):
            lowest = np.inf
            for shape in hand.collision_shapes(link):
                S = graspmix.pose_multiply(poses[li], shape["origin"])
                lowest = min(lowest, (Rotation.from_quat(S[3:]).apply(shape["vertices"]) + S[:3])[:, 2].min())
            expected = max(0.0, 0.3 - lowest) if np.isfinite(lowest) else 0.0
            assert r.plane_depth[li] == pytest.approx(expected, abs=1e-9), link
        assert r.cloud_depth.sum() == 0.0


def test_a_cloud_spread_over_kilometres_is_refused_not_missed():
    """A point 1e30 m away would make the cloud's grid measure the others to no precision: an error naming the
    span (a unit mistake or a stray point), where a collision would otherwise be missed."""
    hand = graspmix.Hand.from_urdf(str(graspmix.data_path("hands", "wsg50.urdf")))
    pts = np.random.default_rng(0).normal(size=(200, 3)) * 0.02
    graspmix.CollisionExpert(hand, pts)  # a scene-sized cloud is fine
    for far in (1e30, 2e4):
        with pytest.raises(ValueError, match="span"):
            graspmix.CollisionExpert(hand, np.vstack([pts, [far, 0.0, 0.0]]))
