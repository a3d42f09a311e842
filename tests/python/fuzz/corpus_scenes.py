"""Clouds that hold no object: a table alone, noisy or not, seen from a camera above it or from none (the PCD
convention's camera at the origin, in the table's own plane), and a plane too sparse to hold a cluster.
`synthesize` and `segment` must say there is no object instead of ranking grasps on fragments of the table's
noise; a table with a box on it, as noisy, still has its box."""

from __future__ import annotations

import random
import struct

from cases import api, cli

SEED = 20261126


def table(n: int, sigma: float, half: float = 0.3, seed: int = SEED) -> list[tuple[float, float, float]]:
    """n points on the square table |x|, |y| <= half at z = 0, heights with Gaussian noise sigma (m)."""
    rng = random.Random(seed)
    return [(rng.uniform(-half, half), rng.uniform(-half, half), rng.gauss(0.0, sigma)) for _ in range(n)]


def pcd(points, viewpoint=(0.0, 0.0, 0.0)) -> bytes:
    """A binary PCD of float32 x y z seen from `viewpoint` (the header's VIEWPOINT, identity rotation)."""
    vp = " ".join(f"{v:g}" for v in viewpoint)
    header = (
        "# .PCD v0.7\nVERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n"
        f"WIDTH {len(points)}\nHEIGHT 1\nVIEWPOINT {vp} 1 0 0 0\nPOINTS {len(points)}\nDATA binary\n"
    )
    return header.encode() + b"".join(struct.pack("<3f", *p) for p in points)


ABOVE = (0.0, 0.0, 1.0)
# Seeds and noises at which the support is found and the table's noise above table_clearance used to fall apart
# into clusters taken for objects (graspmix before the table-noise rule ranked grasps on them).
CLOUDS = {
    # name: (file bytes, what the error names)
    "table-1mm-camera-above": (pcd(table(20000, 0.001), ABOVE), "no object above the support plane"),
    "table-4mm-camera-above": (pcd(table(20000, 0.004, seed=4), ABOVE), "no object above the support plane"),
    "table-1cm-camera-above": (pcd(table(20000, 0.01, seed=0), ABOVE), "no object above the support plane"),
    "table-4mm-no-camera": (pcd(table(20000, 0.004)), "camera"),
    "table-exact-no-camera": (pcd(table(5000, 0.0)), "camera"),
    "table-sparse-no-camera": (pcd(table(600, 0.0, half=0.2)), "camera"),
}


def cli_cases():
    cases = []
    for name, (data, says) in CLOUDS.items():
        files = {"cloud.pcd": data}
        cases.append(cli(f"scene/segment-{name}", "segment", "--cloud", "{tmp}/cloud.pcd", files=files, names=(says,)))
        cases.append(
            cli(
                f"scene/synthesize-{name}",
                "synthesize",
                "--cloud",
                "{tmp}/cloud.pcd",
                "--out",
                "{tmp}/g.json",
                files=files,
                names=(says, "segment_scene"),
            )
        )
    return cases


def noisy_table(sigma: float, seed: int) -> str:
    """Code that makes `pts`, a table of 20000 points with Gaussian height noise sigma, and `rng`."""
    return (
        f"import numpy as np\nrng = np.random.default_rng({seed})\n"
        f"pts = np.c_[rng.uniform(-0.3, 0.3, (20000, 2)), rng.normal(0.0, {sigma}, 20000)]\n"
    )


def box(sigma: float) -> str:
    """Code that adds to `pts` a 6 cm cube's top and one side, as noisy as the table, at the table's centre."""
    return (
        f"top = np.c_[rng.uniform(-0.03, 0.03, (3000, 2)), 0.06 + rng.normal(0.0, {sigma}, 3000)]\n"
        "side = np.c_[rng.uniform(-0.03, 0.03, 2000), np.full(2000, 0.03), rng.uniform(0.0, 0.06, 2000)]\n"
        "pts = np.r_[pts, top, side]\n"
    )


def api_cases():
    return [
        api(
            "scene/segment_scene-noisy-table",
            noisy_table(0.004, 10) + "graspmix.segment_scene(pts, [0, 0, 1])",
            names=("no object above the support plane",),
            group="scene",
        ),
        api(
            "scene/ok-segment_scene-noisy-table-with-a-box",
            noisy_table(0.005, 4) + box(0.005) + "s = graspmix.segment_scene(pts, [0, 0, 1])\n"
            "assert s.plane is not None and len(s.objects) == 1, [o.n_points for o in s.objects]\n"
            "assert np.linalg.norm(s.objects[0].centroid[:2]) < 0.02",
            expect="ok",
            group="scene",
        ),
    ]


CASES = cli_cases() + api_cases()
