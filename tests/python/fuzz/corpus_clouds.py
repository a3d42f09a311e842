"""Fuzz corpus of cloud files (.pcd, .ply, .npy) for any command that reads a cloud.

Self-contained (standard library only): it writes every file itself, so a harness can import it without
graspmix. `CASES` is a list of dicts:

- "name": unique, stable;
- "files": {file name: bytes} to write into a fresh folder;
- "argv": command-line arguments for `python -m graspmix.cli`, with "{dir}" standing for that folder;
- "expect": "error" (exit status 2, one line on stderr, no traceback) or "ok" (exit status 0);
- "mentions": a substring the stderr line must contain when "expect" is "error" ("" for "ok").

Classes: hand-written broken files of every kind the readers check (truncated or short bodies in every
encoding, huge and negative counts, inconsistent headers, non-numeric, short and long ASCII rows, unknown
DATA, wrong magic, binary_compressed with bad sizes, .npy of wrong shape, dtype or length, malformed
per-point viewpoints vp_x vp_y vp_z), NaN and infinite points, empty clouds, valid files in every encoding, and seeded mutations of valid files
(truncations at random offsets, byte flips). Every expectation is known without running graspmix:

- NaN or infinite points are dropped and counted (the command succeeds and reports them); a cloud with no
  finite point is an error ("no valid point"). A NaN viewpoint is an error on a kept point only.
- A truncation anywhere before the last row of a text body, or anywhere in a binary file, is an error.
- Flips of the lowest-order byte of binary float coordinates move points by less than 1e-4 of their size: ok.
- A binary_compressed payload with flipped bytes is decoded here by an LZF decoder with the checks of
  liblzf's: an error when it fails, ok when it yields finite coordinates of the same size.
- A letter written over any byte of a text body makes a token that is not a number, or a row of the wrong
  length: an error.
"""

from __future__ import annotations

import math
import random
import struct

SEED = 20240611
N_POINTS = 40  # on a 1 cm sphere: `features` keeps most of them at its default radius


def _points(seed: int, n: int = N_POINTS) -> list[tuple[float, float, float]]:
    rng = random.Random(seed)
    out = []
    for _ in range(n):
        v = [rng.gauss(0, 1) for _ in range(3)]
        r = math.sqrt(sum(c * c for c in v)) or 1.0
        # float32-exact values, so that every encoding holds the same numbers
        out.append(tuple(struct.unpack("<f", struct.pack("<f", 0.01 * c / r))[0] for c in v))
    return out


# ---- writers -------------------------------------------------------------------------------------


def lzf_compress(data: bytes) -> bytes:
    """A valid LZF stream: runs of one repeated byte as back references of distance 1, the rest literals."""
    out, lit, i = bytearray(), bytearray(), 0

    def flush():
        for k in range(0, len(lit), 32):
            chunk = lit[k : k + 32]
            out.append(len(chunk) - 1)
            out.extend(chunk)
        lit.clear()

    while i < len(data):
        run = 1
        while i + run < len(data) and data[i + run] == data[i] and run < 265:
            run += 1
        if run >= 4:  # the first byte as a literal, the rest a back reference to it
            lit.append(data[i])
            flush()
            n = run - 1 - 2  # a reference copies len + 2 bytes
            if n < 7:
                out += bytes([n << 5, 0])
            else:
                out += bytes([7 << 5, n - 7, 0])
            i += run
        else:
            lit.append(data[i])
            i += 1
    flush()
    return bytes(out)


def lzf_decompress(data: bytes, out_len: int) -> bytes | None:
    """liblzf's decoder with its checks; None where it reports an error (as PCL's does)."""
    out, ip = bytearray(), 0
    while ip < len(data):
        ctrl = data[ip]
        ip += 1
        if ctrl < 32:
            ctrl += 1
            if len(out) + ctrl > out_len or ip + ctrl > len(data):
                return None
            out += data[ip : ip + ctrl]
            ip += ctrl
            continue
        n = ctrl >> 5
        ref = len(out) - ((ctrl & 0x1F) << 8) - 1
        if ip >= len(data):
            return None
        if n == 7:
            n += data[ip]
            ip += 1
            if ip >= len(data):
                return None
        ref -= data[ip]
        ip += 1
        if len(out) + n + 2 > out_len or ref < 0:
            return None
        for _ in range(n + 2):
            out.append(out[ref])
            ref += 1
    return bytes(out)


