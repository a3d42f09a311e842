"""graspmix.load_cloud against independent writers in every encoding: pypcd4 writes PCD (ascii, binary,
binary_compressed), plyfile writes PLY (ascii, binary little and big endian). Random seeded clouds, with and
without normals and extra fields, float32 and float64 coordinates, some NaN points; the loaded numbers must
be the written ones exactly (NaN rows dropped and counted)."""

import graspmix
import numpy as np
import pytest

pypcd4 = pytest.importorskip("pypcd4")
plyfile = pytest.importorskip("plyfile")

N = 200


def _cloud(seed: int, dtype, normals: bool, extra: bool, nan_rows: int):
    """Structured array of x y z [normals] [extra fields]; coordinates on a 1 mm grid so that LZF compresses."""
    rng = np.random.default_rng(seed)
    fields = [("x", dtype), ("y", dtype), ("z", dtype)]
    if normals:
        fields += [("normal_x", np.float32), ("normal_y", np.float32), ("normal_z", np.float32)]
    if extra:
        fields += [("intensity", np.float64), ("ring", np.uint16), ("label", np.int32)]
    a = np.zeros(N, dtype=fields)
    xyz = np.round(rng.uniform(-0.2, 0.2, (N, 3)), 3)
    for i, name in enumerate("xyz"):
        a[name] = xyz[:, i]
    if normals:
        n = rng.normal(size=(N, 3))
        n /= np.linalg.norm(n, axis=1, keepdims=True)
        for i, name in enumerate(("normal_x", "normal_y", "normal_z")):
            a[name] = n[:, i]
    if extra:
        a["intensity"] = rng.integers(0, 4, N) * 0.25
        a["ring"] = rng.integers(0, 16, N)
        a["label"] = rng.integers(-3, 3, N)
    a["x"][rng.choice(N, nan_rows, replace=False)] = np.nan
    return a


def _expected(a):
    xyz = np.column_stack([a["x"], a["y"], a["z"]]).astype(np.float64)
    keep = np.isfinite(xyz).all(axis=1)
    return xyz[keep], keep


def _check(path, a, normal_names):
    c = graspmix.load_cloud(path)
    xyz, keep = _expected(a)
    np.testing.assert_array_equal(c.points, xyz)
    assert c.n_invalid == int((~keep).sum())
    if normal_names:
        n = np.column_stack([a[k] for k in ("normal_x", "normal_y", "normal_z")]).astype(np.float64)[keep]
        np.testing.assert_array_equal(c.normals, n)
    else:
        assert c.normals is None
    assert list(c.fields)[:3] == ["x", "y", "z"]
    return c


CASES = [  # seed, coordinate dtype, normals, extra fields, NaN rows
    (1, np.float32, False, False, 0),
    (2, np.float32, True, False, 3),
    (3, np.float64, False, True, 0),
    (4, np.float64, True, True, 5),
]


@pytest.mark.parametrize("encoding", ["ascii", "binary", "binary_compressed"])
@pytest.mark.parametrize("seed,dtype,normals,extra,nan_rows", CASES)
def test_pcd_written_by_pypcd4(tmp_path, encoding, seed, dtype, normals, extra, nan_rows):
    a = _cloud(seed, dtype, normals, extra, nan_rows)
    names = list(a.dtype.names)
    pc = pypcd4.PointCloud.from_points([a[k] for k in names], names, [a.dtype[k] for k in names])
    path = tmp_path / f"c_{encoding}.pcd"
    pc.save(path, encoding=pypcd4.Encoding(encoding))
    data = path.read_bytes()
    # pypcd4 falls back to binary when LZF does not shrink the data; the grid keeps it compressible.
    assert f"DATA {encoding}\n".encode() in data[:400]
    if encoding == "ascii":
        # pypcd4 writes 10 decimals: the file holds those numbers, as numpy reads them, in each field's type.
        rows = np.loadtxt(data.split(b"DATA ascii\n")[1].decode().splitlines(), ndmin=2)
        a = a.copy()
        for i, k in enumerate(names):
            a[k] = rows[:, i].astype(a.dtype[k])
    c = _check(path, a, normals)
    assert c.format == f"pcd {encoding}"
    assert list(c.fields) == names


@pytest.mark.parametrize("encoding", ["ascii", "binary_little_endian", "binary_big_endian"])
@pytest.mark.parametrize("seed,dtype,normals,extra,nan_rows", CASES)
def test_ply_written_by_plyfile(tmp_path, encoding, seed, dtype, normals, extra, nan_rows):
    a = _cloud(seed, dtype, normals, extra, nan_rows)
    if normals:  # PLY's usual names for normals
        a = a.copy()
        a.dtype.names = [{"normal_x": "nx", "normal_y": "ny", "normal_z": "nz"}.get(k, k) for k in a.dtype.names]
    order = {"ascii": "=", "binary_little_endian": "<", "binary_big_endian": ">"}[encoding]
    vertex = a.astype(a.dtype.newbyteorder(order)) if order != "=" else a
    element = plyfile.PlyElement.describe(vertex, "vertex")
    path = tmp_path / f"c_{encoding}.ply"
    plyfile.PlyData([element], text=encoding == "ascii", byte_order=order if order != "=" else "<").write(str(path))
    assert f"format {encoding} 1.0".encode() in path.read_bytes()[:100]
    if normals:
        a.dtype.names = [{"nx": "normal_x", "ny": "normal_y", "nz": "normal_z"}.get(k, k) for k in a.dtype.names]
    c = _check(path, a, normals)
    assert c.format == "ply"


def test_ply_with_faces_written_by_plyfile(tmp_path):
    """A mesh file: the vertices are the cloud, the face lists are walked and ignored."""
    a = _cloud(5, np.float32, False, False, 0)
    faces = np.empty(2, dtype=[("vertex_indices", object)])
    faces["vertex_indices"] = [np.array([0, 1, 2], np.int32), np.array([3, 4, 5, 6], np.int32)]
    for text in (True, False):
        path = tmp_path / f"mesh_{text}.ply"
        plyfile.PlyData(
            [plyfile.PlyElement.describe(a, "vertex"), plyfile.PlyElement.describe(faces, "face")], text=text
        ).write(str(path))
        _check(path, a, False)
