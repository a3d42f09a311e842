"""The noise study's measures (graspmix.experiment.noise_effects): analytic values of the weight and jitter
measures, scipy's entropy, the clean acquisition's determinism, a zero-noise setting equal to the clean one,
the ranges of a one-object study, and bad input."""

import math

import numpy as np
import pytest
from graspmix.experiment import noise_effects as ne
from graspmix.experiment.noise_effects_report import table, write_outputs
from graspmix.experiment.protocol import Protocol
from graspmix.io import test_objects
from graspmix.model import GraspModel, SynthesisOptions, default_model_path
from scipy import stats as sps

# ---- measures, analytic ------------------------------------------------------------------------------------


@pytest.mark.parametrize("n", [1, 7, 1000])
def test_uniform_weights_are_all_effective(n):
    w = np.full(n, 3.0)
    assert ne.effective_number(w) == pytest.approx(n, rel=1e-12)
    assert ne.effective_fraction(w) == pytest.approx(1.0, rel=1e-12)
    assert ne.top_weight_fraction(w) == pytest.approx(math.ceil(0.1 * n) / n, rel=1e-12)
    assert np.allclose(ne.normalised_weights(np.zeros(n)), 1.0 / n)


def test_one_point_carries_everything():
    w = np.zeros(50)
    w[17] = 2.0
    assert ne.effective_number(w) == pytest.approx(1.0)
    assert ne.effective_fraction(w) == pytest.approx(1 / 50)
    assert ne.top_weight_fraction(w) == pytest.approx(1.0)
    # The same from log weights with -inf (points M_i(r) gives no mass).
    lw = np.full(50, -np.inf)
    lw[17] = -1234.5
    assert ne.effective_number(ne.normalised_weights(lw)) == pytest.approx(1.0)


def test_effective_number_is_exp_scipy_entropy_and_fraction_in_0_1():
    rng = np.random.default_rng(5)
    for _ in range(20):
        w = rng.gamma(0.3, size=rng.integers(2, 300))
        assert ne.effective_number(w) == pytest.approx(math.exp(sps.entropy(w)), rel=1e-10)
        f = ne.effective_fraction(w)
        assert 0 < f <= 1
        top = ne.top_weight_fraction(w)
        assert math.ceil(0.1 * len(w)) / len(w) - 1e-12 <= top <= 1
    # Log weights far below zero give the same normalised weights as their exponentials would.
    lw = np.log(rng.random(40)) - 800.0
    assert np.allclose(ne.normalised_weights(lw), np.exp(lw + 800) / np.exp(lw + 800).sum())


def test_jitter_angles_follow_kopickis_rule():
    s = 100.0
    k = np.array([[0.02, 0.02], [0.04, 0.0], [0.0, 0.0], [0.04, 0.03]])
    a = ne.jitter_angles(k, s)
    assert a[0] == pytest.approx(math.pi)  # isotropic: the heading is undetermined
    assert a[1] == pytest.approx(math.pi * math.exp(-s))  # a cylinder's side: no jitter
    assert a[2] == pytest.approx(math.pi)  # k1 = 0 counts as isotropic
    assert a[3] == pytest.approx(math.pi * math.exp(-s * 0.25**2))
    assert np.all(ne.jitter_angles(k, 0.0) == pytest.approx(math.pi))


def test_weighted_rms_spread_against_numpy_covariance():
    rng = np.random.default_rng(2)
    x = rng.normal(size=(200, 3)) * [0.01, 0.02, 0.03]
    assert ne.weighted_rms_spread(x) == pytest.approx(math.sqrt(np.trace(np.cov(x.T, ddof=0))), rel=1e-12)
    w = rng.random(200)
    assert ne.weighted_rms_spread(x, w) == pytest.approx(
        math.sqrt(np.trace(np.cov(x.T, aweights=w, ddof=0))), rel=1e-10
    )
    assert ne.weighted_rms_spread(np.ones((5, 3))) == pytest.approx(0.0, abs=1e-15)


def test_weighted_median_against_numpy_and_by_hand():
    rng = np.random.default_rng(9)
    x = rng.normal(size=101)
    assert ne.weighted_median(x, np.ones(101)) == np.median(x)
    # All the weight on one value, or on the upper half, moves the median there.
    w = np.zeros(101)
    w[13] = 1.0
    assert ne.weighted_median(x, w) == x[13]
    assert ne.weighted_median([1.0, 2.0, 3.0, 4.0], [0.0, 0.0, 1.0, 1.0]) == 3.0