def pcd(
    points, data: str = "binary", normals=None, header: dict | None = None, rows: list[str] | None = None, vps=None
) -> bytes:
    """A PCD file of float32 x y z [normal_x normal_y normal_z] [vp_x vp_y vp_z] (vps: a camera per point);
    `header` overrides header lines by keyword, `rows` replaces an ASCII body."""
    cols = [
        list(p) + (list(normals[i]) if normals else []) + (list(vps[i]) if vps else []) for i, p in enumerate(points)
    ]
    names = ["x", "y", "z"] + (["normal_x", "normal_y", "normal_z"] if normals else [])
    names += ["vp_x", "vp_y", "vp_z"] if vps else []
    k, n = len(names), len(points)
    lines = {
        "VERSION": "0.7",
        "FIELDS": " ".join(names),
        "SIZE": " ".join(["4"] * k),
        "TYPE": " ".join(["F"] * k),
        "COUNT": " ".join(["1"] * k),
        "WIDTH": str(n),
        "HEIGHT": "1",
        "VIEWPOINT": "0 0 0 1 0 0 0",
        "POINTS": str(n),
        "DATA": data,
    }
    lines.update(header or {})
    text = "# .PCD v0.7 - Point Cloud Data file format\n" + "".join(
        f"{key} {value}\n" for key, value in lines.items() if value is not None
    )
    if data == "ascii":
        body = "".join(
            r + "\n" for r in (rows if rows is not None else [" ".join(f"{v:.9g}" for v in c) for c in cols])
        )
        return text.encode() + body.encode()
    if data == "binary":
        return text.encode() + b"".join(struct.pack(f"<{k}f", *c) for c in cols)
    raw = b"".join(struct.pack(f"<{n}f", *(c[j] for c in cols)) for j in range(k))  # one field after another
    packed = lzf_compress(raw)
    return text.encode() + struct.pack("<II", len(packed), len(raw)) + packed


def ply(
    points,
    fmt: str = "binary_little_endian",
    normals=None,
    faces=None,
    extra_header: str = "",
    count: str | None = None,
    rows: list[str] | None = None,
) -> bytes:
    """A PLY file of float x y z [nx ny nz], with optional faces (lists of vertex indices)."""
    names = ["x", "y", "z"] + (["nx", "ny", "nz"] if normals else [])
    head = f"ply\nformat {fmt} 1.0\ncomment graspmix fuzz corpus\n{extra_header}"
    head += f"element vertex {count if count is not None else len(points)}\n"
    head += "".join(f"property float {nm}\n" for nm in names)
    if faces is not None:
        head += f"element face {len(faces)}\nproperty list uchar int vertex_indices\n"
    head += "end_header\n"
    cols = [list(p) + (list(normals[i]) if normals else []) for i, p in enumerate(points)]
    if fmt == "ascii":
        body = rows if rows is not None else [" ".join(f"{v:.9g}" for v in c) for c in cols]
        body += [" ".join(map(str, [len(f), *f])) for f in faces or []]
        return (head + "".join(r + "\n" for r in body)).encode()
    e = "<" if fmt == "binary_little_endian" else ">"
    body = b"".join(struct.pack(f"{e}{len(c)}f", *c) for c in cols)
    body += b"".join(struct.pack(f"{e}B{len(f)}i", len(f), *f) for f in faces or [])
    return head.encode() + body


def npy(values: list[float] | bytes, shape: str, descr: str = "<f8", fortran: bool = False, version: int = 1) -> bytes:
    """A .npy file; `values` packed with the format of `descr` unless already bytes."""
    header = f"{{'descr': '{descr}', 'fortran_order': {fortran}, 'shape': {shape}, }}"
    pre = 10 if version == 1 else 12
    header += " " * (63 - (pre + len(header)) % 64) + "\n"
    length = struct.pack("<H", len(header)) if version == 1 else struct.pack("<I", len(header))
    code = {"f4": "f", "f8": "d", "i4": "i", "i2": "h"}.get(descr[1:], "d")
    data = values if isinstance(values, bytes) else struct.pack(f"{descr[0]}{len(values)}{code}", *values)
    return b"\x93NUMPY" + bytes([version, 0]) + length + header.encode() + data


# ---- cases -----------------------------------------------------------------------------------------

CASES: list[dict] = []


