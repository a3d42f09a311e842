"""load_cloud / save_cloud: round trips in every encoding, files written independently of PCL (by
numpy), and broken files that must give a ValueError naming the file and the problem."""

import struct

import graspmix
import numpy as np
import pytest


@pytest.fixture
def points():
    rng = np.random.default_rng(1)
    return rng.uniform(-0.5, 0.5, size=(300, 3))


@pytest.mark.parametrize(
    "name,encoding",
    [("a.pcd", "ascii"), ("b.pcd", "binary"), ("c.pcd", "binary_compressed"), ("d.ply", "ascii"), ("e.ply", "binary")],
)
def test_round_trip(tmp_path, points, name, encoding):
    normals = points / np.linalg.norm(points, axis=1, keepdims=True)
    vp = np.array([0.1, 0.2, 0.3, 0.0, 0.0, np.sin(0.3), np.cos(0.3)])
    graspmix.save_cloud(tmp_path / name, points, normals, encoding=encoding, viewpoint=vp)
    c = graspmix.load_cloud(tmp_path / name)
    assert isinstance(c, graspmix.CloudData) and len(c) == 300
    np.testing.assert_array_equal(c.points, points.astype(np.float32).astype(float))  # float32 on disk, exactly
    np.testing.assert_allclose(c.normals, normals, atol=1e-7)
    assert c.n_invalid == 0
    if name.endswith(".pcd"):
        assert c.format == "pcd " + encoding
        assert c.has_viewpoint
        np.testing.assert_allclose(c.viewpoint, vp, atol=1e-6)
    else:
        assert c.format == "ply"


def test_round_trip_without_normals(tmp_path, points):
    graspmix.save_cloud(tmp_path / "p.pcd", points)
    c = graspmix.load_cloud(str(tmp_path / "p.pcd"))
    assert c.normals is None and c.fields == ["x", "y", "z"] and not c.has_viewpoint


def _pcd_header(fields, size, typ, width, height, data, viewpoint="0 0 0 1 0 0 0"):
    n = len(fields)
    return (
        f"# .PCD v0.7\nVERSION 0.7\nFIELDS {' '.join(fields)}\nSIZE {' '.join(map(str, size))}\n"
        f"TYPE {' '.join(typ)}\nCOUNT {' '.join(['1'] * n)}\nWIDTH {width}\nHEIGHT {height}\n"
        f"VIEWPOINT {viewpoint}\nPOINTS {width * height}\nDATA {data}\n"
    ).encode()


