"""The proxy boxes of mesh links (CollisionShape's T_shape_box, box_half, box_growth, box_inner) against the exact hulls of
pybullet_data's meshes (scipy's ConvexHull, not graspmix's qhull call), and the collision expert's verdicts with
the proxies against depths computed here from those hulls."""

from pathlib import Path

import graspmix
import numpy as np
import pybullet_data
import pytest
from graspmix.model.hands import hand_urdf_from_robot
from scipy.spatial import ConvexHull
from scipy.spatial.transform import Rotation

DATA = Path(pybullet_data.getDataPath())


@pytest.fixture(scope="module")
def hands(tmp_path_factory):
    folder = tmp_path_factory.mktemp("hands")
    return {
        "panda": graspmix.Hand.from_urdf(DATA / "franka_panda" / "panda.urdf"),
        "xarm": graspmix.Hand.from_urdf(
            hand_urdf_from_robot(DATA / "xarm" / "xarm6_with_gripper.urdf", "xarm_gripper_base_link", folder / "x.urdf")
        ),
        "pr2": graspmix.Hand.from_urdf(DATA / "pr2_gripper.urdf"),
    }


def mesh_shapes(hand):
    return [(link, s) for link in hand.link_names for s in hand.collision_shapes(link) if s["type"] == "mesh"]


def in_box(shape, points):
    """Points (shape frame) in the proxy box's frame."""
    box = shape["proxy_box"]
    return Rotation.from_quat(box[3:]).inv().apply(points - box[:3])


def hull_distance(hull: ConvexHull, points):
    """The largest n . x - offset over the hull's facets (the experts' hull distance), scipy's planes."""
    return (points @ hull.equations[:, :3].T + hull.equations[:, 3]).max(axis=1)


@pytest.mark.parametrize("name", ["panda", "xarm", "pr2"])
def test_every_hull_vertex_lies_in_the_proxy_box(hands, name):
    shapes = mesh_shapes(hands[name])
    assert shapes
    for link, s in shapes:
        hull = ConvexHull(s["vertices"])
        q = in_box(s, s["vertices"][hull.vertices])
        assert (np.abs(q) <= s["proxy_half"] + 1e-12).all(), link
        # A tight box: each side touches the hull.
        assert np.abs(q).max(axis=0) == pytest.approx(s["proxy_half"], abs=1e-8), link
        assert np.isfinite(s["proxy_growth"]) and 1.0 <= s["proxy_growth"] < 20.0, link
        # The inner box lies in the hull (its corners do), and is not empty.
        inner = s["proxy_inner"]
        assert (inner > 0).all() and (inner <= s["proxy_half"]).all(), link
        signs = np.array([[i, j, k] for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)], dtype=float)
        box = s["proxy_box"]
        corners = Rotation.from_quat(box[3:]).apply(signs * inner) + box[:3]
        assert hull_distance(hull, corners).max() <= 1e-12, link


@pytest.mark.parametrize("name", ["panda", "xarm", "pr2"])
def test_points_within_g_of_the_hull_lie_in_the_grown_box(hands, name):
    """The growth bound, where it is tightest: points within g of sharp hull vertices (rays out of each vertex)."""
    rng = np.random.default_rng(7)
    for link, s in mesh_shapes(hands[name]):
        hull = ConvexHull(s["vertices"])
        V = s["vertices"][hull.vertices]
        for g in (0.001, 0.002, 0.01):
            dirs = Rotation.random(40 * len(V), random_state=rng).apply([1.0, 0, 0])
            P = np.repeat(V, 40, axis=0) + dirs * rng.uniform(0, 4 * g, (len(dirs), 1))
            d = hull_distance(hull, P)
            near = P[d <= g - 1e-12]
            assert len(near) > 0
            q = np.abs(in_box(s, near)) - s["proxy_half"]
            assert q.max() <= s["proxy_growth"] * g + 1e-9, (link, g)


def expected_counts(hand, T, q, cloud, tol):
    """Points inside each link's shapes by more than tol, counted once per shape (the collision expert's n_l,
    point_radius 0), from scipy's hulls and the exact box and cylinder rules."""
    poses = hand.fk(T, q)
    out = np.zeros(hand.n_links, dtype=int)
    for li, link in enumerate(hand.link_names):
        for s in hand.collision_shapes(link):
            S = graspmix.pose_multiply(poses[li], s["origin"])
            local = Rotation.from_quat(S[3:]).inv().apply(cloud - S[:3])
            if s["type"] == "mesh":
                depth = -hull_distance(ConvexHull(s["vertices"]), local)
            elif s["type"] == "box":
                depth = -(np.abs(local) - 0.5 * s["size"]).max(axis=1)
            else:
                radial = s["radius"] - np.hypot(local[:, 0], local[:, 1])
                depth = np.minimum(radial, 0.5 * s["length"] - np.abs(local[:, 2]))
            out[li] += (depth > tol).sum()
    return out


@pytest.mark.parametrize("name", ["panda", "xarm", "pr2"])
def test_collision_counts_with_proxies_match_the_exact_hulls(hands, name):
    """n_l of every link over random hand poses in a cloud around the hand: the proxies decide most points, the
    hull the rest; the counts equal the exact hulls' (points within 1e-9 m of the tolerance excluded)."""
    hand = hands[name]
    rng = np.random.default_rng(3)
    lim = hand.joint_limits
    tol = graspmix.CollisionSettings().contact_tolerance
    cloud = rng.uniform(-0.15, 0.35, (20000, 3))
    expert = graspmix.CollisionExpert(hand, cloud)
    total = 0
    for _ in range(8):
        T = np.r_[rng.uniform(-0.05, 0.05, 3), Rotation.random(random_state=rng).as_quat()]
        q = rng.uniform(lim[:, 0], lim[:, 1])
        got = np.asarray(expert.evaluate(T, q).points_inside)
        np.testing.assert_array_equal(got, expected_counts(hand, T, q, cloud, tol))
        total += got.sum()
    assert total > 20  # the poses do put points inside the hand