def _case(name: str, filename: str, data: bytes, expect: str, mentions: str = "") -> None:
    assert expect in ("ok", "error") and not any(c["name"] == name for c in CASES), name
    CASES.append(
        {
            "name": name,
            "files": {filename: data},
            "argv": ["features", "--cloud", "{dir}/" + filename],
            "expect": expect,
            "mentions": mentions if expect == "error" else "",
        }
    )


P = _points(SEED)
NORMALS = [tuple(c / 0.01 for c in p) for p in P]
FLAT = [c for p in P for c in p]
VPS = [(0.5, 0.0, 0.5) if p[0] > 0 else (-0.5, 0.0, 0.5) for p in P]  # two cameras, each seeing its half
NAN, INF = float("nan"), float("inf")


def _valid_files() -> dict[str, bytes]:
    """Valid files in every encoding; the mutations start from these."""
    return {
        "pcd_ascii.pcd": pcd(P, "ascii"),
        "pcd_binary.pcd": pcd(P, "binary"),
        "pcd_compressed.pcd": pcd(P, "binary_compressed"),
        "ply_ascii.ply": ply(P, "ascii"),
        "ply_le.ply": ply(P, "binary_little_endian"),
        "ply_be.ply": ply(P, "binary_big_endian"),
        "npy_f8.npy": npy(FLAT, f"({N_POINTS}, 3)"),
        "npy_f4.npy": npy(FLAT, f"({N_POINTS}, 3)", "<f4"),
        "pcd_vp_binary.pcd": pcd(P, "binary", vps=VPS),
    }


VALID = _valid_files()


def _ok_cases() -> None:
    for name, data in VALID.items():
        _case("ok_" + name.split(".")[0], name, data, "ok")
    _case("ok_pcd_normals_compressed", "n.pcd", pcd(P, "binary_compressed", NORMALS), "ok")
    _case("ok_pcd_normals_ascii_crlf", "n.pcd", pcd(P, "ascii", NORMALS).replace(b"\n", b"\r\n"), "ok")
    _case("ok_pcd_organised", "o.pcd", pcd(P, "binary", header={"WIDTH": "20", "HEIGHT": "2"}), "ok")
    _case("ok_pcd_no_width_height", "o.pcd", pcd(P, "ascii", header={"WIDTH": None, "HEIGHT": None}), "ok")
    _case("ok_ply_normals_faces_ascii", "f.ply", ply(P, "ascii", NORMALS, faces=[[0, 1, 2], [3, 4, 5, 6]]), "ok")
    _case("ok_ply_faces_be", "f.ply", ply(P, "binary_big_endian", faces=[[0, 1, 2]] * 5), "ok")
    _case("ok_npy_fortran", "f.npy", npy([p[j] for j in range(3) for p in P], f"({N_POINTS}, 3)", fortran=True), "ok")
    _case("ok_npy_version2", "v.npy", npy(FLAT, f"({N_POINTS}, 3)", version=2), "ok")
    # NaN and infinite points are dropped and counted; the others are the cloud.
    holes = [(NAN, NAN, NAN) if i % 7 == 0 else (INF, 0.0, 0.0) if i % 11 == 0 else p for i, p in enumerate(P)]
    _case("ok_pcd_nan_inf_points", "h.pcd", pcd(holes, "binary"), "ok")
    _case("ok_pcd_nan_ascii", "h.pcd", pcd(holes, "ascii"), "ok")
    _case("ok_ply_nan_points", "h.ply", ply(holes, "binary_little_endian"), "ok")
    _case("ok_npy_nan_points", "h.npy", npy([c for p in holes for c in p], f"({N_POINTS}, 3)"), "ok")
    # Per-point viewpoints (PCL's PointWithViewpoint) in the other encodings; NaN ones only on dropped points.
    _case("ok_pcd_vp_ascii", "v.pcd", pcd(P, "ascii", vps=VPS), "ok")
    _case("ok_pcd_vp_compressed_normals", "v.pcd", pcd(P, "binary_compressed", NORMALS, vps=VPS), "ok")
    nan_vps = [(NAN,) * 3 if h[0] != p[0] else v for h, p, v in zip(holes, P, VPS)]
    _case("ok_pcd_vp_nan_on_nan_points", "v.pcd", pcd(holes, "binary", vps=nan_vps), "ok")


