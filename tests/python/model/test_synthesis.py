"""Learning from the bundled box demonstration and synthesising grasps (issue: synthesis end to end).

Independent checks: edges and faces of the box come from its known geometry, finger-to-surface
distances and "object between the fingers" from the WSG 50's finger boxes in numpy, not from the
library's collision code.
"""

import json
import subprocess
import sys
import warnings

import graspmix
import numpy as np
import pytest
from graspmix.sim.acquisition import acquire
from scipy.spatial.transform import Rotation


def options(changes: dict) -> "graspmix.SynthesisOptions":
    """The default synthesis options with `changes` ("part.field" -> value)."""
    return graspmix.SynthesisOptions().updated(changes)


BOX_HALF = np.array([0.03, 0.05, 0.07])  # data/objects/box.urdf, resting on z = 0
FINGER_LO, FINGER_HI = np.array([-0.023, -0.015, 0.008]), np.array([0.0, 0.015, 0.081])  # data/hands/wsg50.urdf


@pytest.fixture(scope="module")
def demo():
    return graspmix.Demonstration.load(graspmix.data_path("demos", "box_wsg50.json"))


@pytest.fixture(scope="module", params=["gmm", "kde"])
def model(request):
    return graspmix.GraspModel.load(graspmix.default_model_path(request.param))


@pytest.fixture(scope="module")
def gmm():
    return graspmix.GraspModel.load(graspmix.default_model_path("gmm"))


def finger_distances(hand, grasp, points):
    """Distance (m, negative inside) from each finger's box to the nearest point, and the number of
    points in the closing region between the fingers."""
    links = hand.fk(np.asarray(grasp.T_world_wrist), grasp.grasp_joints)
    out = []
    for name in ("finger_left", "finger_right"):
        pose = links[hand.link_index(name)]
        local = Rotation.from_quat(pose[3:]).inv().apply(points - pose[:3])
        q = np.abs(local - (FINGER_LO + FINGER_HI) / 2) - (FINGER_HI - FINGER_LO) / 2
        sd = np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(axis=1), 0)
        out.append(sd.min())
    palm = links[hand.link_index("palm")]
    local = Rotation.from_quat(palm[3:]).inv().apply(points - palm[:3])
    opening = grasp.grasp_joints["finger_left_joint"]
    between = (
        (np.abs(local[:, 0]) < opening)
        & (np.abs(local[:, 1]) < 0.015)
        & (local[:, 2] > 0.0725 + FINGER_LO[2])
        & (local[:, 2] < 0.0725 + FINGER_HI[2])
    )
    return np.array(out), int(between.sum())


def test_contact_models_prefer_the_surface_types_their_links_touched(demo, gmm):
    surf, _ = gmm.features.surface(demo.cloud, remove_plane=False)
    # Edges from the box's geometry: points within 5 mm of two faces.
    local = np.abs(surf.points - [0, 0, 0.07])
    edge = ((BOX_HALF - local) < 0.005).sum(axis=1) >= 2
    hand = gmm.hand
    preference, edge_share = {}, {}
    for m in gmm.synthesizer.contact_models:
        d = graspmix.contact_data(hand, m.link, demo.T_world_wrist, demo.grasp_joints, surf.frames, surf.curvatures)
        idx, w = np.asarray(d.indices), d.weights
        edge_share[m.link_name] = (w * edge[idx]).sum() / w.sum()
        lf = m.density.feature_log_density(surf.curvatures)
        preference[m.link_name] = np.median(lf[edge]) - np.median(lf[~edge])
    # The fingers touched mostly the flat sides: they prefer faces to edges.
    for finger in ("finger_left", "finger_right"):
        assert edge_share[finger] < 0.2
        assert preference[finger] < -2.0
    # The palm, over the top face, saw relatively more of its edges, and prefers them relatively more.
    assert edge_share["palm"] > edge_share["finger_left"] + 0.1
    assert preference["palm"] > max(preference["finger_left"], preference["finger_right"]) + 2.0


