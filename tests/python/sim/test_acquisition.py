"""Acquisition: clean clouds lie on the object's surface, the noise model has the spread of
eq:noise_model, seeds reproduce clouds, the CLI writes a readable PCD, errors are clear."""

import dataclasses
import math
import xml.etree.ElementTree as ET

import graspmix
import numpy as np
import pytest
from graspmix import cli, sim
from graspmix.sim import acquisition as acq_mod
from scipy.spatial import cKDTree
from scipy.spatial.transform import Rotation
from scipy.stats import norm

OBJECTS = ["cube_small.urdf", "random_urdfs/033/033.urdf", "random_urdfs/122/122.urdf", "objects/mug.urdf"]


def surface_samples(obj, spacing=4e-4):
    """Points on the object's visual mesh (what the cameras render) in the world, on a barycentric grid of
    at most `spacing` per triangle edge, so the distance to them overestimates the distance to the surface
    by less than `spacing`."""
    urdf = graspmix.io.resolve_object(obj)
    mesh = ET.parse(urdf).getroot().find("link/visual/geometry/mesh")
    scale = [float(s) for s in mesh.get("scale", "1 1 1").split()]
    v, t = graspmix.load_mesh(urdf.parent / mesh.get("filename"), scale)
    pose = sim.rest_pose(obj)
    v = Rotation.from_quat(pose[3:]).apply(v) + pose[:3]
    out = []
    for a, b, c in v[t]:
        n = max(1, math.ceil(max(np.linalg.norm(b - a), np.linalg.norm(c - a), np.linalg.norm(c - b)) / spacing))
        i, j = np.meshgrid(np.arange(n + 1), np.arange(n + 1))
        keep = i + j <= n
        i, j = i[keep] / n, j[keep] / n
        out.append(a + np.outer(i, b - a) + np.outer(j, c - a))
    return np.vstack(out)


@pytest.fixture(scope="module")
def surfaces():
    return {o: cKDTree(surface_samples(o)) for o in OBJECTS}


@pytest.mark.parametrize("obj", OBJECTS)
def test_clean_cloud_lies_on_the_mesh(obj, surfaces):
    a = acq_mod.acquire(obj, noise=False)
    assert len(a.points) > 1000
    d, _ = surfaces[obj].query(a.points)
    print(
        f"{obj}: {len(a.points)} points, distance to the mesh max {d.max() * 1e3:.3f} mm, median {np.median(d) * 1e3:.3f} mm"
    )
    assert d.max() < 1e-3
    # Every camera sees the object, and the points' viewpoints are their cameras.
    assert set(a.camera_index) == {0, 1, 2, 3}
    np.testing.assert_allclose(a.viewpoints[a.camera_index == 2][0], a.cameras[2].eye)


def test_cube_cloud_against_the_analytic_cube():
    a = acq_mod.acquire("cube_small.urdf", noise=False)
    # Distance to the surface of the 5 cm cube standing on z = 0 at the origin.
    q = np.abs(a.points - [0, 0, 0.025]) - 0.025
    d = np.linalg.norm(np.maximum(q, 0), axis=1) + np.minimum(q.max(axis=1), 0)
    assert np.abs(d).max() < 1e-4


def rounded_normal_variance(std):
    """Var of rint(N(0, std^2)): the lateral shift in whole pixels."""
    k = np.arange(-12, 13)
    p = norm.cdf((k + 0.5) / std) - norm.cdf((k - 0.5) / std)
    return float((p * k**2).sum())


def test_noise_model_spread_on_flat_and_sloped_images():
    rng = np.random.default_rng(3)
    h, w = 240, 320
    flat = np.full((h, w), 0.5)
    d = acq_mod.apply_noise(flat, rng, 1.0, 0.001) - flat
    assert d.std() == pytest.approx(0.001, rel=0.02) and abs(d.mean()) < 2e-5
    # A depth ramp of 1 mm per pixel along u: the lateral shift adds slope^2 Var(rint(N(0, 1))).
    u = np.arange(w)[None, :].repeat(h, 0)
    ramp = 0.4 + 1e-3 * u
    d = (acq_mod.apply_noise(ramp, rng, 1.0, 0.001) - ramp)[:, 10:-10]  # away from the clipped borders
    expected = math.sqrt(1e-6 * rounded_normal_variance(1.0) + 1e-6)
    assert d.std() == pytest.approx(expected, rel=0.03)
    # No depth noise, no lateral shift: nothing changes.
    np.testing.assert_array_equal(acq_mod.apply_noise(ramp, rng, 0.0, 0.0), ramp)