def _vp_error_cases() -> None:
    """Malformed per-point viewpoints: a partial set, several entries, an integer type, NaN on a kept point."""
    e, v6 = "error", "x y z vp_x vp_y vp_z"
    only_x = {"FIELDS": "x y z vp_x", "SIZE": "4 4 4 4", "TYPE": "F F F F", "COUNT": "1 1 1 1"}
    rows = [" ".join(f"{c:.9g}" for c in (*p, 1, 2, 3, 4, 5)) for p in P]
    only_x_rows = [r.rsplit(" ", 4)[0] for r in rows]
    _case("pcd_vp_only_x", "v.pcd", pcd(P, "ascii", header=only_x, rows=only_x_rows), e, "has only vp_x of the")
    three = {"FIELDS": v6, "SIZE": "4 4 4 4 4 4", "TYPE": "F F F F F F", "COUNT": "1 1 1 3 1 1"}
    _case("pcd_vp_count_3", "v.pcd", pcd(P, "ascii", header=three, rows=rows), e, "vp_x has 3 entries a point")
    _case("pcd_vp_type_u", "v.pcd", pcd(P, "binary", header={"TYPE": "F F F F U F"}, vps=VPS), e, "vp_y is not a float")
    bad = [(NAN, 0.0, 0.5) if i == 5 else v for i, v in enumerate(VPS)]
    _case("pcd_vp_nan_binary", "v.pcd", pcd(P, "binary", vps=bad), e, "of point 5 is NaN or infinite")
    _case("pcd_vp_inf_compressed", "v.pcd", pcd(P, "binary_compressed", vps=[(INF, 0, 0)] * N_POINTS), e, "point 0 is")