def test_best_grasp_on_the_demonstration_box_reproduces_the_demonstration(demo, model):
    grasps = model.synthesize(demo.cloud, options({"segmentation.find_plane": False}), plane=[0, 0, 1, 0])
    best = np.asarray(grasps.best().T_world_wrist)
    # The box's symmetries: a half turn about its vertical axis (and mirror images, which the
    # hand's own symmetry covers). Positions along the long side of the top face are not pinned down
    # by local surface features (a flat face looks the same everywhere), so y only has to be on the box.
    # Height: the contact densities of a face's side are flat over ~2 cm (GMM's log L 36.7 at the drawn grasps' best,
    # 22.2 cm, and 37.1 at a top-down seed's, 23.3 cm; the demonstration 21.85 cm).
    assert abs(best[0] - demo.T_world_wrist[0]) < 0.01
    assert abs(best[2] - demo.T_world_wrist[2]) < 0.02
    assert abs(best[1]) < BOX_HALF[1]
    demo_rot = Rotation.from_quat(demo.T_world_wrist[3:])
    angles = [(Rotation.from_rotvec([0, 0, a]) * demo_rot).inv() * Rotation.from_quat(best[3:]) for a in (0, np.pi)]
    assert min(r.magnitude() for r in angles) < np.radians(15)


NOVEL = [
    "cube_small.urdf",
    "duck_vhacd.urdf",
    "random_urdfs/012/012.urdf",
    "random_urdfs/031/031.urdf",
    "random_urdfs/120/120.urdf",
]


@pytest.fixture(scope="module")
def novel_clouds():
    return {name: acquire(name).points for name in NOVEL}


@pytest.mark.parametrize("name", ["mug"] + NOVEL)
def test_best_grasp_on_novel_objects_is_plausible(model, novel_clouds, name):
    if name == "mug":
        grasps = model.synthesize(graspmix.data_path("mug.pcd"))  # a scene: the table is removed
        assert grasps.plane is not None and abs(grasps.plane[2]) > 0.99
    else:
        grasps = model.synthesize(novel_clouds[name], options({"segmentation.find_plane": False}), plane=[0, 0, 1, 0])
    best = grasps.best()
    # No point of the cloud inside the hand (the collision term may hold the soft charge of unseen space besides).
    points_only = graspmix.CollisionSettings(volume=False, unseen_weight=0.0)
    on_points = graspmix.CollisionExpert(model.hand, grasps.surface.points, plane=grasps.plane, settings=points_only)
    joints = [best.grasp_joints[k] for k in model.hand.joint_names]
    assert on_points.evaluate(best.T_world_wrist, joints).collision_free, "the best grasp penetrates the cloud"
    assert best.experts["collision"] > -1.0  # the soft charge at most: 0.5 cm^3 of a finger in unseen space
    assert best.experts["kinematic"] == 0.0
    dist, between = finger_distances(model.hand, best, grasps.surface.points)
    # Pads within 1.5 cm of the surface (the closing covers that travel), none more than 2 mm inside it.
    assert np.all(dist < 0.015) and np.all(dist > -0.002), f"finger pads {dist} m from the surface"
    assert between > 20, "the object is not between the fingers"


def test_same_seed_same_grasps_and_the_seed_matters(gmm):
    cloud = graspmix.data_path("mug.pcd")
    a = gmm.synthesize(cloud, options({"seed": 3, "sampling.n_samples": 50}))
    b = gmm.synthesize(cloud, options({"seed": 3, "sampling.n_samples": 50}))
    c = gmm.synthesize(cloud, options({"seed": 4, "sampling.n_samples": 50}))
    assert [g.T_world_wrist for g in a] == [g.T_world_wrist for g in b]
    assert a.best().T_world_wrist != c.best().T_world_wrist
    lls = [g.log_likelihood for g in a]
    assert lls == sorted(lls, reverse=True)


