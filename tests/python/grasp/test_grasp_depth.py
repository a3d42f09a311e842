"""The grasp-depth expert from Python against the definition in numpy (fingertip shapes' corners from the URDF, the
links' poses from the hand's forward kinematics), and through a synthesis."""

import graspmix
import numpy as np
import pytest
from graspmix.model.grasp_frames import rotation_matrices

MIN_DEPTH = graspmix.GraspDepthSettings().min_depth
PENALTY = graspmix.GraspDepthSettings().penalty


def corners(shape):
    """A box shape's 8 corners in its link's frame."""
    half = np.asarray(shape["size"], dtype=float) / 2
    signs = np.array([[sx, sy, sz] for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)], dtype=float)
    origin = np.asarray(shape["origin"], dtype=float)
    return (signs * half) @ rotation_matrices(origin[3:])[0].T + origin[:3]


def reference_depths(hand, points, wrists, joints, settings):
    """include/graspmix/grasp/grasp_depth.hpp's measure, grasp by grasp (box-shaped fingertips)."""
    tips = [hand.link_names.index(t) for t in hand.fingertips]
    local = [np.vstack([corners(s) for s in hand.collision_shapes(t)]) for t in hand.fingertips]
    links = np.asarray(hand.fk_batch(wrists, joints))
    out = []
    for w, pose in zip(wrists, links):
        a = rotation_matrices(w[3:])[0] @ np.asarray(hand.approach_axis, dtype=float)
        world = [c @ rotation_matrices(pose[t, 3:])[0].T + pose[t, :3] for t, c in zip(tips, local)]
        reach = max(float((c @ a).max()) for c in world)
        middles = np.array([c.mean(axis=0) for c in world])
        m = middles.mean(axis=0)
        half_gap = 0.5 * np.linalg.norm(middles[1:].mean(axis=0) - middles[0]) if len(middles) > 1 else 0.0
        rho = max(half_gap, settings.min_radius)
        v = points - m
        s = v @ a
        lateral2 = np.einsum("ij,ij->i", v, v) - s * s
        inside = lateral2 < rho * rho
        if np.any(np.abs(lateral2 - rho * rho) < 1e-9):
            out.append(np.nan)  # a point on the cylinder's wall: either side is right
            continue
        depth = (reach - points[inside] @ a).max() if inside.any() else 0.0
        out.append(min(depth, settings.min_depth))
    return np.array(out)


@pytest.mark.parametrize("hand_file", ["wsg50.urdf", "three_finger.urdf"])
def test_depths_are_the_definitions_for_random_grasps_about_an_object(hand_file):
    hand = graspmix.Hand.from_urdf(graspmix.data_path("hands", hand_file))
    rng = np.random.default_rng(7)
    # A 6 x 10 x 4 cm blob of points on the table and 300 grasps around it, turned every way.
    points = rng.uniform([-0.03, -0.05, 0.0], [0.03, 0.05, 0.04], size=(2000, 3))
    n = 300
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    axis = rotation_matrices(q) @ np.asarray(hand.approach_axis, dtype=float)
    centres = rng.uniform([-0.04, -0.06, -0.01], [0.04, 0.06, 0.06], size=(n, 3))
    wrists = np.hstack([centres - rng.uniform(0.1, 0.2, size=(n, 1)) * axis, q])
    lo, hi = np.asarray(hand.joint_limits, dtype=float).T
    joints = rng.uniform(lo, hi, size=(n, len(lo)))
    settings = graspmix.GraspDepthSettings()
    expert = graspmix.GraspDepthExpert(hand, points, settings=settings)
    got = np.asarray(expert.depths(wrists, joints))
    want = reference_depths(hand, points, wrists, joints, settings)
    ok = ~np.isnan(want)
    assert ok.sum() > 250
    np.testing.assert_allclose(got[ok], want[ok], rtol=0, atol=1e-12)
    # The spread of cases: grasps short of the minimum, none, and capped ones.
    assert (want[ok] < 0).any() and (want[ok] == MIN_DEPTH).any() and ((want[ok] > 0) & (want[ok] < MIN_DEPTH)).any()


def test_bad_settings_and_points_are_value_errors():
    hand = graspmix.Hand.from_urdf(graspmix.data_path("hands", "wsg50.urdf"))
    with pytest.raises(ValueError, match="penalty"):
        graspmix.GraspDepthExpert(hand, np.zeros((3, 3)), penalty=-1.0)
    with pytest.raises(ValueError, match="points"):
        graspmix.GraspDepthExpert(hand, np.full((3, 3), np.nan))
    with pytest.raises(ValueError, match="no points"):
        graspmix.GraspDepthExpert(hand, np.zeros((0, 3)))
    expert = graspmix.GraspDepthExpert(hand, np.zeros((3, 3)))
    with pytest.raises(ValueError, match="joints"):
        expert.depths([[0, 0, 0.2, 1, 0, 0, 0]], [[np.nan]])
    with pytest.raises(ValueError, match="grasp_depth.min_depth"):
        graspmix.SynthesisOptions(grasp_depth=graspmix.GraspDepthSettings(min_depth=float("nan")))


def test_a_synthesis_charges_each_grasp_its_depth_term_and_none_turns_it_off():
    model = graspmix.GraspModel.load(graspmix.data_path("models", "box_wsg50_gmm.json"))
    cloud = graspmix.data_path("mug.pcd")
    on = model.synthesize(cloud, graspmix.SynthesisOptions(seed=1))
    # the grasps no hard expert rejected first (the others' later terms are NaN: not evaluated)
    scored = [g for g in on if np.isfinite(g.experts["grasp_depth"])]
    assert len(scored) >= 10
    # The term is the expert's on the target's surface (observed and completed points) at each grasp.
    expert = graspmix.GraspDepthExpert(model.hand, on.surface.points)
    wrists = np.array([g.T_world_wrist for g in scored])
    joints = np.array([model.hand.joints_array(g.grasp_joints) for g in scored])
    want = -PENALTY * np.maximum(0.0, MIN_DEPTH - np.asarray(expert.depths(wrists, joints)))
    np.testing.assert_allclose([g.experts["grasp_depth"] for g in scored], want, rtol=0, atol=1e-9)
    off = model.synthesize(cloud, graspmix.SynthesisOptions(seed=1, grasp_depth=None))
    assert all("grasp_depth" not in g.experts for g in off)
