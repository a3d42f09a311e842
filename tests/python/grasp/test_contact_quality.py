"""The contact-quality expert from Python against analytic contacts (WSG 50: approach +z, fingers closing along x,
inner faces at x = -+q from 80.5 to 153.5 mm above the flange), and its errors."""

import graspmix
import numpy as np
import pytest
from scipy.spatial.transform import Rotation

WSG50 = graspmix.data_path("hands", "wsg50.urdf")
CENTRE = np.array([0.0, 0.0, 0.12])  # between the fingers of a wrist at the origin
CONE = np.arctan(0.5)
TIP = 0.1535  # the fingertips' height above the flange


@pytest.fixture(scope="module")
def hand():
    return graspmix.Hand.from_urdf(WSG50)


@pytest.fixture(scope="module")
def opening():
    """Each grasp's pre-grasp is 20 mm more open (clamped to 55 mm)."""
    return graspmix.ConfigModel([0.05], [0.03], [[0.0, 0.055]])


def sphere(centre, r, n=4000):
    i = np.arange(n)
    z = 1 - 2 * (i + 0.5) / n
    rho = np.sqrt(1 - z * z)
    a = np.pi * (3 - np.sqrt(5)) * i
    u = np.c_[rho * np.cos(a), rho * np.sin(a), z]
    return centre + r * u, u


def box(centre, half, step=0.002):
    """Face interiors of an axis-aligned box on a grid, with their outward normals."""
    pts, nrm = [], []
    for k in range(3):
        u, v = (k + 1) % 3, (k + 2) % 3
        gu = np.linspace(-half[u], half[u], int(round(2 * half[u] / step)) + 1)[1:-1]
        gv = np.linspace(-half[v], half[v], int(round(2 * half[v] / step)) + 1)[1:-1]
        U, V = np.meshgrid(gu, gv, indexing="ij")
        for side in (-1.0, 1.0):
            p = np.zeros((U.size, 3))
            p[:, k], p[:, u], p[:, v] = side * half[k], U.ravel(), V.ravel()
            n = np.zeros_like(p)
            n[:, k] = side
            pts.append(centre + p)
            nrm.append(n)
    return np.vstack(pts), np.vstack(nrm)


def wrist(at=(0, 0, 0), rot=None):
    q = [0, 0, 0, 1] if rot is None else rot.as_quat()
    return np.r_[at, q][None]


def test_box_across_faces_scores_zero_and_meets_it_where_the_gap_is_its_width(hand, opening):
    P, N = box(CENTRE, [0.02, 0.02, 0.02])
    e = graspmix.ContactQualityExpert(hand, P, -N, opening)  # normal signs do not matter
    assert e.name == "contact_quality" and e.finger_names == ["finger_left", "finger_right"]
    r = e.evaluate(wrist(), [[0.015]])
    assert r.log_value[0] == 0.0
    # Pre-grasp 35 mm; a finger meets the face 20 mm out once within the 1 mm tolerance: joint 21 mm.
    np.testing.assert_allclose(r.joints[0, :, 0], 0.021, atol=1e-9)
    np.testing.assert_allclose(r.t[0], (0.035 - 0.021) / 0.035, atol=1e-9)
    np.testing.assert_allclose(np.abs(r.normals[0, :, 0]), 1.0, atol=1e-9)
    np.testing.assert_allclose(r.normals[0, :, 0], [-1.0, 1.0], atol=1e-9)  # towards each finger
    np.testing.assert_allclose(r.angles[0], 0.0, atol=1e-6)
    np.testing.assert_array_equal(e.log_value(wrist(), [[0.015]]), r.log_value)