def test_result_columns_hold_each_grasps_fields(gmm):
    """SynthesisResult.columns() (what GraspModel.synthesize reads) against the per-grasp objects."""
    surface = graspmix.compute_surface_features(graspmix.io.load_points(graspmix.data_path("mug.pcd"))[0])
    collision = graspmix.CollisionExpert(gmm.hand, surface.points)
    settings = graspmix.SynthesizerSettings(sampling=graspmix.SamplingSettings(n_samples=40, n_optimise=3), seed=5)
    res = gmm.synthesizer.synthesize(surface.frames, surface.curvatures, collision, [], settings)
    cols = res.columns()
    assert len(cols["log_likelihood"]) == len(res.grasps) > 0
    for key in ("T_world_wrist", "joints", "pregrasp", "log_contact", "log_experts"):
        assert np.array_equal(
            cols[key], np.array([np.asarray(getattr(g, key)) for g in res.grasps]).reshape(cols[key].shape)
        )
    for key in ("log_likelihood", "log_collision", "log_config", "log_pregrasp", "optimised"):
        assert np.array_equal(cols[key], np.array([getattr(g, key) for g in res.grasps]), equal_nan=True)
    assert cols["optimised"].dtype == bool and 0 < cols["optimised"].sum() <= 3


def test_save_and_load_give_the_same_model(model, tmp_path, novel_clouds):
    path = tmp_path / "model.json"
    model.save(path)
    again = graspmix.GraspModel.load(path)
    cloud = novel_clouds["cube_small.urdf"]
    kw = dict(
        options=options(
            {"segmentation.find_plane": False, "seed": 1, "sampling.n_samples": 40, "sampling.n_optimise": 3}
        ),
        plane=[0, 0, 1, 0],
    )
    # To 1e-9, not bit for bit: a KDE model's save and load round trip changes some value in its last bit (the
    # grasps then differ by ~1e-17 once the clear-approach expert is on; reported in issue 13's note).
    np.testing.assert_allclose(
        [g.T_world_wrist for g in model.synthesize(cloud, **kw)],
        [g.T_world_wrist for g in again.synthesize(cloud, **kw)],
        rtol=0,
        atol=1e-9,
    )


def test_user_experts_see_batches_and_hard_ones_reject(gmm):
    batches = []

    def high_enough(wrists, joints):
        batches.append(len(wrists))
        return wrists[:, 2] > 0.05  # hard: the wrist above 5 cm

    grasps = gmm.synthesize(graspmix.data_path("mug.pcd"), experts=[graspmix.expert("high", high_enough, kind="hard")])
    assert max(batches) > 1, "the user expert must be called on batches"
    finite = [g for g in grasps if np.isfinite(g.log_likelihood)]
    assert finite and all(g.T_world_wrist[2] > 0.05 and g.experts["high"] == 0.0 for g in finite)


def test_a_synthesis_none_of_whose_grasps_passed_warns_and_says_which_expert_rejected_them(gmm):
    """A grasp set whose every grasp a hard expert rejected is not a result to execute: synthesize warns
    (NoFeasibleGraspWarning, naming the experts), n_feasible is 0; a set with grasps that passed says nothing."""
    cloud = graspmix.data_path("mug.pcd")
    fast = options({"seed": 2, "sampling.n_samples": 30, "sampling.max_sampling_rounds": 2, "sampling.n_optimise": 2})
    never = graspmix.expert("out_of_reach", lambda w, q: np.zeros(len(w), dtype=bool), kind="hard")
    with pytest.warns(graspmix.NoFeasibleGraspWarning, match="no sampled grasp passed.*out_of_reach") as caught:
        grasps = gmm.synthesize(cloud, fast, experts=[never])
    assert len(caught) == 1 and len(grasps) == 30 and grasps.n_feasible == 0
    assert not any(np.isfinite(g.log_likelihood) for g in grasps)
    assert sum(grasps.rejections().values()) == 30 and "out_of_reach" in grasps.rejections()
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fine = gmm.synthesize(cloud, fast)
    assert fine.n_feasible == sum(np.isfinite(g.log_likelihood) for g in fine) > 0
    assert np.isfinite(fine.best().log_likelihood) and sum(fine.rejections().values()) == len(fine) - fine.n_feasible