def _pcd_error_cases() -> None:
    e = "error"
    b, a, c = VALID["pcd_binary.pcd"], VALID["pcd_ascii.pcd"], VALID["pcd_compressed.pcd"]
    _case("pcd_binary_short_body", "t.pcd", b[:-10], e, "truncated")
    _case("pcd_compressed_short_body", "t.pcd", c[:-10], e, "truncated")
    _case("pcd_ascii_missing_rows", "t.pcd", b"\n".join(a.split(b"\n")[:-5]) + b"\n", e, "truncated")
    _case("pcd_ascii_cut_mid_row", "t.pcd", a[: a.rstrip(b"\n").rfind(b" ")], e, "truncated")
    # The 100-byte binary_compressed file that crashed PCL's reader, and friends.
    crash = b"FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 1000\nPOINTS 1000\nDATA binary_compressed\n"
    crash += struct.pack("<II", 5000, 12000)
    _case("pcd_compressed_100_bytes", "crash.pcd", (crash + b"x" * 100)[:100], e, "truncated")
    hc = {"WIDTH": "4", "POINTS": "4", "DATA": "binary_compressed"}
    head = pcd(P[:4], "ascii", header=hc, rows=[])
    _case("pcd_compressed_no_sizes", "s.pcd", head + b"ab", e, "two 4-byte sizes")
    _case("pcd_compressed_size_too_big", "s.pcd", head + struct.pack("<II", 999, 48) + b"abcd", e, "999 compressed")
    _case(
        "pcd_compressed_wrong_uncompressed", "s.pcd", head + struct.pack("<II", 4, 47) + b"abcd", e, "47 uncompressed"
    )
    _case("pcd_compressed_ratio", "s.pcd", head + struct.pack("<II", 0, 48), e, "at most 88")
    _case("pcd_compressed_garbled", "s.pcd", head + struct.pack("<II", 16, 48) + b"\xff" * 16, e, "cannot read")
    huge = {"WIDTH": "4294967295", "POINTS": "4294967295"}
    _case("pcd_binary_huge_points", "h.pcd", pcd(P, "binary", header=huge), e, "truncated")
    _case("pcd_ascii_huge_points", "h.pcd", pcd(P, "ascii", header=huge), e, "truncated")
    _case("pcd_compressed_huge_points", "h.pcd", pcd(P, "binary_compressed", header=huge), e, "uncompressed bytes")
    _case("pcd_points_too_big", "h.pcd", pcd(P, "binary", header={"POINTS": "99999999999"}), e, "exceeds 2^32")
    _case("pcd_negative_points", "n.pcd", pcd(P, "binary", header={"POINTS": "-1"}), e, "non-negative")
    _case("pcd_negative_width", "n.pcd", pcd(P, "binary", header={"WIDTH": "-40"}), e, "non-negative")
    _case("pcd_width_height_points", "w.pcd", pcd(P, "binary", header={"HEIGHT": "2"}), e, "!= POINTS")
    _case("pcd_height_without_width", "w.pcd", pcd(P, "ascii", header={"WIDTH": None}), e, "HEIGHT given without")
    _case("pcd_size_entries", "h.pcd", pcd(P, "binary", header={"SIZE": "4 4"}), e, "SIZE has 2 entries")
    _case("pcd_type_entries", "h.pcd", pcd(P, "binary", header={"TYPE": "F F F F"}), e, "TYPE has 4 entries")
    _case("pcd_count_entries", "h.pcd", pcd(P, "binary", header={"COUNT": "1"}), e, "COUNT has 1 entries")
    _case("pcd_size_3", "h.pcd", pcd(P, "binary", header={"SIZE": "4 3 4"}), e, "must be 1, 2, 4 or 8")
    _case("pcd_type_letter", "h.pcd", pcd(P, "binary", header={"TYPE": "F X F"}), e, "must be F, I or U")
    _case("pcd_float_size_2", "h.pcd", pcd(P, "binary", header={"SIZE": "4 4 2"}), e, "F needs SIZE 4 or 8")
    _case("pcd_count_zero", "h.pcd", pcd(P, "binary", header={"COUNT": "1 0 1"}), e, "COUNT of field 'y'")
    _case("pcd_unknown_data", "h.pcd", pcd(P, "ascii", header={"DATA": "zip"}), e, "unknown DATA 'zip'")
    _case("pcd_no_data_line", "h.pcd", pcd(P, "ascii", header={"DATA": None}, rows=[]), e, "without a DATA line")
    _case("pcd_bad_viewpoint", "h.pcd", pcd(P, "binary", header={"VIEWPOINT": "0 0 0 1 0 0"}), e, "VIEWPOINT")
    _case("pcd_repeated_fields", "h.pcd", b"FIELDS x y z\n" + b, e, "repeated or out of order")
    _case("pcd_unknown_keyword", "h.pcd", b.replace(b"VERSION", b"VERSOIN"), e, "'VERSOIN' is not a PCD keyword")
    _case("pcd_magic_is_ply", "m.pcd", VALID["ply_le.ply"], e, "'ply' is not a PCD keyword")
    _case("pcd_magic_binary_garbage", "m.pcd", bytes(range(1, 256)) * 4, e, "not a valid PCD header")
    _case("pcd_empty_cloud", "z.pcd", pcd([], "binary"), e, "empty")
    _case("pcd_zero_bytes", "z.pcd", b"", e, "empty")
    _case("pcd_no_xyz", "x.pcd", pcd(P, "ascii", header={"FIELDS": "a b c"}), e, "no x, y, z")
    rows = [" ".join(f"{v:.9g}" for v in p) for p in P]
    _case("pcd_ascii_short_row", "r.pcd", pcd(P, "ascii", rows=rows[:5] + ["1 2"] + rows[6:]), e, "2 values")
    _case("pcd_ascii_long_row", "r.pcd", pcd(P, "ascii", rows=rows[:5] + ["1 2 3 4"] + rows[6:]), e, "4 values")
    _case(
        "pcd_ascii_word", "r.pcd", pcd(P, "ascii", rows=rows[:5] + ["1 two 3"] + rows[6:]), e, "'two' is not a number"
    )
    _case("pcd_ascii_comma", "r.pcd", pcd(P, "ascii", rows=rows[:5] + ["1,5 2 3"] + rows[6:]), e, "'1,5'")
    _case("pcd_ascii_blank_row", "r.pcd", pcd(P, "ascii", rows=rows[:5] + [" "] + rows[5:-1]), e, "blank data row")
    _case("pcd_ascii_extra_rows", "r.pcd", pcd(P, "ascii", rows=rows + ["1 2 3"]), e, "more data rows")
    ints = pcd(
        P[:2],
        "ascii",
        header={"FIELDS": "x y z c", "SIZE": "4 4 4 1", "TYPE": "F F F U", "COUNT": None},
        rows=["1 2 3 7", "1 2 3 300"],
    )
    _case("pcd_ascii_int_range", "i.pcd", ints, e, "'300' is not an integer in range")
    _case("pcd_all_nan", "a.pcd", pcd([(NAN, NAN, NAN)] * 5, "binary"), e, "no valid point")
    _case("pcd_all_inf_ascii", "a.pcd", pcd([(INF, 0, 0)] * 5, "ascii"), e, "no valid point")


