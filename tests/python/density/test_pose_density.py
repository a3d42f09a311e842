"""PoseMixture and PoseKDE against independent numpy/scipy computations of the same densities."""

import pickle

import graspmix
import numpy as np
import pytest
from scipy.spatial.transform import Rotation
from scipy.special import ive, logsumexp
from scipy.stats import multivariate_normal


def contact_like_data(rng, n=400):
    """Two surface types (features near [0.03, 0] and [0.003, 0.001]) with different link poses."""
    half = n // 2
    rot_a = Rotation.from_rotvec([0, 0, 0.4]) * Rotation.from_rotvec(rng.normal(scale=0.08, size=(half, 3)))
    rot_b = Rotation.from_rotvec([2.9, 0.3, 0.0]) * Rotation.from_rotvec(rng.normal(scale=0.08, size=(n - half, 3)))
    pos = np.vstack([rng.normal([0, 0, 0.02], 0.003, (half, 3)), rng.normal([0.01, 0.0, 0.03], 0.003, (n - half, 3))])
    quat = np.vstack([rot_a.as_quat(), rot_b.as_quat()])
    feats = np.vstack([rng.normal([0.03, 0.0], 0.003, (half, 2)), rng.normal([0.003, 0.001], 0.001, (n - half, 2))])
    weights = rng.uniform(0.2, 1.0, n)
    return np.hstack([pos, quat]), feats, weights


def test_pose_mixture_density_is_the_conditioned_gaussian_in_log_coordinates(rng):
    poses, feats, w = contact_like_data(rng)
    pm = graspmix.PoseMixture(n_components=2, seed=0).fit(poses, feats, w)
    assert pm.kind == "gmm" and pm.n_kernels == 2 and pm.n_features == 2
    joint = pm.joint
    ref = Rotation.from_quat(pm.reference)
    q_poses = rng.normal(size=(40, 7)) * 0.01 + poses[rng.integers(len(poses), size=40)]
    q_feats = feats[rng.integers(len(feats), size=40)] + rng.normal(scale=0.001, size=(40, 2))
    # Independent computation: omega = rotvec(ref^-1 q) / 2 with scipy, then the partitioned Gaussian.
    omega = (ref.inv() * Rotation.from_quat(q_poses[:, 3:])).as_rotvec() / 2
    U = np.hstack([q_poses[:, :3], omega])
    expected = []
    for u, r in zip(U, q_feats):
        terms, norms = [], []
        for k in range(2):
            mu, S = joint.means_[k], joint.covariances_[k]
            A = S[:6, 6:] @ np.linalg.inv(S[6:, 6:])
            lw = np.log(joint.weights_[k]) + multivariate_normal(mu[6:], S[6:, 6:]).logpdf(r)
            norms.append(lw)
            terms.append(lw + multivariate_normal(mu[:6] + A @ (r - mu[6:]), S[:6, :6] - A @ S[6:, :6]).logpdf(u))
        a = np.linalg.norm(u[3:])
        expected.append(logsumexp(terms) - logsumexp(norms) - 2 * np.log(np.sin(a) / a))
    np.testing.assert_allclose(pm.log_density(q_poses, q_feats), expected, atol=1e-8)
    np.testing.assert_allclose(
        pm.feature_log_density(q_feats), joint.marginal([6, 7]).score_samples(q_feats), atol=1e-10
    )