@pytest.mark.parametrize("axis", [(1.0, 0.0, 0.0), (-1.0, 0.0, 0.0)])
def test_approach_axis_expert_turns_the_best_grasp(gmm, axis):
    # The mug is grasped from the side all around: the soft expert turns the best grasp towards the axis
    # (it re-ranks and steers the candidates; it cannot outweigh every contact term), and its term is the
    # analytic log E = concentration (cos - 1).
    def approach(grasps, top=1):
        """The mean cosine between the approach axis and `axis` over the best `top` grasps."""
        dirs = Rotation.from_quat([g.T_world_wrist[3:] for g in grasps.grasps[:top]]).apply([0, 0, 1])
        return float(np.mean(dirs @ np.asarray(axis)))

    # Without the hard clear-approach expert: on the mug it passes a few dozen of the 2000 samples (the others'
    # open hands touch the cloud), too few for a soft preference to choose among.
    # Without the solid volume and the charge of unseen space either: the mug's inside is partly unseen from its four
    # cameras, and both keep a finger out of it, which the grasps the axis turns to put there (docs/one-view.md).
    # Nor contact quality's charge of small patches: the mug's handle and rim, which the axis turns grasps towards,
    # are narrow, and the charge outweighs the axis' 20 nats there (the single best then faces away).
    # Nor the floor under each link's contact term: with it, grasps with one finger far from its density (at the
    # floor) join the ten annealed, and on the mug one of them, facing away, ends best (a grasp facing the axis, log L
    # 7.3, is then not among those annealed): this test is about the axis steering the densities' own candidates.
    # Nor twice the candidates drawn: from the wider draw the free best ten already lean towards this axis (0.47).
    kw = dict(
        options=options(
            {
                "sampling.oversample": 1,
                "approach": None,
                "collision.volume": False,
                "collision.unseen_weight": 0.0,
                "contact_quality.patch_points": 0.0,
                "query.link_floor": None,
            }
        )
    )
    free = gmm.synthesize(graspmix.data_path("mug.pcd"), **kw)
    turned = gmm.synthesize(graspmix.data_path("mug.pcd"), approach_axis=axis, **kw)
    # The best ten turn towards the axis (the single best may already face it by chance of the seed).
    assert approach(turned, 10) > approach(free, 10) + 0.25 and approach(turned) > 0.4
    concentration = graspmix.AxisAlignmentSettings().concentration
    assert turned.best().experts["approach_axis"] == pytest.approx(concentration * (approach(turned) - 1), abs=1e-6)


def test_errors_are_clear(gmm, tmp_path, demo):
    with pytest.raises(ValueError, match="empty"):
        gmm.synthesize(np.zeros((0, 3)))
    with pytest.raises(ValueError, match=r"\(N, 3\)"):
        gmm.synthesize(np.zeros((10, 2)))
    with pytest.raises(ValueError):  # a handful of points: too few for features
        gmm.synthesize(np.random.default_rng(0).normal(size=(5, 3)) * 0.01, options({"segmentation.find_plane": False}))
    # A model for one hand used with another: the PR2 gripper has none of the WSG 50's links.

    path = tmp_path / "model.json"
    gmm.save(path)
    data = json.loads(path.read_text())
    data["hand"] = str(graspmix.io.pybullet_data_path() / "pr2_gripper.urdf")
    path.write_text(json.dumps(data))
    with pytest.raises(ValueError, match="another hand"):
        graspmix.GraspModel.load(path)
    path.write_text("{ not json")
    with pytest.raises(ValueError, match="not valid JSON"):
        graspmix.GraspModel.load(path)
    with pytest.raises(ValueError, match="method"):
        graspmix.learn(demo.source, method="svm")


def test_cli_synthesize_runs_with_defaults_and_fails_cleanly(tmp_path):
    out = tmp_path / "grasps.json"
    r = subprocess.run(
        [
            sys.executable,
            "-m",
            "graspmix.cli",
            "synthesize",
            "--cloud",
            str(graspmix.data_path("mug.pcd")),
            "--out",
            str(out),
            "--samples",
            "50",
            "--png",
            str(tmp_path / "g.png"),
        ],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )
    assert r.returncode == 0, r.stderr
    data = json.loads(out.read_text())
    assert data["format"] == "graspmix.grasps/1" and data["method"] == "gmm" and len(data["grasps"]) == 50
    assert set(data["timing_s"]) >= {"features", "query", "sampling", "optimisation", "total"}
    assert (tmp_path / "g.png").stat().st_size > 10_000
    bad = tmp_path / "bad.pcd"
    bad.write_text("VERSION .7\nFIELDS x y z\n")
    r = subprocess.run(
        [sys.executable, "-m", "graspmix.cli", "synthesize", "--cloud", str(bad)],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )
    assert r.returncode == 2
    assert len(r.stderr.strip().splitlines()) == 1 and "bad.pcd" in r.stderr


