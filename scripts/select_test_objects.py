#!/usr/bin/env python3
"""Chooses the 60 test objects of the paper's experiment from pybullet_data and writes data/objects/test60.txt.

Candidates: every one-link object URDF of pybullet_data with mesh collision geometry (random_urdfs/*
and the named objects below). For each, with the object as it rests on the plane (URDF orientation):
  * its parts, as pybullet sees them (one convex hull per OBJ group), and their union;
  * width: the narrowest horizontal width of its convex hull over 180 directions (what a top grasp of the
    WSG 50 must span), height, largest extent;
  * convexity = volume / hull volume, boxiness = volume / bounding-box volume, elongation = largest /
    smallest bounding-box side (volumes of the union of parts by quasi-Monte Carlo).
It keeps the objects that fit the WSG 50 (width 15-100 mm: the opening is 110 mm; height 20-200 mm, so
the fingers reach below the top and the object is not taller than a grasp can handle) and are solid
enough (convexity >= 0.2: some random_urdfs are loose clouds of tiny parts), then picks 60 varied
ones deterministically: k-means (seeded) on the standardised descriptors (convexity, boxiness, elongation,
log size), one object per cluster, the member nearest the centre.

Run from the repository root: python3 scripts/select_test_objects.py [--out data/objects/test60.txt]
"""

from __future__ import annotations

import argparse
import math
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import graspmix
import numpy as np
from scipy.cluster.vq import kmeans2
from scipy.spatial import ConvexHull, Delaunay
from scipy.stats import qmc

# Named single-link objects considered besides random_urdfs (cube-like boxes are left out: the
# demonstration is a box).
NAMED = [
    "objects/mug.urdf",
    "duck_vhacd.urdf",
    "teddy_vhacd.urdf",
    "domino/domino.urdf",
    "soccerball.urdf",
    "sphere_small.urdf",
    "jenga/jenga.urdf",
    "lego/lego.urdf",
]
WIDTH = (0.015, 0.100)  # m
HEIGHT = (0.020, 0.200)  # m
MIN_CONVEXITY = 0.2  # some random_urdfs are loose clouds of tiny parts (a few % of their hull): not objects


def data_path() -> Path:
    return graspmix.io.pybullet_data_path()


def mesh_of(urdf: Path):
    """(file, scale) of the single mesh collision of a one-link URDF, or None."""
    root = ET.parse(urdf).getroot()
    if len(root.findall("link")) != 1:
        return None
    meshes = root.findall("link/collision/geometry/mesh")
    if (
        len(meshes) != 1
        or root.findall("link/collision/geometry/box")
        or root.findall("link/collision/geometry/sphere")
    ):
        return None
    m = meshes[0]
    scale = np.array([float(x) for x in m.get("scale", "1 1 1").split()])
    return urdf.parent / m.get("filename"), scale


def obj_parts(path: Path, scale: np.ndarray) -> list[np.ndarray]:
    """Vertices of each o/g group's faces (pybullet hulls each), scaled; one part for other formats."""
    if path.suffix.lower() != ".obj":
        return [graspmix.load_mesh(path, scale)[0]]
    verts, groups = [], [[]]
    for line in path.read_text(errors="replace").splitlines():
        t = line.split()
        if not t:
            continue
        if t[0] == "v":
            verts.append([float(x) for x in t[1:4]])
        elif t[0] in ("o", "g"):
            if groups[-1]:
                groups.append([])
        elif t[0] == "f":
            for ref in t[1:]:
                i = int(ref.split("/")[0])
                groups[-1].append(i - 1 if i > 0 else len(verts) + i)
    V = np.asarray(verts) * scale
    return [V[sorted(set(g))] for g in groups if g]


def describe(parts: list[np.ndarray]) -> dict:
    allv = np.vstack(parts)
    lo, hi = allv.min(0), allv.max(0)
    ext = hi - lo
    hull = ConvexHull(allv)
    # Union volume of the part hulls by a scrambled Sobol' sequence in the bounding box (seeded).
    X = lo + qmc.Sobol(3, scramble=True, seed=0).random(4096) * ext
    inside = np.zeros(len(X), bool)
    for part in parts:
        if len(part) >= 4:
            try:
                inside |= Delaunay(part).find_simplex(X) >= 0
            except Exception:  # flat part: no volume
                pass
    volume = inside.mean() * ext.prod()
    hv = allv[hull.vertices][:, :2]
    widths = [np.ptp(hv @ np.array([math.cos(a), math.sin(a)])) for a in np.linspace(0, math.pi, 180, endpoint=False)]
    return {
        "width": min(widths),
        "height": ext[2],
        "size": ext.max(),
        "convexity": volume / hull.volume,
        "boxiness": volume / ext.prod(),
        "elongation": ext.max() / max(ext.min(), 1e-6),
    }