def test_pose_kde_density_matches_brute_force(rng):
    poses, feats, w = contact_like_data(rng, 60)
    kde = graspmix.PoseKDE(position_bandwidth=0.004, orientation_bandwidth=0.2, feature_bandwidth=[0.002, 0.001])
    kde.fit(poses, feats, w)
    assert kde.kind == "kde" and kde.n_kernels == 60
    q_poses = poses[:10] + rng.normal(scale=0.002, size=(10, 7))
    q_feats = feats[:10]
    kappa = 4 / 0.2**2
    log_c = np.log(kappa) - 2 * np.log(2 * np.pi) - (np.log(ive(1, kappa)) + kappa)
    wn = w / w.sum()
    qk = poses[:, 3:] / np.linalg.norm(poses[:, 3:], axis=1, keepdims=True)
    expected = []
    for p, r in zip(q_poses, q_feats):
        q = p[3:] / np.linalg.norm(p[3:])
        lr = np.log(wn) + multivariate_normal.logpdf(feats - r, cov=np.diag([0.002**2, 0.001**2]))
        lp = multivariate_normal.logpdf(poses[:, :3] - p[:3], cov=0.004**2 * np.eye(3))
        lq = log_c + np.log(np.exp(kappa * (qk @ q)) + np.exp(-kappa * (qk @ q)))
        expected.append(logsumexp(lr + lp + lq) - logsumexp(lr))
    np.testing.assert_allclose(kde.log_density(q_poses, q_feats), expected, atol=1e-8)


@pytest.mark.parametrize(
    "make", [lambda: graspmix.PoseMixture(n_components=2, seed=1), lambda: graspmix.PoseKDE(feature_bandwidth=0.002)]
)
def test_conditioning_on_features_selects_the_demonstrated_poses(rng, make):
    poses, feats, w = contact_like_data(rng)
    d = make().fit(poses, feats, w)
    for centre, expected_z, expected_rot in [([0.03, 0.0], 0.02, [0, 0, 0.4]), ([0.003, 0.001], 0.03, [2.9, 0.3, 0])]:
        s = d.sample(2000, features=centre, seed=2)
        assert s[:, 2].mean() == pytest.approx(expected_z, abs=0.002)
        mean_rot = Rotation.from_quat(s[:, 3:]).mean()
        assert (mean_rot.inv() * Rotation.from_rotvec(expected_rot)).magnitude() < 0.05
    # q and -q are the same rotation.
    flipped = poses.copy()
    flipped[:, 3:] *= -1
    np.testing.assert_allclose(d.log_density(poses, feats), d.log_density(flipped, feats), atol=1e-9)
    # Same seed, same samples; features for every row or one for all.
    np.testing.assert_array_equal(
        d.sample(5, features=feats[0], seed=3), d.sample(5, features=np.tile(feats[0], (5, 1)), seed=3)
    )


def test_pose_mixture_without_features_and_pickle(rng):
    poses, _, _ = contact_like_data(rng)
    pm = graspmix.PoseMixture(n_components=5, seed=0).fit(poses)
    assert pm.n_features == 0
    lp = pm.log_density(poses)
    assert np.all(np.isfinite(lp))
    clone = pickle.loads(pickle.dumps(pm))
    np.testing.assert_allclose(clone.log_density(poses), lp, rtol=1e-12)
    rebuilt = graspmix.PoseMixture.from_parameters(pm.reference, pm.joint)
    np.testing.assert_allclose(rebuilt.log_density(poses), lp, rtol=1e-12)


@pytest.mark.parametrize("make", [graspmix.PoseMixture, graspmix.PoseKDE])
def test_bad_input_is_a_value_error(rng, make):
    poses, feats, w = contact_like_data(rng, 40)
    d = make()
    with pytest.raises(ValueError, match=r"expected shape \(N, 7\)"):
        d.fit(poses[:, :6], feats)
    with pytest.raises(ValueError, match="weight 3"):
        bad = w.copy()
        bad[3] = 0
        d.fit(poses, feats, bad)
    with pytest.raises(ValueError, match="feature rows"):
        d.fit(poses, feats[:-1])
    d.fit(poses, feats, w)
    with pytest.raises(ValueError, match="features are required"):
        d.log_density(poses)
    with pytest.raises(ValueError, match="expected 2 values, got 3"):
        d.sample(3, features=[0.1, 0.2, 0.3])
    with pytest.raises(ValueError, match="NaN"):
        d.log_density(np.full((1, 7), np.nan), feats[:1])
    with pytest.raises(ValueError, match="bandwidth"):
        graspmix.PoseKDE(position_bandwidth=-1.0)