def test_noisy_cloud_residuals(surfaces):
    clean = acq_mod.acquire("cube_small.urdf", noise=False)
    noisy = acq_mod.acquire("cube_small.urdf", noise=True, seed=5)
    dc, _ = surfaces["cube_small.urdf"].query(clean.points)
    dn, _ = surfaces["cube_small.urdf"].query(noisy.points)
    # Depth noise of 1 mm along rays that meet the faces at 45-70 degrees, plus shifted pixels (which
    # mostly land on the same face): median distances of a fraction of a millimetre to a few.
    print(
        f"cube: clean median {np.median(dc) * 1e3:.3f} mm, noisy median {np.median(dn) * 1e3:.3f} mm, "
        f"noisy 95% {np.percentile(dn, 95) * 1e3:.2f} mm"
    )
    assert 0.3e-3 < np.median(dn) < 1.5e-3
    assert np.percentile(dn, 95) < 5e-3
    assert np.median(dn) > 10 * np.median(dc)


def test_seeds_reproduce_clouds():
    a = acq_mod.acquire("random_urdfs/033/033.urdf", noise=True, seed=11)
    b = acq_mod.acquire("random_urdfs/033/033.urdf", noise=True, seed=11)
    c = acq_mod.acquire("random_urdfs/033/033.urdf", noise=True, seed=12)
    np.testing.assert_array_equal(a.points, b.points)
    assert a.points.shape != c.points.shape or not np.array_equal(a.points, c.points)
    # Without noise the seed does not matter.
    np.testing.assert_array_equal(
        acq_mod.acquire("random_urdfs/033/033.urdf", seed=1).points,
        acq_mod.acquire("random_urdfs/033/033.urdf", seed=2).points,
    )


def test_postprocess_hook_and_keep_scene():
    seen = {}

    def crop_above(a, height=0.01):
        seen["n"] = len(a.points)
        keep = a.points[:, 2] > height
        return dataclasses.replace(
            a, points=a.points[keep], viewpoints=a.viewpoints[keep], camera_index=a.camera_index[keep]
        )

    a = acq_mod.acquire("cube_small.urdf", postprocess=crop_above)
    assert seen["n"] > len(a.points) > 0 and a.points[:, 2].min() > 0.01
    scene = acq_mod.acquire("cube_small.urdf", settings=acq_mod.AcquisitionSettings(keep="scene"))
    assert len(scene.points) > seen["n"] and np.abs(scene.points[:, 2]).min() < 1e-4  # the plane is in
    with pytest.raises(ValueError, match="no points"):
        acq_mod.acquire("cube_small.urdf", postprocess=lambda a: crop_above(a, height=1.0))


def test_errors():
    with pytest.raises(ValueError, match="no_such.urdf"):
        acq_mod.acquire("no_such.urdf")
    with pytest.raises(ValueError, match="keep"):
        acq_mod.acquire("cube_small.urdf", settings=acq_mod.AcquisitionSettings(keep="everything"))


def test_cli_acquire(tmp_path, capsys):
    out, pic = tmp_path / "cloud.pcd", tmp_path / "depth.png"
    assert (
        cli.main(
            [
                "acquire",
                "--object",
                "random_urdfs/012/012.urdf",
                "--views",  # the paper's ring and the object's pixels: the library's defaults
                "4",
                "--keep",
                "object",
                "--noise",
                "--seed",
                "3",
                "--out",
                str(out),
                "--picture",
                str(pic),
            ]
        )
        == 0
    )
    assert "points" in capsys.readouterr().out
    pts = graspmix.load_cloud(str(out)).points
    ref = acq_mod.acquire("random_urdfs/012/012.urdf", noise=True, seed=3).points
    np.testing.assert_allclose(pts, ref, atol=1e-6)
    assert pic.stat().st_size > 10_000
    assert cli.main(["acquire", "--object", "missing/thing.urdf", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "missing/thing.urdf" in err
    # a voxel size without the clean-up it belongs to was ignored; now it is an error, before any rendering
    assert (
        cli.main(["acquire", "--object", "random_urdfs/012/012.urdf", "--voxel-size", "0.005", "--out", str(out)]) == 2
    )
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--clean" in err


def test_clean_up_removes_the_table_of_a_scene_and_keeps_viewpoints_aligned():
    raw = acq_mod.acquire("random_urdfs/012/012.urdf", settings=acq_mod.AcquisitionSettings(keep="scene"))
    clean = acq_mod.acquire(
        "random_urdfs/012/012.urdf", settings=acq_mod.AcquisitionSettings(keep="scene"), postprocess=acq_mod.clean_up()
    )
    assert (raw.points[:, 2] < 0.002).mean() > 0.3  # the table dominates the raw scene
    assert clean.plane is not None and abs(abs(clean.plane[2]) - 1) < 1e-3 and abs(clean.plane[3]) < 2e-3
    assert (clean.points[:, 2] < 0.002).mean() < 0.02
    assert len(clean.viewpoints) == len(clean.points) == len(clean.camera_index)
    # Every kept point is seen from its camera: the camera lies on the outer side of the point.
    eyes = np.array([c.eye for c in clean.cameras])
    np.testing.assert_allclose(clean.viewpoints, eyes[clean.camera_index])
