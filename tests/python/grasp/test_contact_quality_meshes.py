"""The contact-quality expert's closing rule for hands with mesh links (decided by their proxy boxes, the hull where
those cannot), checked against the exact hulls (scipy's ConvexHull of each mesh): pybullet_data's PR2 gripper
(revolute fingers, mesh and box links) and the Panda hand (prismatic mesh fingers), closing on a sphere."""

from pathlib import Path

import graspmix
import numpy as np
import pybullet_data
import pytest
from graspmix.model.hands import hand_urdf_from_robot
from scipy.spatial import ConvexHull
from scipy.spatial.transform import Rotation

DATA = Path(pybullet_data.getDataPath())
STEPS = graspmix.ContactQualitySettings().closing_steps
TOL = graspmix.ContactQualitySettings().contact_tolerance


def sphere(centre, r, n=3000):
    i = np.arange(n)
    z = 1 - 2 * (i + 0.5) / n
    a = np.pi * (3 - np.sqrt(5)) * i
    N = np.c_[np.sqrt(1 - z * z) * np.cos(a), np.sqrt(1 - z * z) * np.sin(a), z]
    return centre + r * N, N


def link_distances(hand, link, pose, points):
    """Each point's distance to the link posed at `pose` (7,): the largest n . x - offset over the facets of
    scipy's hull for meshes, the exact distance for boxes."""
    best = np.full(len(points), np.inf)
    for s in hand.collision_shapes(link):
        S = graspmix.pose_multiply(pose, s["origin"])
        x = Rotation.from_quat(S[3:]).inv().apply(points - S[:3])
        if s["type"] == "mesh":
            eq = ConvexHull(s["vertices"]).equations
            d = (x @ eq[:, :3].T + eq[:, 3]).max(axis=1)
        else:
            q = np.abs(x) - 0.5 * s["size"]
            d = np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(axis=1), 0)
        best = np.minimum(best, d)
    return best


CASES = {
    # the wrist's x (the fingers) towards the sphere, open 0.5 rad each, closing towards 0
    "pr2": dict(centre=[0.29, 0.0, 0.0], r=0.025, pre=[0.5, 0.5], grasp=[0.3, 0.3], q=[0.3, 0.3]),
    # +z (the fingers) towards the sphere, 40 mm each side open, closing towards 0
    "panda": dict(centre=[0.0, 0.0, 0.1], r=0.025, pre=[0.04], grasp=[0.02], q=[0.02]),
}


@pytest.fixture(scope="module")
def hands(tmp_path_factory):
    folder = tmp_path_factory.mktemp("h")
    return {
        "pr2": graspmix.Hand.from_urdf(DATA / "pr2_gripper.urdf"),
        "panda": graspmix.Hand.from_urdf(
            hand_urdf_from_robot(DATA / "franka_panda" / "panda.urdf", "panda_hand", folder / "p.urdf")
        ),
    }


@pytest.mark.parametrize("name", list(CASES))
def test_first_contacts_of_mesh_fingers_follow_the_rule_on_the_exact_hulls(hands, name):
    """For every finger that touches: within tol of the cloud at the reported joints, farther than tol at every
    step of the closing before it, and its patch within 2 tol; grasps jittered about the case's wrist."""
    hand, case = hands[name], CASES[name]
    P, N = sphere(np.asarray(case["centre"]), case["r"])
    lim = hand.joint_limits
    config = graspmix.ConfigModel(case["pre"], case["grasp"], lim)
    expert = graspmix.ContactQualityExpert(hand, P, N, config)
    rng = np.random.default_rng(11)
    wrists = np.c_[rng.normal(0, 0.004, (6, 3)), Rotation.from_rotvec(rng.normal(0, 0.1, (6, 3))).as_quat()]
    q = np.tile(case["q"], (6, 1))
    r = expert.evaluate(wrists, q)
    touched = 0
    for i in range(len(wrists)):
        p = np.asarray(config.pregrasp_for(q[i]))
        closed = np.where(q[i] < p, lim[:, 0], lim[:, 1])  # every joint here closes towards its limit
        for f, link in enumerate(r.links):
            name_f = hand.link_names[link]
            t = r.t[i, f]
            if np.isnan(t):
                continue
            touched += 1
            at = hand.fk(wrists[i], r.joints[i, f])[link]
            d = link_distances(hand, name_f, at, P)
            assert d.min() <= TOL + 1e-9, (name_f, i)
            assert r.patch_size[i, f] == (d <= 2 * TOL).sum(), (name_f, i)
            for k in range(STEPS + 1):
                if k / STEPS < t - 1e-9:
                    before = hand.fk(wrists[i], p + k / STEPS * (closed - p))[link]
                    assert link_distances(hand, name_f, before, P).min() > TOL, (name_f, i, k)
    assert touched >= 6