def test_sphere_through_its_centre_scores_zero_and_off_centre_worse_with_the_offset(hand, opening):
    R = 0.03
    P, N = sphere(CENTRE, R)
    e = graspmix.ContactQualityExpert(hand, P, N, opening, patch_points=0.0)  # the cone term alone
    with_patches = graspmix.ContactQualityExpert(hand, P, N, opening)  # the defaults: small patches charged too
    defaults = graspmix.ContactQualitySettings()
    assert e.log_value(wrist(), [[0.02]])[0] == 0.0
    assert with_patches.log_value(wrist(), [[0.02]])[0] == 0.0  # through the centre each finger presses a wide cap
    # The centre h beyond the fingertips: their edges touch where the normal is asin((h - tol) / R) off the
    # closing axis.
    values = []
    for deg in (35, 45, 60):
        alpha = np.radians(deg)
        h = R * np.sin(alpha) + 1e-3
        r = e.evaluate(wrist([0, 0, CENTRE[2] - TIP - h]), [[0.02]])
        np.testing.assert_allclose(r.angles[0], alpha, atol=0.05)
        np.testing.assert_allclose(r.log_value[0], -20 * (alpha - CONE), atol=1.5)
        values.append(r.log_value[0])
        # An edge presses on few points: each finger's shortfall below patch_points charged on top.
        both = with_patches.evaluate(wrist([0, 0, CENTRE[2] - TIP - h]), [[0.02]])
        np.testing.assert_array_equal(both.patch_size, r.patch_size)
        short = np.clip(1 - r.patch_size[0] / defaults.patch_points, 0, None)
        assert short.min() > 0
        np.testing.assert_allclose(both.log_value[0], r.log_value[0] - defaults.patch_penalty * short.sum(), atol=1e-12)
    assert 0 > values[0] > values[1] > values[2]
    # The WSG 50's 30 x 73 mm pads meet far more of a flat face than patch_points: each finger's reference is it.
    assert with_patches.patch_reference == [defaults.patch_points] * 2


def test_cylinder_across_its_axis_scores_zero(hand, opening):
    a = 2 * np.pi * (np.arange(120) + 0.5) / 120
    y = np.linspace(-0.04, 0.04, 41)
    A, Y = np.meshgrid(a, y, indexing="ij")
    N = np.c_[np.cos(A.ravel()), np.zeros(A.size), np.sin(A.ravel())]
    P = CENTRE + 0.025 * N + np.c_[np.zeros(A.size), Y.ravel(), np.zeros(A.size)]
    r = graspmix.ContactQualityExpert(hand, P, N, opening).evaluate(wrist(), [[0.02]])
    assert r.log_value[0] == 0.0
    np.testing.assert_allclose(r.joints[0, :, 0], 0.025 * np.cos(np.pi / 120) + 1e-3, atol=1e-9)


def test_corner_pinch_scores_low(hand, opening):
    """Fingers closing diagonally across a box's vertical edge each meet a face 45 degrees off the grasp line."""
    P, N = box(np.array([-0.02, -0.02, 0.12]), [0.02, 0.02, 0.02])
    e = graspmix.ContactQualityExpert(hand, P, N, opening)
    r = e.evaluate(wrist(rot=Rotation.from_euler("z", -45, degrees=True)), [[0.02]])
    np.testing.assert_allclose(r.angles[0], np.pi / 4, atol=0.02)
    np.testing.assert_allclose(r.log_value[0], -20 * (np.pi / 4 - CONE), atol=0.3)
    assert r.log_value[0] < -5
    assert e.log_value(wrist([-0.02, -0.02, 0]), [[0.015]])[0] == 0.0  # the same box across two faces


def test_nothing_between_the_fingers_costs_two_air_penalties(hand, opening):
    P, N = box(np.array([0.5, 0.0, 0.12]), [0.02, 0.02, 0.02])
    e = graspmix.ContactQualityExpert(hand, P, N, opening, air_penalty=4.0)
    r = e.evaluate(wrist(), [[0.02]])
    assert r.log_value[0] == -8.0
    assert np.isnan(r.t).all() and np.isnan(r.points).all() and (r.patch_size == 0).all()


def test_more_friction_accepts_what_less_rejects(hand, opening):
    P, N = sphere(CENTRE, 0.03)
    w = wrist([0, 0, CENTRE[2] - TIP - 0.03 * np.sin(np.radians(35)) - 1e-3])  # contacts 35 degrees off
    values = [
        graspmix.ContactQualityExpert(hand, P, N, opening, friction=mu, patch_points=0.0).log_value(w, [[0.02]])[0]
        for mu in (0.3, 0.5, 0.7, 1.0)
    ]
    assert values == sorted(values) and values[1] < -0.5 and values[3] == 0.0