def describe_candidates() -> list[dict]:
    """The descriptors (describe) of every candidate, with its "path" relative to pybullet_data, sorted."""
    D = data_path()
    candidates = sorted(str(p.relative_to(D)) for p in (D / "random_urdfs").glob("*/*.urdf")) + NAMED
    rows = []
    for k, rel in enumerate(candidates):
        if k % 100 == 0:
            print(f"[select] {k}/{len(candidates)} candidates described", file=sys.stderr)
        urdf = D / rel
        if not urdf.is_file():
            continue
        m = mesh_of(urdf)
        if m is None or not m[0].is_file():
            continue
        try:
            d = describe(obj_parts(*m))
        except Exception as e:  # unreadable or degenerate mesh: not a candidate
            print(f"[select] skip {rel}: {e}", file=sys.stderr)
            continue
        d["path"] = rel
        rows.append(d)
    return rows


def fits_wsg50(r: dict) -> bool:
    """The object fits the WSG 50 and is solid enough (WIDTH, HEIGHT, MIN_CONVEXITY)."""
    return (
        WIDTH[0] <= r["width"] <= WIDTH[1] and HEIGHT[0] <= r["height"] <= HEIGHT[1] and r["convexity"] >= MIN_CONVEXITY
    )


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="data/objects/test60.txt")
    ap.add_argument("-n", type=int, default=60)
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)
    rows = describe_candidates()
    fit = [r for r in rows if fits_wsg50(r)]
    print(f"[select] {len(rows)} described, {len(fit)} fit the WSG 50", file=sys.stderr)
    if len(fit) < args.n:
        raise SystemExit(f"only {len(fit)} objects fit, {args.n} wanted")
    F = np.array([[r["convexity"], r["boxiness"], math.log(r["elongation"]), math.log(r["size"])] for r in fit])
    Z = (F - F.mean(0)) / F.std(0)
    centres, labels = kmeans2(Z, args.n, seed=args.seed, minit="++", iter=50)
    chosen = []
    for c in range(args.n):
        members = np.flatnonzero(labels == c)
        if len(members) == 0:
            continue
        chosen.append(members[np.argmin(np.linalg.norm(Z[members] - centres[c], axis=1))])
    # An empty cluster leaves a gap: fill it with the objects farthest from those already chosen.
    while len(chosen) < args.n:
        d = np.min(np.linalg.norm(Z[:, None] - Z[chosen][None], axis=2), axis=1)
        chosen.append(int(np.argmax(d)))
    picked = sorted((fit[i] for i in chosen), key=lambda r: r["path"])
    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    conv = sum(r["convexity"] > 0.95 for r in picked)
    boxy = sum(r["boxiness"] > 0.75 for r in picked)
    with out.open("w") as f:
        f.write(
            f"# {args.n} test objects (paths relative to pybullet_data), written by scripts/select_test_objects.py.\n"
        )
        f.write(
            f"# Candidates: the one-link mesh objects of pybullet_data ({len(rows)}); kept: narrowest horizontal width\n"
        )
        f.write(
            f"# {WIDTH[0] * 1e3:.0f}-{WIDTH[1] * 1e3:.0f} mm, height {HEIGHT[0] * 1e3:.0f}-{HEIGHT[1] * 1e3:.0f} mm as they rest, convexity >= {MIN_CONVEXITY} ({len(fit)});\n"
        )
        f.write(
            f"# chosen: one per k-means cluster (seed {args.seed}) of convexity, boxiness, log elongation, log size.\n"
        )
        f.write(
            f"# Of these, {conv} are nearly convex (volume/hull > 0.95), {args.n - conv} non-convex, {boxy} box-like (volume/box > 0.75);\n"
        )
        f.write(f"# sizes {min(r['size'] for r in picked) * 1e3:.0f}-{max(r['size'] for r in picked) * 1e3:.0f} mm.\n")
        for r in picked:
            f.write(f"{r['path']}\n")
    for r in picked:
        print(
            f"{r['path']:<32} width {r['width'] * 1e3:4.0f} mm height {r['height'] * 1e3:4.0f} mm convexity "
            f"{r['convexity']:.2f} boxiness {r['boxiness']:.2f} elongation {r['elongation']:.1f}"
        )
    print(f"[select] wrote {out} ({len(picked)} objects)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
