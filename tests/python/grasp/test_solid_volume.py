"""The solid volume of a completed object (solid_volume) on a box rendered by pybullet from one camera, against the
renderer's ground truth (the box's pose and size), and the collision expert's volume term (CollisionSettings.volume):
a finger inside the completed box, near none of its points, is charged; one clear of it is not."""

import numpy as np
import pytest
from graspmix import _core
from graspmix.perception import segment_scene
from graspmix.sim.acquisition import AcquisitionSettings, Camera, acquire

EYE = (0.5, 0.1, 0.45)  # sees the box's +x face and its top
SIZE = (0.06, 0.06, 0.10)  # m
FINGER = """<robot name="finger"><link name="finger"><collision><geometry><box size="0.02 0.04 0.06"/></geometry>
</collision></link></robot>"""


@pytest.fixture(scope="module")
def completed(box_urdf):
    acq = acquire(box_urdf(SIZE), seed=0, settings=AcquisitionSettings(cameras=[Camera(eye=EYE)], keep="scene"))
    scene = segment_scene(acq.points, acq.viewpoints).complete()
    return scene, np.asarray(acq.object_pose[:3])


def test_the_completed_box_is_solid_inside_and_free_outside(completed):
    scene, c = completed
    vol = _core.solid_volume(scene.solid_points(), scene.plane)
    occupied = 1
    half = np.array(SIZE) / 2
    rng = np.random.default_rng(0)
    p = c + rng.uniform(-1.5, 1.5, (4000, 3)) * half
    inside_by = -np.max(np.abs(p - c) - half, axis=1)  # the box's exact signed depth
    state = vol.state(p)
    margin = np.sqrt(3) * vol.resolution + 0.003  # a cell's diagonal and the completion's 6 mm gap, halved
    deep, out = inside_by > margin, inside_by < -margin
    assert deep.sum() > 200 and out.sum() > 1000
    assert np.mean(state[deep] == occupied) > 0.97  # the unseen half included: the completion's
    assert np.all(state[out] != occupied)


@pytest.fixture(scope="module")
def finger(tmp_path_factory):
    urdf = tmp_path_factory.mktemp("finger") / "finger.urdf"
    urdf.write_text(FINGER)
    return _core.Hand.from_urdf(str(urdf))


def test_a_finger_inside_the_completed_box_is_charged_only_with_the_volume(completed, finger):
    scene, c = completed
    hand = finger
    points = scene.solid_points()
    # The box's middle: every observed or completed point 5 mm or more outside the finger (2 x 4 x 6 cm).
    assert np.all(np.max(np.abs(points - c) - [0.01, 0.02, 0.03], axis=1) > 0.005)
    pose = np.array([[*c, 0, 0, 0, 1], [*(c + [0.1, 0, 0]), 0, 0, 0, 1]])
    q = np.zeros((1, 0))
    plain = _core.CollisionExpert(hand, points, plane=scene.plane, settings=_core.CollisionSettings(volume=False))
    volume = _core.CollisionExpert(hand, points, plane=scene.plane)  # the volume is on by default
    assert plain.volume is None and volume.volume is not None
    assert plain.evaluate_batch(pose, q).collision_free.tolist() == [True, True]
    r = volume.evaluate_batch(pose, q)
    assert r.collision_free.tolist() == [False, True]
    assert 0 < r.total_depth[0] <= 0.02 * 0.04 * 0.06 / volume.settings.reference_area + 1e-12


def test_bad_input_is_a_value_error(completed, finger):
    scene, _ = completed
    with pytest.raises(ValueError, match="plane"):
        _core.solid_volume(scene.solid_points(), [0, 0, 0, 0])
    with pytest.raises(ValueError, match="resolution"):
        _core.solid_volume(scene.solid_points(), scene.plane, resolution=0.0)
    with pytest.raises(ValueError, match="NaN"):
        _core.solid_volume(np.full((3, 3), np.nan), scene.plane)
    with pytest.raises(ValueError, match="volume_resolution"):
        bad = _core.CollisionSettings(volume=True, volume_resolution=-1.0)
        _core.CollisionExpert(finger, scene.solid_points(), plane=scene.plane, settings=bad)