@pytest.mark.parametrize(
    "call",
    [
        lambda: ne.effective_number([]),
        lambda: ne.effective_number([1.0, -0.5]),
        lambda: ne.effective_fraction([0.0, 0.0]),
        lambda: ne.effective_number([1.0, np.nan]),
        lambda: ne.normalised_weights([np.nan, 0.0]),
        lambda: ne.normalised_weights([]),
        lambda: ne.top_weight_fraction([1.0, 2.0], share=0.0),
        lambda: ne.top_weight_fraction([1.0, 2.0], share=1.5),
        lambda: ne.jitter_angles(np.ones((4, 1)), 100.0),
        lambda: ne.jitter_angles(np.ones((4, 2)), -1.0),
        lambda: ne.weighted_rms_spread(np.ones((3, 3)), [1.0, 1.0]),
        lambda: ne.weighted_rms_spread(np.ones(3)),
        lambda: ne.check_setting("noisy"),
        lambda: ne.weighted_median([1.0, 2.0], [1.0]),
    ],
)
def test_bad_arguments_raise_value_error(call):
    with pytest.raises(ValueError):
        call()


# ---- the pipeline on one object ---------------------------------------------------------------------------


@pytest.fixture(scope="module")
def protocol():
    # Few query samples keep the test short; the measures' definitions do not depend on them.
    return Protocol(objects=test_objects()[:1], trials=1, synthesis=SynthesisOptions().updated({"query.n_samples": 60}))


@pytest.fixture(scope="module")
def models():
    return {m: GraspModel.load(default_model_path(m)) for m in ("gmm", "kde")}


def test_clean_is_deterministic_and_zero_lateral_noise_equals_clean(protocol):
    obj = protocol.objects[0]
    a = ne.acquire_setting(protocol, obj, 0, "clean")
    b = ne.acquire_setting(protocol, obj, 0, "clean")
    np.testing.assert_array_equal(a.points, b.points)
    # Lateral only with sigma_p = 0 (and sigma_d = 0): the noise model draws but changes no depth.
    z = ne.acquire_setting(protocol, obj, 0, "lateral", stds=(0.0, 0.0))
    np.testing.assert_array_equal(z.points, a.points)
    lat = ne.acquire_setting(protocol, obj, 0, "lateral")
    assert lat.points.shape != a.points.shape or not np.array_equal(lat.points, a.points)
    with pytest.raises(ValueError, match="setting"):
        ne.acquire_setting(protocol, obj, 0, "fog")


def test_one_object_study_in_range_and_repeatable(protocol, models, tmp_path):
    settings = ("clean", "full")
    r1 = ne.run_study(protocol, models, settings)
    assert [u["setting"] for u in r1["units"]] == list(settings)
    assert all("error" not in u for u in r1["units"]), r1["units"]
    for u in r1["units"]:
        for m, mm in u["methods"].items():
            assert set(mm["links"]) == {c.link_name for c in models[m].synthesizer.contact_models}
            for v in mm["links"].values():
                assert 0 < v["effective_fraction"] <= 1
                assert v["effective_points"] == pytest.approx(v["effective_fraction"] * u["n_surface"])
                assert 0.1 - 1e-9 <= v["top10_weight"] <= 1
                assert 0 <= v["jitter_mean"] <= math.pi and 0 <= v["jitter_undetermined"] <= 1
                assert v["query_spread"] > 0 and v["query_means_spread"] >= 0
                assert 0 <= v["weighted_k1"] <= 1 and np.isfinite(v["max_log_density"])
                upper = 5 if m == "gmm" else protocol.synthesis.query.n_samples  # K_Q components; N_Q kernels
                assert 1 - 1e-9 <= v["query_components"] <= upper + 1e-9
    # The same protocol and seeds give the same numbers.
    r2 = ne.run_study(protocol, models, ("clean",))
    assert r2["units"][0] == r1["units"][0]
    s = r1["summary"]["clean"]["gmm"]["effective_fraction"]
    assert s["n"] == 1 and s["q1"] == s["median"] == s["q3"]
    demo = ne.demonstration_contacts(models["gmm"])
    assert set(demo) == set(r1["units"][0]["methods"]["gmm"]["links"])
    for r, w in demo.values():
        assert r.shape == (len(w), 2) and np.all(w > 0) and np.all(w <= 1)
    paths = write_outputs(r1, demo, tmp_path, {"test": True})
    assert all(p.stat().st_size > 0 for p in paths)
    assert "effective_fraction" in table(r1)


def test_run_study_bad_arguments(protocol, models):
    with pytest.raises(ValueError, match="models"):
        ne.run_study(protocol, {})
    with pytest.raises(ValueError, match="setting"):
        ne.run_study(protocol, models, ("clean", "rain"))
    with pytest.raises(ValueError, match="settings"):
        ne.run_study(protocol, models, "clean")