def _ply_error_cases() -> None:
    e = "error"
    le, asc = VALID["ply_le.ply"], VALID["ply_ascii.ply"]
    _case("ply_negative_count", "n.ply", ply(P, count="-1"), e, "'-1' is not a non-negative integer")
    _case("ply_huge_count_binary", "h.ply", ply(P, count="4294967295"), e, "truncated")
    _case("ply_huge_count_ascii", "h.ply", ply(P, "ascii", count="4294967295"), e, "truncated")
    _case("ply_count_beyond_32_bits", "h.ply", ply(P, count="18446744073709551615"), e, "not a non-negative")
    _case("ply_le_short_body", "t.ply", le[:-5], e, "truncated")
    _case("ply_be_short_body", "t.ply", VALID["ply_be.ply"][:-5], e, "truncated")
    _case("ply_ascii_missing_rows", "t.ply", b"\n".join(asc.split(b"\n")[:-4]) + b"\n", e, "truncated")
    rows = [" ".join(f"{v:.9g}" for v in p) for p in P]
    _case("ply_ascii_short_row", "r.ply", ply(P, "ascii", rows=rows[:3] + ["1 2"] + rows[4:]), e, "too few values")
    _case("ply_ascii_long_row", "r.ply", ply(P, "ascii", rows=rows[:3] + ["1 2 3 4"] + rows[4:]), e, "4 values")
    _case("ply_ascii_word", "r.ply", ply(P, "ascii", rows=rows[:3] + ["1 x 3"] + rows[4:]), e, "'x' is not a number")
    _case("ply_ascii_extra_rows", "r.ply", ply(P, "ascii", rows=rows + ["1 2 3"]), e, "more rows")
    _case(
        "ply_unknown_format", "f.ply", le.replace(b"binary_little_endian", b"binary_middle_endian"), e, "unknown format"
    )
    _case("ply_no_end_header", "f.ply", le[: le.find(b"end_header")], e, "without end_header")
    _case(
        "ply_unknown_type", "f.ply", le.replace(b"property float y", b"property float128 y"), e, "unknown property type"
    )
    _case("ply_no_vertex", "f.ply", le.replace(b"element vertex", b"element point"), e, "no 'vertex' element")
    _case("ply_empty", "z.ply", ply([], "binary_little_endian"), e, "empty")
    _case("ply_no_xyz", "x.ply", le.replace(b"float x\n", b"float a\n"), e, "no x, y, z")
    faces_le = ply(P, faces=[[0, 1, 2]] * 4)
    _case("ply_faces_short", "f.ply", faces_le[:-6], e, "truncated")
    _case("ply_faces_huge_list", "f.ply", faces_le[:-52] + struct.pack("<B", 250) + faces_le[-51:], e, "truncated")
    _case(
        "ply_faces_negative_list",
        "f.ply",
        ply(P, "ascii", faces=[[0, 1, 2]]).replace(b"\n3 0 1 2", b"\n-3 0 1 2"),
        e,
        "not an integer in range",
    )
    org = "obj_info num_cols 100000\nobj_info num_rows 100000\n"
    _case("ply_obj_info_organisation", "o.ply", ply(P, extra_header=org), e, "num_cols 100000 x num_rows 100000")
    _case(
        "ply_range_grid",
        "g.ply",
        ply(P).replace(b"end_header", b"element range_grid 0\nproperty list uchar int vertex_indices\nend_header"),
        e,
        "range_grid",
    )
    _case(
        "ply_property_less_element",
        "p.ply",
        ply(P).replace(b"end_header", b"element junk 4000000000\nend_header"),
        e,
        "no properties",
    )
    _case("ply_magic_is_pcd", "m.ply", VALID["pcd_binary.pcd"], e, "does not start with 'ply'")
    _case("ply_all_nan", "a.ply", ply([(NAN, 0, 0)] * 5), e, "no valid point")


