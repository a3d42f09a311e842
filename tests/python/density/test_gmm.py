"""GaussianMixture against scikit-learn and scipy on the same data."""

import pickle

import graspmix
import numpy as np
import pytest
from scipy.stats import multivariate_normal
from sklearn.mixture import GaussianMixture as SkGaussianMixture


def blobs(rng, n, d=4, k=3):
    centres = rng.normal(scale=4.0, size=(k, d))
    labels = rng.integers(k, size=n)
    A = rng.normal(size=(k, d, d)) * 0.5
    return centres[labels] + np.einsum("nij,nj->ni", A[labels], rng.normal(size=(n, d)))


def random_mixture(rng, K, d):
    w = rng.uniform(0.2, 1.0, K)
    mu = rng.normal(scale=2.0, size=(K, d))
    A = rng.normal(size=(K, d, d))
    cov = A @ A.transpose(0, 2, 1) / d + 0.3 * np.eye(d)
    return graspmix.GaussianMixture.from_parameters(w, mu, cov), w / w.sum(), mu, cov


def mixture_logpdf(x, w, mu, cov):
    return np.log(sum(w[k] * multivariate_normal(mu[k], cov[k]).pdf(x) for k in range(len(w))))


@pytest.mark.parametrize("K", [2, 3])
def test_fit_matches_scikit_learn(rng, K):
    X = blobs(rng, 2000, d=4, k=K)
    ours = graspmix.GaussianMixture(n_components=K, n_init=3, seed=0, tol=1e-6, max_iter=500).fit(X)
    ref = SkGaussianMixture(
        n_components=K, covariance_type="full", n_init=3, random_state=0, tol=1e-6, max_iter=500
    ).fit(X)
    assert ours.converged_
    assert ours.score(X) == pytest.approx(ref.score(X), abs=1e-4)
    # Same optimum: match the components up to order.
    order = [int(np.argmin(np.linalg.norm(ref.means_ - m, axis=1))) for m in ours.means_]
    np.testing.assert_allclose(ours.means_, ref.means_[order], atol=1e-3)
    np.testing.assert_allclose(ours.weights_, ref.weights_[order], atol=1e-4)
    np.testing.assert_allclose(ours.covariances_, ref.covariances_[order], atol=1e-3)
    np.testing.assert_allclose(ours.predict_proba(X)[:, 0], ref.predict_proba(X)[:, order[0]], atol=1e-3)


def test_score_samples_match_scipy(rng):
    gm, w, mu, cov = random_mixture(rng, 3, 5)
    X = rng.normal(size=(50, 5))
    np.testing.assert_allclose(gm.score_samples(X), mixture_logpdf(X, w, mu, cov), rtol=1e-10)
    assert gm.score(X) == pytest.approx(mixture_logpdf(X, w, mu, cov).mean(), rel=1e-10)


def test_lower_bound_never_decreases(rng):
    X = blobs(rng, 1500, d=3, k=4)
    gm = graspmix.GaussianMixture(n_components=4, reg_covar=0.0, tol=0.0, max_iter=80, seed=3).fit(X)
    h = np.array(gm.lower_bound_history_)
    assert len(h) == 80
    assert np.all(np.diff(h) >= -1e-9)
    assert gm.lower_bound_ == h[-1]


def test_weights_equal_repeated_samples(rng):
    X = blobs(rng, 300, d=3, k=2)
    counts = rng.integers(1, 4, size=len(X))
    init = X[[0, 1]]
    a = graspmix.GaussianMixture(n_components=2, seed=0).fit(X, weights=counts.astype(float), means_init=init)
    b = graspmix.GaussianMixture(n_components=2, seed=0).fit(np.repeat(X, counts, axis=0), means_init=init)
    assert a.n_iter_ == b.n_iter_
    np.testing.assert_allclose(a.means_, b.means_, atol=1e-10)
    np.testing.assert_allclose(a.covariances_, b.covariances_, atol=1e-10)
    np.testing.assert_allclose(a.weights_, b.weights_, atol=1e-12)


def test_condition_matches_joint_gaussian_algebra(rng):
    gm, w, mu, cov = random_mixture(rng, 3, 5)
    given, rest = [3, 0], [1, 2, 4]
    r = np.array([0.4, -1.0])
    cond = gm.condition(given, r)
    # Brute force with numpy: per component, the textbook partitioned-Gaussian formulas...
    for k in range(3):
        S = cov[k]
        Suu, Sur, Srr = S[np.ix_(rest, rest)], S[np.ix_(rest, given)], S[np.ix_(given, given)]
        m = mu[k][rest] + Sur @ np.linalg.solve(Srr, r - mu[k][given])
        C = Suu - Sur @ np.linalg.solve(Srr, Sur.T)
        j = int(np.argmin(np.linalg.norm(cond.means_ - m, axis=1)))
        np.testing.assert_allclose(cond.means_[j], m, atol=1e-10)
        np.testing.assert_allclose(cond.covariances_[j], C, atol=1e-10)
    # ...and the whole conditional density is the joint over the marginal, pointwise.
    U = rng.normal(size=(30, 3))
    X = np.zeros((30, 5))
    X[:, rest], X[:, given] = U, r
    marg = mixture_logpdf(r, w, [m[given] for m in mu], [c[np.ix_(given, given)] for c in cov])
    np.testing.assert_allclose(cond.score_samples(U), mixture_logpdf(X, w, mu, cov) - marg, atol=1e-9)
    np.testing.assert_allclose(gm.marginal(given).score_samples(r[None]), [marg], atol=1e-10)


