"""The experiment's own inputs: per-point camera positions survive the clean-up (voxel grid included), so
every surface normal of an acquired convex object points out of it (before the fix, half of them pointed
in: every voxel centroid took the last camera)."""

import graspmix
import numpy as np
import pytest
from graspmix.experiment import Protocol
from graspmix.experiment.attempt import crop_above_plane
from graspmix.model import FeatureScale
from graspmix.model.scene_synthesis import object_surface
from graspmix.perception import segment_scene
from graspmix.sim.acquisition import acquire

SUPPORT_PLANE = [0.0, 0.0, 1.0, 0.0]


def experiment_surface(obj, noise):
    p = Protocol(objects=[obj], trials=1)
    clearance = p.synthesis.segmentation.table_clearance
    acq = acquire(obj, noise=noise, seed=3, postprocess=crop_above_plane(clearance))
    assert len(np.unique(acq.camera_index)) >= 3  # the object is seen from several cameras
    # What the experiment's synthesis does: the scene with its known table, then the object's features.
    scene = segment_scene(acq.points, acq.viewpoints, SUPPORT_PLANE, table_clearance=clearance)
    assert len(scene.objects) == 1
    return object_surface(scene, 0, FeatureScale())


@pytest.mark.parametrize("noise", [False, True])
def test_normals_on_a_cube_point_out_of_its_faces(noise):
    """cube_small.urdf: a 5 cm cube on the table. Away from its edges (farther than the 1 cm feature
    radius, where a neighbourhood spans two faces and the normal is a blend) every normal points out of its
    face; near the edges, most do."""
    surface = experiment_surface("cube_small.urdf", noise)
    q = surface.points - [0.0, 0.0, 0.025]
    face_axis = np.abs(q).argmax(axis=1)
    outward = np.sign(q[np.arange(len(q)), face_axis]) * surface.normals[np.arange(len(q)), face_axis] > 0
    # distance to the nearest edge: the second largest |coordinate| tells how far from a neighbouring face
    second = np.sort(np.abs(q), axis=1)[:, 1]
    interior = 0.025 - second > 0.011
    assert interior.sum() > 100
    assert outward[interior].mean() >= (0.99 if noise else 1.0), f"{(~outward[interior]).sum()} face normals point in"
    assert outward.mean() >= 0.95


def test_normals_on_a_sphere_point_out():
    surface = experiment_surface("sphere_small.urdf", False)
    lo, hi = surface.points.min(axis=0), surface.points.max(axis=0)
    centre = (lo + hi) / 2
    centre[2] = hi[2] - (hi[0] - lo[0]) / 2  # the sphere's top minus its radius (its bottom is cut)
    outward = np.einsum("ij,ij->i", surface.normals, surface.points - centre) > 0
    assert outward.all(), f"{(~outward).sum()} of {len(outward)} normals point in"


def test_viewpoints_must_match_the_points():
    pts = np.random.default_rng(0).normal(size=(50, 3)) * 0.02 + [0, 0, 0.05]
    with pytest.raises(ValueError, match=r"viewpoints: expected shape \(3,\) or \(50, 3\)"):
        FeatureScale().surface(pts, remove_plane=False, viewpoints=np.zeros((7, 3)))
    with pytest.raises(ValueError, match="viewpoints: contains NaN"):
        FeatureScale().surface(pts, remove_plane=False, viewpoints=np.full(3, np.nan))


def test_sources_point_at_the_nearest_member_of_their_voxel():
    """CleanupResult.sources: every voxel centroid's source row is the member of its voxel nearest to it."""
    rng = np.random.default_rng(1)
    pts = rng.uniform(-0.05, 0.05, size=(3000, 3))
    scene = graspmix.prepare_cloud(pts, voxel_size=0.01, remove_plane=False, remove_outliers=False)
    assert np.all(scene.indices == -1) and len(scene.sources) == len(scene.points)
    cells = np.floor(pts.astype(np.float32) * np.float32(1 / 0.01)).astype(int)  # PCL's voxel of each point
    for centroid, src in zip(scene.points, scene.sources):
        members = np.all(cells == cells[src], axis=1)
        np.testing.assert_allclose(pts[members].mean(axis=0), centroid, atol=1e-6)  # the source is in its voxel
        d = np.linalg.norm(pts[members] - centroid, axis=1)
        # a centroid of two points is equally near both: compare distances, not rows
        assert np.linalg.norm(pts[src] - centroid) <= d.min() + 1e-6
    kept = graspmix.prepare_cloud(pts, voxel_size=0.0, remove_plane=False, remove_outliers=True)
    np.testing.assert_array_equal(kept.sources, kept.indices)


def test_a_stray_far_point_is_a_clear_error():
    pts = np.random.default_rng(2).normal(size=(100, 3)) * 0.02
    pts[0] = [1000.0, 1000.0, 1000.0]
    with pytest.raises(ValueError, match="crop the cloud or use a larger voxel_size"):
        graspmix.prepare_cloud(pts, voxel_size=0.003)
