"""complete_object through the binding on pybullet-rendered one-view scenes (noise on, seeded): a box's completion
against the box's true geometry (its size from the URDF, its pose from pybullet), a mug completed by some
hypothesis, nothing ever in seen-free space, and bad input as ValueError naming the cause."""

import numpy as np
import pybullet as p
import pytest
from graspmix import CompletionKind, CompletionSettings, SpaceState, complete_object
from graspmix.perception import segment_scene
from graspmix.sim.acquisition import AcquisitionSettings, Camera, TableWorld, acquire

# 55 cm from the object's middle, 45 degrees above the table, in front of it (-y).
EYE = (0.0, -0.39, 0.44)
BOX = np.array([0.09, 0.06, 0.10])  # m, the box's size
YAW = 0.3  # rad, the box's turn about z


def _quat_z(angle):
    return (0.0, 0.0, np.sin(angle / 2), np.cos(angle / 2))


def _scene(urdf, seed, yaw=0.0):
    settings = AcquisitionSettings(cameras=[Camera(eye=EYE)], keep="scene", object_orientation=_quat_z(yaw))
    acq = acquire(urdf, noise=True, seed=seed, settings=settings)
    scene = segment_scene(acq.points, acq.viewpoints)
    obj = scene.objects[scene.select("largest")[0]]
    return acq, scene, obj


def _rotation(q):
    x, y, z, w = q
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )


def _nothing_free(c, visibility):
    assert not np.any(visibility.classify(c.points) == SpaceState.SeenFree)
    for h in c.hypotheses:
        if h["accepted"]:
            assert h["free_fraction"] <= CompletionSettings().max_free_fraction
    np.testing.assert_allclose(np.linalg.norm(c.normals, axis=1), 1.0, atol=1e-9)


@pytest.fixture(scope="module")
def box_scene(box_urdf):
    return _scene(box_urdf(tuple(BOX)), seed=5, yaw=YAW)


def test_a_box_is_mirrored_onto_its_true_back_face(box_scene):
    acq, scene, obj = box_scene
    c = complete_object(obj.points, scene.plane, scene.result.visibility)
    assert c.kind == CompletionKind.Mirror, c.hypotheses
    assert c.warning == ""
    assert len(c.points) > 100 and c.points.shape == c.normals.shape
    # The true box: its centre and axes from pybullet, its half extents from the URDF.
    R = _rotation(acq.object_pose[3:])
    local = (c.points - acq.object_pose[:3]) @ R  # rows in the box's frame
    q = np.abs(local) - BOX / 2
    sdf = np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(axis=1), 0)
    # Within 1 cm of the true box: the plane's turn is found to a few degrees at the scene's 8 mm surface tolerance
    # (segment_scene's visibility_tolerance; at 5 mm 90% lie within 6 mm).
    assert np.mean(np.abs(sdf) < 0.01) > 0.95, np.percentile(np.abs(sdf), [50, 90, 99])
    face = np.argmax(q, axis=1)
    true_normal = R[:, face].T * np.sign(local[np.arange(len(local)), face])[:, None]
    assert np.mean(np.sum(c.normals * true_normal, axis=1) > 0.7) > 0.8  # (the face of a point near an edge is a guess)
    # The back face (local +y: away from the camera) is covered by completed points.
    on_back = np.abs(local[:, 1] - BOX[1] / 2) < 0.006
    assert on_back.sum() > 0.4 * BOX[0] * BOX[2] / 0.003**2
    _nothing_free(c, scene.result.visibility)


def test_a_mug_gets_a_completion():
    _, scene, obj = _scene("objects/mug.urdf", seed=6)
    c = complete_object(obj.points, scene.plane, scene.result.visibility)
    assert c.kind != CompletionKind.None_, c.hypotheses
    assert len(c.points) > 20
    assert c.hypotheses[0]["kind"] == c.kind and c.hypotheses[0]["accepted"]
    _nothing_free(c, scene.result.visibility)
    # Every completed point lies within the mug's true bounding box (pybullet's, with 1 cm for the noise).
    with TableWorld("objects/mug.urdf", AcquisitionSettings(cameras=[Camera(eye=EYE)])) as world:
        lo, hi = (np.asarray(b) for b in p.getAABB(world.body, -1, physicsClientId=world.client))
    assert np.all(c.points > lo - 0.01) and np.all(c.points < hi + 0.01), (lo, hi, c.points.min(0), c.points.max(0))


def test_settings_keywords_and_bad_input(box_scene):
    _, scene, obj = box_scene
    vis = scene.result.visibility
    c = complete_object(obj.points, scene.plane, vis, spacing=0.005)
    cells = np.round(c.points / 0.005)  # one point per 5 mm cell (cells about the multiples of the spacing)
    assert len(np.unique(cells, axis=0)) == len(c.points)
    assert len(c.points) < len(complete_object(obj.points, scene.plane, vis).points)
    assert complete_object(obj.points, scene.plane, vis, settings=CompletionSettings(spacing=0.005)).kind == c.kind
    with pytest.raises(ValueError, match="spacing"):
        complete_object(obj.points, scene.plane, vis, spacing=0.0)
    with pytest.raises(ValueError, match="no_such"):
        complete_object(obj.points, scene.plane, vis, no_such=1)
    with pytest.raises(ValueError, match="points: no point"):
        complete_object(np.zeros((0, 3)), scene.plane, vis)
    bad = obj.points.copy()
    bad[2, 0] = np.nan
    with pytest.raises(ValueError, match="points: row 2 is not finite"):
        complete_object(bad, scene.plane, vis)
    with pytest.raises(ValueError, match="not a unit normal"):
        complete_object(obj.points, [0, 0, 0, 0], vis)
    with pytest.raises(ValueError, match="in or below the plane"):
        complete_object(obj.points, -np.asarray(scene.plane), vis)
    with pytest.raises(ValueError, match="no view"):
        complete_object(obj.points, scene.plane, type(vis)())
    with pytest.raises(ValueError, match="plane"):
        complete_object(obj.points, [0, 0, 1], vis)