def _npy_error_cases() -> None:
    e = "error"
    f8 = VALID["npy_f8.npy"]
    _case("npy_short_body", "t.npy", f8[:-3], e, "truncated")
    _case("npy_huge_shape", "h.npy", npy(FLAT, "(4000000000000, 3)"), e, "truncated")
    _case("npy_trailing_bytes", "t.npy", f8 + b"\0" * 8, e, "8 bytes after")
    _case("npy_shape_n2", "s.npy", npy(FLAT[:40], "(20, 2)"), e, "expected an (N, 3) array, got shape (20, 2)")
    _case("npy_shape_1d", "s.npy", npy(FLAT, f"({3 * N_POINTS},)"), e, "expected an (N, 3) array")
    _case("npy_shape_3d", "s.npy", npy(FLAT, f"({N_POINTS}, 3, 1)"), e, "expected an (N, 3) array")
    _case("npy_negative_dim", "s.npy", npy(FLAT, "(-1, 3)"), e, "shape entry '-1'")
    _case("npy_big_endian", "d.npy", npy(FLAT, f"({N_POINTS}, 3)", ">f8"), e, "unsupported .npy dtype '>f8'")
    _case("npy_bool", "d.npy", npy(b"\1" * 3 * N_POINTS, f"({N_POINTS}, 3)", "|b1"), e, "unsupported .npy dtype")
    _case("npy_object", "d.npy", npy(b"\0" * 24 * N_POINTS, f"({N_POINTS}, 3)", "|O"), e, "unsupported .npy dtype")
    _case("npy_header_len_huge", "l.npy", b"\x93NUMPY\x02\x00\xff\xff\xff\x7f{}", e, "truncated .npy header")
    _case("npy_bad_magic", "m.npy", b"\x93NUMPZ" + f8[6:], e, "bad magic")
    _case("npy_version_9", "m.npy", f8[:6] + b"\x09" + f8[7:], e, "version 9")
    _case("npy_no_descr", "m.npy", f8.replace(b"'descr'", b"'dtype'"), e, "no 'descr' entry")
    _case("npy_empty", "z.npy", npy([], "(0, 3)"), e, "empty")
    _case("npy_all_nan", "a.npy", npy([NAN] * 6, "(2, 3)"), e, "no valid point")
    _case("unknown_extension", "c.xyz", b"1 2 3\n", e, "unknown cloud format")


# ---- seeded mutations of the valid files -----------------------------------------------------------------


def _body_start(name: str, data: bytes) -> int:
    if name.endswith(".ply"):
        return data.find(b"end_header\n") + len(b"end_header\n")
    if name.endswith(".pcd"):
        return data.find(b"\n", data.find(b"\nDATA ") + 1) + 1
    return data.find(b"\n", 8) + 1  # .npy: the header ends with a newline


def _mutations() -> None:
    rng = random.Random(SEED)
    for name, data in VALID.items():
        stem, text = name.split(".")[0], "ascii" in name
        start = _body_start(name, data)
        # Truncations: anywhere in a binary file; before the last row of a text body (a cut inside the last
        # number of a text file leaves a shorter number, which no reader can tell).
        end = data.rstrip(b"\n").rfind(b"\n") + 1 if text else len(data)
        for k in range(4):
            cut = rng.randrange(1, end)
            _case(f"cut_{stem}_{k}_{cut}", name, data[:cut], "error", name)
        if text:  # a letter over any byte of the body
            for k in range(3):
                at = rng.randrange(start, len(data))
                _case(f"letter_{stem}_{k}_{at}", name, data[:at] + b"x" + data[at + 1 :], "error", name)
        elif "compressed" in name:
            _compressed_flips(name, data, start, rng)
        else:  # the lowest-order byte of a float coordinate
            size = 8 if "f8" in name else 4
            low = size - 1 if name.endswith("be.ply") else 0
            for k in range(3):
                at = start + size * rng.randrange((len(data) - start) // size) + low
                _case(f"flip_{stem}_{k}_{at}", name, data[:at] + bytes([data[at] ^ 0xFF]) + data[at + 1 :], "ok")


def _compressed_flips(name: str, data: bytes, start: int, rng: random.Random) -> None:
    compressed, raw_len = struct.unpack("<II", data[start : start + 8])
    payload = start + 8
    for k in range(6):
        at = rng.randrange(payload, payload + compressed)
        mutated = data[:at] + bytes([data[at] ^ (1 << rng.randrange(8))]) + data[at + 1 :]
        raw = lzf_decompress(mutated[payload:], raw_len)
        if raw is None or len(raw) != raw_len:
            _case(f"lzf_{k}_{at}", name, mutated, "error", "cannot read")
            continue
        xyz = struct.unpack(f"<{3 * N_POINTS}f", raw)
        if all(math.isfinite(v) and abs(v) < 1.0 for v in xyz):
            _case(f"lzf_{k}_{at}", name, mutated, "ok")


_ok_cases()
_pcd_error_cases()
_ply_error_cases()
_npy_error_cases()
_vp_error_cases()
_mutations()
