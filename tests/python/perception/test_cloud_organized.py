"""Organised clouds (width x height, NaN holes) through save_cloud / load_cloud: CloudData.pixels and
CloudData.organized() against the grid that was written, by graspmix in every PCD encoding and by numpy, and in a
camera's frame against scipy's rotation."""

import graspmix
import numpy as np
import pytest

W, H = 8, 6


def _grid(seed: int) -> np.ndarray:
    """(H, W, 3) points of a tilted plane seen by a camera, a seeded quarter of the pixels NaN."""
    rng = np.random.default_rng(seed)
    v, u = np.mgrid[0:H, 0:W]
    z = 1.0 + 0.02 * u + 0.01 * v
    grid = np.stack([(u - W / 2) * 0.01 * z, (v - H / 2) * 0.01 * z, z], axis=-1)
    grid[rng.random((H, W)) < 0.25] = np.nan
    return grid


@pytest.mark.parametrize("encoding", ["ascii", "binary", "binary_compressed"])
def test_round_trip_keeps_the_grid(tmp_path, encoding):
    grid = _grid(1)
    flat = grid.reshape(-1, 3)
    path = tmp_path / f"o_{encoding}.pcd"
    graspmix.save_cloud(path, flat, encoding=encoding, width=W, height=H)
    c = graspmix.load_cloud(path)
    finite = np.isfinite(flat).all(axis=1)
    assert (c.width, c.height, c.n_invalid) == (W, H, int((~finite).sum()))
    assert c.pixels.dtype == np.int64
    np.testing.assert_array_equal(c.pixels, np.flatnonzero(finite))
    np.testing.assert_array_equal(c.points, flat[finite].astype(np.float32))  # float32 on disk, exactly
    organized = c.organized()
    assert organized.shape == (H, W, 3) and organized.dtype == np.float64
    np.testing.assert_array_equal(organized, grid.astype(np.float32))  # NaN where NaN was written


def test_an_organised_file_written_by_numpy(tmp_path):
    grid = _grid(2).astype(np.float32)
    rec = np.zeros(H * W, dtype=[("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("rgb", "<u4")])
    rec["x"], rec["y"], rec["z"] = grid.reshape(-1, 3).T
    head = (
        f"VERSION 0.7\nFIELDS x y z rgb\nSIZE 4 4 4 4\nTYPE F F F U\nCOUNT 1 1 1 1\nWIDTH {W}\nHEIGHT {H}\n"
        f"VIEWPOINT 0 0 0 1 0 0 0\nPOINTS {W * H}\nDATA binary\n"
    )
    (tmp_path / "cam.pcd").write_bytes(head.encode() + rec.tobytes())
    c = graspmix.load_cloud(tmp_path / "cam.pcd")
    rows, cols = np.nonzero(np.isfinite(grid).all(axis=-1))
    np.testing.assert_array_equal(c.pixels, rows * W + cols)
    np.testing.assert_array_equal(c.points, grid[rows, cols])
    np.testing.assert_array_equal(c.organized(), grid)


def test_the_grid_in_a_cameras_frame(tmp_path):
    # organized(camera_pose=T) is the grid mapped by T^-1, as scipy's rotation maps it; NaN holes stay NaN.
    from scipy.spatial.transform import Rotation

    grid = _grid(5)
    graspmix.save_cloud(tmp_path / "w.pcd", grid.reshape(-1, 3), encoding="binary", width=W, height=H)
    c = graspmix.load_cloud(tmp_path / "w.pcd")
    world = c.organized()
    q = Rotation.from_euler("xyz", [0.7, -0.2, 1.9]).as_quat()  # x, y, z, w
    t = np.array([0.3, -0.55, 0.6])
    expected = Rotation.from_quat(q).inv().apply(world.reshape(-1, 3) - t).reshape(H, W, 3)
    got = c.organized(camera_pose=[*t, *q])
    assert got.shape == (H, W, 3)
    np.testing.assert_array_equal(np.isnan(got), np.isnan(world))
    hit = np.isfinite(world).all(axis=-1)
    np.testing.assert_allclose(got[hit], expected[hit], atol=1e-12)
    np.testing.assert_array_equal(c.organized(camera_pose=[0, 0, 0, 0, 0, 0, 1]), world)  # the identity
    with pytest.raises(ValueError, match="camera_pose"):
        c.organized(camera_pose=[0, 0, 0, 0, 0, 0, 2])  # not a unit quaternion
    with pytest.raises(ValueError, match="camera_pose"):
        c.organized(camera_pose=[0, 0, 0, 1])


def test_unorganised_clouds_have_no_grid(tmp_path):
    pts = _grid(3).reshape(-1, 3)
    pts = pts[np.isfinite(pts).all(axis=1)]
    graspmix.save_cloud(tmp_path / "u.pcd", pts)
    c = graspmix.load_cloud(tmp_path / "u.pcd")
    assert c.height == 1 and c.pixels.shape == (0,)
    with pytest.raises(ValueError, match=r"u\.pcd: not an organized cloud \(height 1\)"):
        c.organized()


def test_bad_organised_writes(tmp_path):
    flat = _grid(4).reshape(-1, 3)
    with pytest.raises(ValueError, match=r"o\.ply: an organized cloud \(height 6\) cannot be written as PLY"):
        graspmix.save_cloud(tmp_path / "o.ply", flat, width=W, height=H)
    with pytest.raises(ValueError, match=r"width x height = 8 x 5 for 48 points"):
        graspmix.save_cloud(tmp_path / "o.pcd", flat, width=W, height=5)
    with pytest.raises(ValueError, match="points: contains NaN"):  # holes only in an organised cloud
        graspmix.save_cloud(tmp_path / "o.pcd", flat)
    with pytest.raises(ValueError, match="height"):
        graspmix.save_cloud(tmp_path / "o.pcd", flat, width=W, height=-6)
    assert not (tmp_path / "o.pcd").exists() and not (tmp_path / "o.ply").exists()
