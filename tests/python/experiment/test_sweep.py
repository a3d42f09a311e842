"""The protocol's noise parts and K_Q, and the settings sweep: variants, learnt models, sweep.json, bad input."""

import json

import graspmix
import numpy as np
import pytest
from graspmix import cli
from graspmix import experiment as ex
from graspmix.experiment.sweep import DEFAULTS, Sweep, run_sweep
from graspmix.sim.acquisition import acquire


def test_the_noise_parts_reach_the_acquisition():
    """sigma_p = 0 leaves the depth noise alone (every pixel keeps its depth plus N(0, sigma_d)); sigma_d = 0
    the lateral shift alone (every noisy depth is a depth of the clean image)."""
    clean = acquire("cube_small.urdf", noise=False, seed=5)
    depth_only = ex.Protocol(objects=["cube_small.urdf"], pixel_noise_std=0.0).acquisition_settings()
    lateral_only = ex.Protocol(objects=["cube_small.urdf"], depth_noise_std=0.0).acquisition_settings()
    d = acquire("cube_small.urdf", noise=True, seed=5, settings=depth_only)
    lat = acquire("cube_small.urdf", noise=True, seed=5, settings=lateral_only)
    for c, dn, ln in zip(clean.depth_images, d.depth_images, lat.depth_images):
        finite = np.isfinite(c)
        assert np.all(np.isfinite(dn) == finite)
        residual = dn[finite] - c[finite]
        assert residual.std() == pytest.approx(depth_only.depth_noise_std, rel=0.05)
        assert abs(residual.mean()) < 1e-4
        ok = np.isfinite(ln)
        assert np.all(np.isin(ln[ok], c[np.isfinite(c)]))
        assert np.any(ln[ok] != c[ok])  # the shift moved some edges


def test_protocol_rejects_bad_noise_and_query_components():
    for kw, match in (
        (dict(pixel_noise_std=-1.0), "pixel_noise_std"),
        (dict(depth_noise_std=float("nan")), "depth_noise_std"),
    ):
        with pytest.raises(ValueError, match=match):
            ex.Protocol(objects=["cube_small.urdf"], **kw)
    for changes in ({"query.n_components": 0}, {"query.n_components": 600, "query.n_samples": 500}):
        with pytest.raises(ValueError, match="query.n_components"):
            graspmix.SynthesisOptions().updated(changes)


def test_query_components_change_gmm_and_not_kde():
    """K_Q shapes GMM's query densities; KDE's have no components, so its grasps stay the same."""
    cloud = graspmix.data_path("mug.pcd")
    base = graspmix.SynthesisOptions().updated({"sampling.n_samples": 40, "sampling.n_optimise": 2, "seed": 3})
    for method, same in (("gmm", False), ("kde", True)):
        model = graspmix.GraspModel.load(graspmix.default_model_path(method))
        a = model.synthesize(cloud, base.updated({"query.n_components": 1})).grasps
        b = model.synthesize(cloud, base.updated({"query.n_components": 8})).grasps
        poses = [np.array([g.T_world_wrist for g in x]) for x in (a, b)]
        assert (poses[0].shape == poses[1].shape and np.allclose(*poses)) == same, method


def base_protocol(**kw):
    synthesis = ex.Protocol.preset("paper").synthesis.updated({"sampling.n_samples": 30})
    p = dict(objects=["cube_small.urdf"], trials=1, conditions=["C"], methods=["gmm"], synthesis=synthesis)
    p.update(kw)
    return ex.Protocol(**p)


def test_sweep_variants_and_bad_input():
    s = Sweep(base_protocol(methods=["gmm", "kde"]), {"n_components": [1, 2, 3], "kde_position_bandwidth": [0.01]})
    assert s.variants() == [
        (DEFAULTS, None),
        ("n_components", 1),
        ("n_components", 3),
        ("kde_position_bandwidth", 0.01),
    ]
    for params, match in (
        ({"colour": [1]}, "unknown sweep parameter"),
        ({"n_components": []}, "no values"),
        ({"n_components": [0]}, "n_components"),
        ({"kde_feature_bandwidth": [-0.1]}, "kde_feature_bandwidth"),
        ({"query_components": [1000]}, "query.n_components"),
        ({"pixel_noise_std": [float("nan")]}, "pixel_noise_std"),
    ):
        with pytest.raises(ValueError, match=match):
            Sweep(base_protocol(methods=["gmm", "kde"]), params)
    with pytest.raises(ValueError, match="belongs to kde"):
        Sweep(base_protocol(), {"kde_position_bandwidth": [0.01]})
    with pytest.raises(ValueError, match="at least one parameter"):
        Sweep(base_protocol(), {})
    with pytest.raises(ValueError, match="give no models"):
        Sweep(base_protocol(models={"gmm": str(graspmix.default_model_path("gmm"))}), {"n_components": [3]})