def test_batches_are_per_grasp_and_finite(hand, opening):
    P, N = sphere(CENTRE, 0.03, 2000)
    e = graspmix.ContactQualityExpert(hand, P, N, opening)
    rng = np.random.default_rng(0)
    rot = Rotation.random(300, random_state=1)
    wrists = np.c_[CENTRE - rot.apply([0, 0, 0.12]) + rng.normal(0, 0.01, (300, 3)), rot.as_quat()]
    joints = rng.uniform(0.0, 0.055, (300, 1))
    batch = e.log_value(wrists, joints)  # parallel over grasps
    one_by_one = [e.log_value(wrists[i : i + 1], joints[i : i + 1])[0] for i in range(0, 300, 7)]
    np.testing.assert_array_equal(batch[::7], one_by_one)
    assert np.isfinite(batch).all() and (batch <= 0).all() and (batch < 0).any() and (batch == 0).any()


@pytest.mark.parametrize(
    "kw",
    [
        {"friction": 0.0},
        {"friction": -0.5},
        {"friction": float("nan")},
        {"concentration": -1.0},
        {"air_penalty": -1.0},
        {"closing_steps": 0},
    ],
)
def test_bad_settings_raise(hand, opening, kw):
    P, N = box(CENTRE, [0.02, 0.02, 0.02], 0.004)
    with pytest.raises(ValueError, match=next(iter(kw))):
        graspmix.ContactQualityExpert(hand, P, N, opening, **kw)


def test_bad_clouds_and_grasps_raise(hand, opening):
    P, N = box(CENTRE, [0.02, 0.02, 0.02], 0.004)
    with pytest.raises(ValueError, match="normals"):
        graspmix.ContactQualityExpert(hand, P, N[:-1], opening)
    zero = N.copy()
    zero[3] = 0
    with pytest.raises(ValueError, match="normals row 3 is zero"):
        graspmix.ContactQualityExpert(hand, P, zero, opening)
    bad = P.copy()
    bad[0, 0] = np.nan
    with pytest.raises(ValueError, match="points"):
        graspmix.ContactQualityExpert(hand, bad, N, opening)
    with pytest.raises(ValueError, match="points"):
        graspmix.ContactQualityExpert(hand, P[:, :2], N, opening)
    with pytest.raises(ValueError, match="configuration model"):
        graspmix.ContactQualityExpert(hand, P, N, graspmix.ConfigModel([0.05, 0.0], [0.03, 0.0], [[0, 1], [0, 1]]))
    e = graspmix.ContactQualityExpert(hand, P, N, opening)
    with pytest.raises(ValueError, match="joints"):
        e.log_value(wrist(), [[0.02], [0.01]])
    with pytest.raises(ValueError, match="wrists"):
        e.log_value(np.r_[0, 0, 0, 0, 0, 0, 0.0][None], [[0.02]])
    with pytest.raises(ValueError, match="unknown_setting"):
        graspmix.ContactQualityExpert(hand, P, N, opening, unknown_setting=1)
    assert graspmix.ContactQualitySettings().friction == 0.5  # the C++ defaults


def test_synthesis_options_of_the_new_experts_are_checked(capsys):
    """synthesize() and the CLI refuse a friction <= 0 and a negative stand-off or clearance before any work."""
    from graspmix import cli

    model = graspmix.GraspModel.load(graspmix.default_model_path())
    cloud = graspmix.data_path("mug.pcd")
    for changes, name in (
        ({"contact_quality.friction": 0.0}, "friction"),
        ({"contact_quality.friction": -1.0}, "friction"),
        ({"contact_quality.friction": float("nan")}, "friction"),
        ({"approach.stand_off": -0.01}, "stand_off"),
        ({"approach.clearance": -0.001}, "clearance"),
    ):
        with pytest.raises(ValueError, match=name):
            model.synthesize(cloud, graspmix.SynthesisOptions().updated(changes))
    for flag, value in (("--friction", "0"), ("--stand-off", "-0.1"), ("--approach-clearance", "-1")):
        assert cli.main(["synthesize", "--cloud", str(cloud), flag, value]) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and flag in err