def test_organised_binary_pcd_with_nans_rgb_intensity_and_viewpoint(tmp_path):
    # A 4 x 3 organised cloud as a depth camera writes it: NaN holes, packed rgb, intensity.
    rng = np.random.default_rng(2)
    xyz = rng.uniform(-1, 1, size=(12, 3)).astype(np.float32)
    xyz[[1, 5, 6]] = np.nan
    rec = np.zeros(12, dtype=[("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("rgb", "<u4"), ("intensity", "<f4")])
    rec["x"], rec["y"], rec["z"] = xyz.T
    rec["rgb"] = 0x00FF8800
    rec["intensity"] = np.arange(12)
    path = tmp_path / "org.pcd"
    path.write_bytes(
        _pcd_header(
            ["x", "y", "z", "rgb", "intensity"],
            [4] * 5,
            ["F", "F", "F", "U", "F"],
            4,
            3,
            "binary",
            viewpoint="0.5 0 1 0 0 0 1",
        )
        + rec.tobytes()
    )
    c = graspmix.load_cloud(path)
    assert (c.width, c.height, c.n_invalid) == (4, 3, 3)
    assert c.fields == ["x", "y", "z", "rgb", "intensity"]
    np.testing.assert_array_equal(c.points, xyz[np.isfinite(xyz[:, 0])].astype(float))
    assert c.has_viewpoint
    np.testing.assert_allclose(c.viewpoint, [0.5, 0, 1, 0, 0, 1, 0])  # PCD order qw qx qy qz -> [qx qy qz qw]


@pytest.mark.parametrize("fmt,endian", [("binary_little_endian", "<"), ("binary_big_endian", ">"), ("ascii", None)])
def test_double_precision_ply_with_normals_written_by_numpy(tmp_path, fmt, endian):
    rng = np.random.default_rng(3)
    P = rng.normal(size=(50, 3))
    N = P / np.linalg.norm(P, axis=1, keepdims=True)
    head = (
        f"ply\nformat {fmt} 1.0\nelement vertex 50\nproperty double x\nproperty double y\nproperty double z\n"
        "property float nx\nproperty float ny\nproperty float nz\nend_header\n"
    ).encode()
    if endian:
        rec = np.zeros(50, dtype=[(k, endian + "f8") for k in "xyz"] + [(k, endian + "f4") for k in ("nx", "ny", "nz")])
        rec["x"], rec["y"], rec["z"] = P.T
        rec["nx"], rec["ny"], rec["nz"] = N.T
        body = rec.tobytes()
    else:
        body = "".join(" ".join(f"{v:.17g}" for v in row) + "\n" for row in np.c_[P, N]).encode()
    (tmp_path / "m.ply").write_bytes(head + body)
    c = graspmix.load_cloud(tmp_path / "m.ply")
    np.testing.assert_array_equal(c.points, P)  # doubles stay doubles
    np.testing.assert_allclose(c.normals, N, atol=1e-7)


def test_npy(tmp_path, points):
    np.save(tmp_path / "p.npy", points)
    np.testing.assert_array_equal(graspmix.load_cloud(tmp_path / "p.npy").points, points)
    q = points.astype(np.float32)
    q[3] = np.nan
    np.save(tmp_path / "q.npy", q)
    c = graspmix.load_cloud(tmp_path / "q.npy")
    assert len(c) == 299 and c.n_invalid == 1
    np.save(tmp_path / "f.npy", np.asfortranarray(points))
    np.testing.assert_array_equal(graspmix.load_cloud(tmp_path / "f.npy").points, points)
    np.save(tmp_path / "bad.npy", points[:, :2])
    with pytest.raises(ValueError, match=r"bad\.npy: expected an \(N, 3\) array, got shape \(300, 2\)"):
        graspmix.load_cloud(tmp_path / "bad.npy")


def _expect_error(path, *words):
    with pytest.raises(ValueError) as e:
        graspmix.load_cloud(path)
    msg = str(e.value)
    assert path.name in msg, msg
    for w in words:
        assert w in msg, msg


def test_truncated_files(tmp_path, points):
    for name, enc in [("b.pcd", "binary"), ("a.pcd", "ascii"), ("c.pcd", "binary_compressed"), ("e.ply", "binary")]:
        graspmix.save_cloud(tmp_path / name, points, encoding=enc)
        data = (tmp_path / name).read_bytes()
        header_end = data.find(b"end_header\n") + 11 if name.endswith(".ply") else data.find(b"DATA") + 20
        cut = tmp_path / ("cut_" + name)
        cut.write_bytes(data[: header_end + 600])  # well inside the 3600 bytes of data
        with pytest.raises(ValueError) as e:
            graspmix.load_cloud(cut)
        assert cut.name in str(e.value)
        assert "truncated" in str(e.value) or "corrupt" in str(e.value), str(e.value)


def test_wrong_header_empty_and_all_nan(tmp_path):
    p = tmp_path / "wrong.pcd"
    p.write_bytes(
        b"VERSION 0.7\nFIELDS x y z\nSIZE 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3\n"
    )
    _expect_error(p, "header")
    p = tmp_path / "garbage.pcd"
    p.write_bytes(b"hello world\n")
    _expect_error(p, "header")
    p = tmp_path / "empty.pcd"
    p.write_bytes(_pcd_header(["x", "y", "z"], [4] * 3, ["F"] * 3, 0, 1, "ascii"))
    _expect_error(p, "empty")
    p = tmp_path / "zero.ply"
    p.write_bytes(b"")
    _expect_error(p, "empty")
    p = tmp_path / "nan.pcd"
    p.write_bytes(
        _pcd_header(["x", "y", "z"], [4] * 3, ["F"] * 3, 2, 1, "binary") + struct.pack("<6f", *([float("nan")] * 6))
    )
    _expect_error(p, "NaN", "all 2 points")
    p = tmp_path / "noxyz.pcd"
    p.write_bytes(_pcd_header(["a", "b", "c"], [4] * 3, ["F"] * 3, 1, 1, "ascii") + b"1 2 3\n")
    _expect_error(p, "no x, y, z")
    p = tmp_path / "bad.ply"
    p.write_bytes(b"plx\nformat ascii 1.0\nend_header\n")
    _expect_error(p, "PLY header")
    _expect_error(tmp_path / "missing.pcd", "no such file")
    p = tmp_path / "cloud.xyz"
    p.write_text("1 2 3\n")
    _expect_error(p, "unknown cloud format")


def test_save_errors(tmp_path, points):
    with pytest.raises(ValueError, match="encoding"):
        graspmix.save_cloud(tmp_path / "x.pcd", points, encoding="zip")
    with pytest.raises(ValueError, match=r"\(N, 3\)"):
        graspmix.save_cloud(tmp_path / "x.pcd", points[:, :2])
    with pytest.raises(ValueError, match="empty"):
        graspmix.save_cloud(tmp_path / "x.pcd", np.zeros((0, 3)))
    with pytest.raises(ValueError, match="normals"):
        graspmix.save_cloud(tmp_path / "x.pcd", points, points[:5])
    with pytest.raises(ValueError, match="can only write"):
        graspmix.save_cloud(tmp_path / "x.txt", points)


def test_double_and_integer_pcd_fields(tmp_path):
    # x y z as float64 (PCL's PointXYZ templates would skip them) and a uint8 label, binary_compressed-free.
    rng = np.random.default_rng(4)
    P = rng.normal(size=(20, 3))
    rec = np.zeros(20, dtype=[("x", "<f8"), ("y", "<f8"), ("z", "<f8"), ("label", "u1")])
    rec["x"], rec["y"], rec["z"] = P.T
    rec["label"] = 7
    path = tmp_path / "double.pcd"
    path.write_bytes(
        _pcd_header(["x", "y", "z", "label"], [8, 8, 8, 1], ["F", "F", "F", "U"], 20, 1, "binary") + rec.tobytes()
    )
    c = graspmix.load_cloud(path)
    np.testing.assert_array_equal(c.points, P)
    assert c.fields == ["x", "y", "z", "label"]


# ---- per-point viewpoints (PCL's PointWithViewpoint: x y z vp_x vp_y vp_z) ----------------------------


def _nearest_of_four(points):
    """The camera of a four-camera ring nearest each point: what a merged multi-view cloud carries."""
    cams = np.array([[1.0, 0, 0.5], [0, 1, 0.5], [-1, 0, 0.5], [0, -1, 0.5]])
    return cams[np.argmin(np.linalg.norm(points[:, None] - cams[None], axis=2), axis=1)]


@pytest.mark.parametrize(
    "name,encoding",
    [("a.pcd", "ascii"), ("b.pcd", "binary"), ("c.pcd", "binary_compressed"), ("d.ply", "ascii"), ("e.ply", "binary")],
)
def test_per_point_viewpoints_round_trip(tmp_path, points, name, encoding):
    vps = _nearest_of_four(points) + np.random.default_rng(3).normal(0, 0.01, (len(points), 3))
    graspmix.save_cloud(tmp_path / name, points, encoding=encoding, viewpoints=vps)
    c = graspmix.load_cloud(tmp_path / name)
    assert c.fields == ["x", "y", "z", "vp_x", "vp_y", "vp_z"] and not c.has_viewpoint
    np.testing.assert_array_equal(c.viewpoints, vps.astype(np.float32).astype(float))  # exactly what was written
    np.testing.assert_array_equal(c.points, points.astype(np.float32).astype(float))
    p, _, v = graspmix.io.load_points(tmp_path / name)
    assert v.shape == (300, 3)
    np.testing.assert_array_equal(v, c.viewpoints)


def test_per_point_viewpoints_follow_the_kept_points(tmp_path):
    # Written by numpy, not by us: an organised binary cloud with NaN holes, and a header VIEWPOINT too.
    rec = np.zeros(6, dtype=[(f, "<f4") for f in ("x", "y", "z", "vp_x", "vp_y", "vp_z")])
    rec["x"] = [0.1, np.nan, 0.3, 0.4, np.nan, 0.6]
    rec["vp_x"] = np.arange(6)
    rec["vp_y"][[1, 4]] = np.nan  # a NaN viewpoint on a dropped point is no error
    fields = ["x", "y", "z", "vp_x", "vp_y", "vp_z"]
    head = _pcd_header(fields, [4] * 6, ["F"] * 6, 3, 2, "binary", viewpoint="1 2 3 1 0 0 0")
    (tmp_path / "o.pcd").write_bytes(head + rec.tobytes())
    c = graspmix.load_cloud(tmp_path / "o.pcd")
    assert c.n_invalid == 2 and c.has_viewpoint
    np.testing.assert_array_equal(c.viewpoints[:, 0], [0, 2, 3, 5])
    np.testing.assert_array_equal(c.points[:, 0], np.float32([0.1, 0.3, 0.4, 0.6]))
    # load_points prefers the per-point viewpoints; without them the header's position, else None
    assert graspmix.io.load_points(tmp_path / "o.pcd")[2].shape == (4, 3)
    graspmix.save_cloud(tmp_path / "h.pcd", c.points, viewpoint=[1, 2, 3, 0, 0, 0, 1])
    np.testing.assert_array_equal(graspmix.io.load_points(tmp_path / "h.pcd")[2], [1, 2, 3])
    graspmix.save_cloud(tmp_path / "n.pcd", c.points)
    assert graspmix.io.load_points(tmp_path / "n.pcd")[2] is None
    assert graspmix.load_cloud(tmp_path / "n.pcd").viewpoints.shape == (0, 3)


@pytest.mark.parametrize(
    "fields,typ,row,words",
    [
        ("x y z vp_x vp_y", "F F F F F", "1 2 3 4 5", ["only vp_x, vp_y of the per-point viewpoint fields"]),
        ("x y z vp_x vp_y vp_z", "F F F F F I", "1 2 3 4 5 6", ["field vp_z is not a float"]),
        ("x y z vp_x vp_y vp_z", "F F F F F F", "1 2 3 inf 5 6", ["viewpoint", "of point 0 is NaN or infinite"]),
    ],
)
def test_malformed_viewpoint_fields(tmp_path, fields, typ, row, words):
    f, t = fields.split(), typ.split()
    (tmp_path / "v.pcd").write_bytes(_pcd_header(f, [4] * len(f), t, 1, 1, "ascii") + row.encode() + b"\n")
    _expect_error(tmp_path / "v.pcd", *words)


def test_save_viewpoints_errors(tmp_path, points):
    vps = _nearest_of_four(points)
    with pytest.raises(ValueError, match="viewpoints: 299 rows for 300 points"):
        graspmix.save_cloud(tmp_path / "x.pcd", points, viewpoints=vps[1:])
    vps[3, 2] = np.nan
    with pytest.raises(ValueError, match="viewpoints: contains NaN"):
        graspmix.save_cloud(tmp_path / "x.pcd", points, viewpoints=vps)
    with pytest.raises(ValueError, match="viewpoints"):
        graspmix.save_cloud(tmp_path / "x.pcd", points, viewpoints=vps[:, :2])


def test_a_file_name_that_is_not_utf8_names_its_file(tmp_path):
    """A name with bytes that are not UTF-8 (Python holds them as lone surrogates) reaches the file it names;
    a missing one is a ValueError naming it, not a failed conversion."""
    import os

    pts = np.random.default_rng(0).normal(size=(30, 3))
    name = os.fsdecode(b"\xff\xfecloud.pcd")  # '\udcff\udcfecloud.pcd'
    graspmix.save_cloud(str(tmp_path / name), pts)
    assert (tmp_path / name).is_file()
    np.testing.assert_allclose(graspmix.load_cloud(str(tmp_path / name)).points, pts, atol=1e-6)
    with pytest.raises(ValueError, match="no such file"):
        graspmix.load_cloud(str(tmp_path / os.fsdecode(b"\xffabsent.pcd")))


def test_prepare_cloud_refuses_a_nan_crop_bound():
    pts = np.random.default_rng(0).normal(size=(100, 3))
    for bound in ({"crop_min": [np.nan, 0, 0]}, {"crop_max": [0, np.nan, 0]}):
        with pytest.raises(ValueError, match="NaN"):
            graspmix.prepare_cloud(pts, **bound)
    # +-inf leaves a side open (the default), and is no error.
    assert len(graspmix.prepare_cloud(pts, crop_min=[-np.inf, -np.inf, 0.0], voxel_size=0).points) > 0