def test_sample_moments(rng):
    gm, w, mu, cov = random_mixture(rng, 2, 3)
    S = gm.sample(200_000, seed=4)
    mean = w @ mu
    second = sum(w[k] * (cov[k] + np.outer(mu[k], mu[k])) for k in range(2))
    np.testing.assert_allclose(S.mean(0), mean, atol=0.03)
    np.testing.assert_allclose(np.cov(S.T, bias=True), second - np.outer(mean, mean), atol=0.08)
    np.testing.assert_array_equal(gm.sample(10, seed=4), S[:10])


def test_same_seed_same_fit_and_pickle(rng):
    X = blobs(rng, 500, d=3, k=3)
    a = graspmix.GaussianMixture(n_components=3, seed=9).fit(X)
    b = graspmix.GaussianMixture(n_components=3, seed=9).fit(X)
    np.testing.assert_array_equal(a.means_, b.means_)
    c = pickle.loads(pickle.dumps(a))
    np.testing.assert_allclose(c.score_samples(X), a.score_samples(X), rtol=1e-13)


@pytest.mark.parametrize(
    "fit, message",
    [
        (lambda g: g.fit(np.zeros((1, 2))), "fewer than"),
        (lambda g: g.fit(np.array([[0.0, 0.0]] * 5 + [[1.0, 1.0]] * 5)), "distinct"),
        (lambda g: g.fit(np.array([[0.0, np.nan]] * 5)), "NaN"),
        (lambda g: g.fit(np.zeros(5)), "2-D"),
        (lambda g: g.fit(np.random.default_rng(0).normal(size=(9, 2)), weights=-np.ones(9)), "positive"),
        (lambda g: g.fit(np.random.default_rng(0).normal(size=(9, 2)), weights=np.ones(8)), "8 entries"),
    ],
)
def test_bad_input_is_a_value_error(fit, message):
    with pytest.raises(ValueError, match=message):
        fit(graspmix.GaussianMixture(n_components=3))


def test_bad_settings_and_queries_are_value_errors(rng):
    with pytest.raises(ValueError, match="n_components"):
        graspmix.GaussianMixture(n_components=0)
    with pytest.raises(ValueError, match="seed"):
        graspmix.GaussianMixture(seed=-1)
    gm, *_ = random_mixture(rng, 2, 3)
    with pytest.raises(ValueError, match="3 dimensions"):
        gm.score_samples(np.zeros((4, 2)))
    with pytest.raises(ValueError, match="outside"):
        gm.condition([5], [0.0])
    with pytest.raises(ValueError, match="values"):
        gm.condition([0, 1], [0.0])


def test_an_unfitted_mixture_pickles_as_scikit_learns_does():
    """scikit-learn pickles an unfitted estimator with its parameters; so does graspmix, and it stays unfitted."""
    ours = graspmix.GaussianMixture(n_components=4, max_iter=7)
    back = pickle.loads(pickle.dumps(ours))
    theirs = pickle.loads(pickle.dumps(SkGaussianMixture(n_components=4, max_iter=7)))
    assert back.settings == ours.settings and (back.settings.n_components, theirs.n_components) == (4, 4)
    assert "not fitted" in repr(back)
    with pytest.raises(ValueError, match="fit"):
        back.sample(3)


@pytest.mark.parametrize("n", [10**12, 2**31 - 1, -1, 1.5, "3", True])
def test_sample_counts_are_bounded_before_memory_is_taken(n):
    gm = graspmix.GaussianMixture(n_components=1, seed=0)
    gm.fit(np.random.default_rng(0).normal(size=(40, 2)))
    # The bundled models' contact densities: a fitted PoseMixture (GMM) and a PoseKDE.
    densities = [
        graspmix.GraspModel.load(graspmix.default_model_path(m)).synthesizer.contact_models[0].density
        for m in ("gmm", "kde")
    ]
    samplers = [gm.sample] + [lambda k, d=d: d.sample(k, np.zeros(d.n_features)) for d in densities]
    for sample in samplers:
        with pytest.raises(ValueError, match=r"n must be an integer in \[0, 10000000\]") as e:
            sample(n)
        assert "\n" not in str(e.value)


def test_a_setting_of_the_wrong_type_names_what_it_takes():
    for value in ("3", 2**70, 1.5):
        with pytest.raises(ValueError, match="n_components.*expected an integer") as e:
            graspmix.GaussianMixture(n_components=value)
        assert "\n" not in str(e.value) and "SupportsInt" not in str(e.value)