def test_review_regressions(gmm, tmp_path, demo):
    """Cases a review found: NaN from an expert, reserved or repeated expert names, canonical
    quaternions after annealing, paths surviving a load/save round trip, tables removed with a given plane."""
    cloud = graspmix.data_path("mug.pcd")
    nan_expert = graspmix.expert("nan", lambda w, q: np.full(len(w), np.nan), kind="log")
    with pytest.raises(ValueError, match="nan"):
        gmm.synthesize(cloud, options({"sampling.n_samples": 20}), experts=[nan_expert])
    with pytest.raises(ValueError, match="reserved"):
        gmm.synthesize(
            cloud,
            options({"sampling.n_samples": 20}),
            experts=[graspmix.expert("collision", lambda w, q: np.ones(len(w)))],
        )
    twice = [graspmix.expert("a", lambda w, q: np.ones(len(w))), graspmix.expert("a", lambda w, q: np.ones(len(w)))]
    with pytest.raises(ValueError, match="two experts"):
        gmm.synthesize(cloud, options({"sampling.n_samples": 20}), experts=twice)
    grasps = gmm.synthesize(cloud, options({"seed": 2}))
    assert all(g.T_world_wrist[6] >= 0 for g in grasps)
    # A saved, loaded and saved again model still finds its demonstration.
    first, second = tmp_path / "a" / "m.json", tmp_path / "b" / "c" / "m.json"
    first.parent.mkdir()
    second.parent.mkdir(parents=True)
    gmm.save(first)
    graspmix.GraspModel.load(first).save(second)
    assert graspmix.GraspModel.load(second).demo == str(demo.source)
    # A scene cloud with a known plane: the table points do not reach the features.
    scene = graspmix.load_cloud(str(cloud)).points
    fast = options({"segmentation.find_plane": False, "sampling.n_samples": 20, "sampling.optimise": False})
    with_plane = gmm.synthesize(scene, fast, plane=[0, 0, 1, 0])
    assert with_plane.surface.points[:, 2].min() > 0.004
    # grasps.json refers to the hand by the bundled package path.
    with_plane.save(tmp_path / "g.json")
    assert json.loads((tmp_path / "g.json").read_text())["hand"] == "package://graspmix/hands/wsg50.urdf"


def test_demo_and_learn_commands_record_and_learn_the_box_grasp(tmp_path):
    """graspmix_cli demo closes the WSG 50 on the box in pybullet: the fingers stop on its 60 mm sides
    (a joint value of half the width, to within pybullet's contact margin); learn then finds contact
    models for the links near the box."""
    from graspmix import cli

    demo, cloud, model = tmp_path / "demo.json", tmp_path / "box.pcd", tmp_path / "model.json"
    assert (
        cli.main(
            [
                "demo",
                "--wrist",
                "0,0,0.2185,1,0,0,0",
                "--pregrasp",
                "finger_left_joint=0.05",
                "--close",
                "finger_left_joint=0.0",
                "--out",
                str(demo),
                "--cloud-out",
                str(cloud),
            ]
        )
        == 0
    )
    d = graspmix.Demonstration.load(demo)
    assert d.grasp_joints["finger_left_joint"] == pytest.approx(BOX_HALF[0], abs=0.002)
    # The recorded cloud is the box's surface, in the world frame the wrist pose is given in.
    local = np.abs(d.cloud - [0, 0, 0.07])
    assert np.all(local <= BOX_HALF + 0.001)
    assert np.all(np.min(BOX_HALF - local, axis=1) < 0.001)
    assert cli.main(["learn", "--demo", str(demo), "--method", "kde", "--out", str(model)]) == 0
    learnt = graspmix.GraspModel.load(model)
    assert learnt.method == "kde" and learnt.contact_links == ["palm", "finger_left", "finger_right"]
    # The hand must touch the object: closing in the air is an error, one line from the CLI.
    assert (
        cli.main(
            [
                "demo",
                "--wrist",
                "0.5,0,0.2185,1,0,0,0",
                "--pregrasp",
                "finger_left_joint=0.05",
                "--close",
                "finger_left_joint=0.0",
                "--out",
                str(tmp_path / "air.json"),
            ]
        )
        == 2
    )