def test_a_small_sweep_learns_models_runs_each_value_and_summarises(tmp_path):
    s = Sweep(base_protocol(), {"n_components": [1, 2], "query_components": [2]})
    res = run_sweep(s, tmp_path / "sw", jobs=1, progress=False)
    assert sorted(p.name for p in (tmp_path / "sw").iterdir() if p.is_dir()) == [
        DEFAULTS, "models", "n_components=1", "query_components=2"
    ]  # fmt: skip
    learnt = graspmix.GraspModel.load(tmp_path / "sw" / "models" / "gmm_n_components=1.json")
    assert learnt.learn_settings["n_components"] == 1
    proto = json.loads((tmp_path / "sw" / "query_components=2" / ex.PROTOCOL_NAME).read_text())["protocol"]
    assert proto["synthesis"]["query"]["n_components"] == 2 and proto["methods"] == ["gmm"]
    entry = res["parameters"]["n_components"]
    assert entry["default"] == 2 and [p["value"] for p in entry["methods"]["gmm"]["points"]] == [1, 2]
    for p in entry["methods"]["gmm"]["points"]:
        c = p["conditions"]["C"]
        assert c["attempts"] == 1 and c["rate"] in (0.0, 1.0) and c["ci_low"] <= c["rate"] <= c["ci_high"]
    assert entry["methods"]["gmm"]["best"] in (1, 2) and "best_shared" not in entry
    assert json.loads((tmp_path / "sw" / "sweep.json").read_text()) == res
    assert (tmp_path / "sw" / "sweep.png").stat().st_size > 0
    again = run_sweep(s, tmp_path / "sw", jobs=1, progress=False)  # resumes: nothing left to run
    assert again == res


@pytest.mark.parametrize(
    "argv, match",
    [
        (["--vary", "colour=1,2"], "expected NAME=V1,V2"),
        (["--vary", "n_components=a"], "expected int values"),
        ([], "at least one --vary"),
        (["--vary", "n_components=1", "--vary", "n_components=2"], "given twice"),
        (["--vary", "kde_position_bandwidth=0.01", "--methods", "gmm"], "belongs to kde"),
    ],
)
def test_sweep_cli_bad_input(tmp_path, capsys, argv, match):
    assert cli.main(["sweep", "--out", str(tmp_path / "s"), "--preset", "smoke", *argv]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert match in err[-1]


# ---- comparisons across runs -------------------------------------------------------------------


def synthetic_rows(success: np.ndarray, condition="A", method="gmm", reasons=None):
    """Rows of a (trials, objects) success matrix."""
    rows = []
    for t in range(success.shape[0]):
        for o in range(success.shape[1]):
            s = int(success[t, o])
            reason = (reasons or {}).get((t, o), "success" if s else "not held")
            rows.append(dict(object=f"o{o}", trial=t, condition=condition, method=method, success=s, reason=reason))
    return rows


def test_differences_are_the_paired_tests_over_trials_and_objects():
    from graspmix.experiment.compare import cell, difference, outcome_shares
    from scipy import stats as sps

    rng = np.random.default_rng(4)
    a_m = (rng.random((6, 9)) < 0.8).astype(int)
    b_m = (rng.random((6, 9)) < 0.6).astype(int)
    a = cell(synthetic_rows(a_m), "A", "gmm")
    b = cell(synthetic_rows(b_m, reasons={(0, 0): "start in collision"}), "A", "gmm")
    d = difference(a, b)
    assert d.difference == pytest.approx(a_m.mean() - b_m.mean())
    assert d.trials["p"] == pytest.approx(sps.ttest_rel(a_m.mean(1), b_m.mean(1)).pvalue)
    assert d.objects["p"] == pytest.approx(sps.ttest_rel(a_m.mean(0), b_m.mean(0)).pvalue)
    shares = outcome_shares(b)
    assert sum(shares.values()) == pytest.approx(1.0) and shares["success"] == pytest.approx(b_m.mean())
    assert "start in collision" in shares or b_m[0, 0] == 1
    with pytest.raises(ValueError, match="not paired"):
        difference(a, cell(synthetic_rows(b_m[:, :5]), "A", "gmm"))
    with pytest.raises(ValueError, match="attempts missing"):
        cell(synthetic_rows(a_m)[1:], "A", "gmm")
    with pytest.raises(ValueError, match="no attempts"):
        cell(synthetic_rows(a_m), "B", "gmm")


def test_gmm_reg_covar_bounds_every_variance_of_the_contact_mixtures(tmp_path):
    demo = str(graspmix.data_path("demos", "box_wsg50.json"))
    for reg in (1e-6, 2.5e-5):
        model = graspmix.GraspModel.learn(demo, "gmm", gmm_reg_covar=reg)
        model.save(tmp_path / "m.json")
        saved = json.loads((tmp_path / "m.json").read_text())
        assert saved["learn_settings"]["gmm_reg_covar"] == reg
        for cm in saved["types"][0]["contact_models"]:
            for cov in cm["density"]["covariances"]:
                assert np.min(np.diag(np.asarray(cov))) >= reg * (1 - 1e-9)
    with pytest.raises(ValueError, match="gmm_reg_covar"):
        graspmix.GraspModel.learn(demo, "gmm", gmm_reg_covar=0.0)


def test_outcome_change_is_the_exact_mcnemar_test():
    from graspmix.experiment.compare import cell, outcome_change
    from scipy.stats import binomtest

    ok = np.ones((2, 10), dtype=int)
    a_reasons = {(0, o): "start in collision" for o in range(7)}  # 7 in a
    b_reasons = {(0, 0): "start in collision", (1, 3): "start in collision"}  # 1 shared, 1 only in b
    a = cell(synthetic_rows(ok * 0, method="kde", reasons=a_reasons), "A", "kde")
    b = cell(synthetic_rows(ok * 0, method="kde", reasons=b_reasons), "A", "kde")
    ch = outcome_change(a, b, "start in collision")
    assert (ch.only_a, ch.only_b) == (6, 1)
    assert (ch.share_a, ch.share_b) == (pytest.approx(7 / 20), pytest.approx(2 / 20))
    assert ch.p == pytest.approx(binomtest(6, 7, 0.5).pvalue)
    assert outcome_change(a, a, "start in collision").p == 1.0
