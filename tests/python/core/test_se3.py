"""SE(3) helpers against scipy's Rotation and homogeneous matrices."""

import graspmix
import numpy as np
import pytest
from scipy.spatial.transform import Rotation


def random_poses(rng, n):
    q = Rotation.random(n, random_state=rng.integers(1 << 31)).as_quat()
    return np.hstack([rng.normal(size=(n, 3)), q])


def to_matrix(poses):
    M = np.tile(np.eye(4), (len(poses), 1, 1))
    M[:, :3, :3] = Rotation.from_quat(poses[:, 3:]).as_matrix()
    M[:, :3, 3] = poses[:, :3]
    return M


def test_log_is_half_the_rotation_vector(rng):
    q = Rotation.random(200, random_state=1).as_quat()
    rotvec = Rotation.from_quat(q).as_rotvec()  # scipy's rotvec: angle * axis, angle in [0, pi]
    np.testing.assert_allclose(graspmix.quat_log(q), rotvec / 2, atol=1e-12)
    np.testing.assert_allclose(graspmix.quat_log(-q), rotvec / 2, atol=1e-12)


def test_exp_inverts_log(rng):
    q = Rotation.random(200, random_state=2).as_quat()
    q[q[:, 3] < 0] *= -1
    np.testing.assert_allclose(graspmix.quat_exp(graspmix.quat_log(q)), q, atol=1e-12)
    np.testing.assert_allclose(graspmix.quat_exp(np.zeros(3)), [0, 0, 0, 1])
    assert graspmix.quat_log([0, 0, 0, 1]).shape == (3,)


def test_compose_and_inverse_match_matrices(rng):
    a, b = random_poses(rng, 50), random_poses(rng, 50)
    ab = graspmix.pose_multiply(a, b)
    np.testing.assert_allclose(to_matrix(ab), to_matrix(a) @ to_matrix(b), atol=1e-12)
    np.testing.assert_allclose(to_matrix(graspmix.pose_inverse(a)), np.linalg.inv(to_matrix(a)), atol=1e-12)
    assert np.all(ab[:, 6] >= 0)
    # A single pose broadcasts over a batch, and a 1-D pose gives a 1-D result.
    broadcast = graspmix.pose_multiply(a[0], b)
    np.testing.assert_allclose(to_matrix(broadcast), to_matrix(a[:1]) @ to_matrix(b), atol=1e-12)
    assert graspmix.pose_inverse(a[0]).shape == (7,)


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: graspmix.pose_inverse(np.zeros((3, 6))), "expected shape (N, 7)"),
        (lambda: graspmix.pose_inverse(np.zeros((2, 7))), "row 0"),
        (lambda: graspmix.quat_exp(np.full((1, 3), np.nan)), "NaN"),
        (
            lambda: graspmix.pose_multiply(
                np.tile([0, 0, 0, 0, 0, 0, 1.0], (2, 1)), np.tile([0, 0, 0, 0, 0, 0, 1.0], (3, 1))
            ),
            "differ",
        ),
        (lambda: graspmix.quat_log("abc"), "array of numbers"),
    ],
)
def test_bad_input_is_a_value_error(call, message):
    with pytest.raises(ValueError, match=message.replace("(", r"\(").replace(")", r"\)")):
        call()


@pytest.mark.parametrize("scale", [1e3, 1e6, 1e20, 1e150, 1e300])
def test_exp_of_long_rotation_vectors_is_a_unit_quaternion_and_scipys_rotation(scale):
    """The exp map is periodic in the angle: a long rotation vector is a rotation by its length modulo 2 pi
    (half-angle convention: quat_exp(w) is scipy's rotation by the vector 2 w)."""
    rng = np.random.default_rng(3)
    w = rng.normal(size=(20, 3))
    w = w / np.linalg.norm(w, axis=1, keepdims=True) * scale * rng.uniform(0.5, 1.0, (20, 1))
    q = graspmix.quat_exp(w)
    assert np.all(np.isfinite(q)) and np.allclose(np.linalg.norm(q, axis=1), 1.0, atol=1e-12)
    if scale <= 1e6:  # beyond, one ulp of the angle exceeds 2 pi: the rotation itself is noise
        ref = Rotation.from_rotvec(2.0 * w).as_quat()
        assert np.allclose(np.abs(np.sum(q * ref, axis=1)), 1.0, atol=1e-8)