def test_unseen_space_beyond_the_completion_is_charged_softly(completed, finger, box_urdf):
    """The occupancy model with unknown cells free, the volume and the soft unseen charge: the completed box's
    inside is refused, the unseen shadow beyond it is charged but not refused, the seen-free front costs nothing."""
    scene, c = completed
    acq = acquire(box_urdf(SIZE), seed=0, settings=AcquisitionSettings(cameras=[Camera(eye=EYE)], keep="scene"))
    occ = _core.OccupancyMap(
        acq.points,
        acq.viewpoints,
        scene.points,
        scene.plane,
        settings=_core.OccupancySettings(unknown_is_occupied=False),
    )
    s = _core.CollisionSettings(volume=True, unseen_weight=0.1)
    expert = _core.CollisionExpert(finger, scene.solid_points(), plane=scene.plane, occupancy=occ, settings=s)
    away = -np.array(EYE[:2] + (0,)) / np.linalg.norm(EYE[:2])  # from the box, away from the camera
    poses = np.array([[*p, 0, 0, 0, 1] for p in (c, c + 0.09 * away, c - 0.12 * away)])
    r = expert.evaluate_batch(poses, np.zeros((1, 0)))
    assert r.collision_free.tolist() == [False, True, True]
    assert r.unseen_depth.sum(axis=1)[1] > 0 and r.unseen_depth.sum(axis=1)[2] == 0
    # A map whose unknown cells are obstacles charges them in full (blocked), not softly on top.
    solid = _core.OccupancyMap(acq.points, acq.viewpoints, scene.points, scene.plane)
    hard = _core.CollisionExpert(finger, scene.solid_points(), plane=scene.plane, occupancy=solid, settings=s)
    assert hard.unseen is None
    h = hard.evaluate_batch(poses, np.zeros((1, 0)))
    assert np.all(h.unseen_depth == 0) and not h.collision_free[1] and h.collision_free[2]


def test_the_surface_model_charges_the_scenes_unseen_space_from_its_visibility_model(completed, finger, box_urdf):
    """The unseen map baked from the scene's visibility model (OccupancyMap.from_visibility) against the rays'
    map of the same view: the same region, nearly every cell the same, and the same charges on the surface model
    as on the occupancy model with the seen surface left to the points."""
    scene, c = completed
    acq = acquire(box_urdf(SIZE), seed=0, settings=AcquisitionSettings(cameras=[Camera(eye=EYE)], keep="scene"))
    free_unknown = _core.OccupancySettings(unknown_is_occupied=False)
    rays = _core.OccupancyMap(acq.points, acq.viewpoints, scene.points, scene.plane, settings=free_unknown)
    seen = _core.OccupancyMap.from_visibility(scene.visibility, scene.points, scene.plane, settings=free_unknown)
    assert np.allclose(seen.region_min, rays.region_min) and list(seen.dims) == list(rays.dims)
    h = seen.resolution
    ijk = np.stack(np.meshgrid(*[np.arange(n) for n in seen.dims], indexing="ij"), -1).reshape(-1, 3)
    centres = seen.region_min + h * (ijk + 0.5)
    assert np.mean(seen.state(centres) == rays.state(centres)) > 0.95
    assert seen.stats["n_rays"] == 0 and seen.stats["n_unknown"] > 1000
    s = _core.CollisionSettings(volume=True, unseen_weight=0.1)
    surface = _core.CollisionExpert(finger, scene.solid_points(), plane=scene.plane, unseen=seen, settings=s)
    assert surface.model == "surface" and surface.unseen is not None
    away = -np.array(EYE[:2] + (0,)) / np.linalg.norm(EYE[:2])
    poses = np.array([[*p, 0, 0, 0, 1] for p in (c, c + 0.09 * away, c - 0.12 * away)])
    r = surface.evaluate_batch(poses, np.zeros((1, 0)))
    assert r.collision_free.tolist() == [False, True, True]
    assert r.unseen_depth.sum(axis=1)[1] > 0 and r.unseen_depth.sum(axis=1)[2] == 0
    # The occupancy model on the same map, its occupied cells not charged: the same numbers.
    occ = _core.CollisionExpert(
        finger,
        scene.solid_points(),
        plane=scene.plane,
        occupancy=seen,
        settings=_core.CollisionSettings(volume=True, unseen_weight=0.1, occupied_cells=False),
    )
    assert np.array_equal(occ.evaluate_batch(poses, np.zeros((1, 0))).total_depth, r.total_depth)
    with pytest.raises(ValueError, match="not both"):
        _core.CollisionExpert(finger, scene.solid_points(), occupancy=seen, unseen=seen, settings=s)
    with pytest.raises(ValueError, match="no object points"):
        _core.OccupancyMap.from_visibility(scene.visibility, np.zeros((0, 3)), scene.plane)
