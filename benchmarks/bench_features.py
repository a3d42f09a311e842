"""Times compute_surface_features (radius 1 cm) for 5k, 20k and 100k points; prints medians.

Two objects of fixed size, so more points means a denser cloud and larger neighbourhoods:
a 3.5 cm sphere (PCL's reference curvatures for it: docs/design.md's pitfalls), and a closed mug-sized cylinder (r 4 cm, h 10 cm).
Target: 20k points in under 0.5 s.

    python benchmarks/bench_features.py [--repeats 5] [--threads 0] [--sizes 5000 20000 100000]
"""

from __future__ import annotations

import argparse
import os
import time

import graspmix
import numpy as np


def sphere(n, rng, R=0.035):
    v = rng.normal(size=(n, 3))
    return R * v / np.linalg.norm(v, axis=1, keepdims=True)


def closed_cylinder(n, rng, R=0.04, h=0.10):
    side, cap = 2 * np.pi * R * h, np.pi * R * R
    on_side = rng.uniform(size=n) < side / (side + 2 * cap)
    a = rng.uniform(0, 2 * np.pi, n)
    rho = np.where(on_side, R, R * np.sqrt(rng.uniform(size=n)))
    z = np.where(on_side, rng.uniform(-h / 2, h / 2, n), np.where(rng.uniform(size=n) < 0.5, -h / 2, h / 2))
    return np.c_[rho * np.cos(a), rho * np.sin(a), z]


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--sizes", type=int, nargs="+", default=[5000, 20000, 100000])
    p.add_argument("--repeats", type=int, default=5, help="timed runs per size (3 for 100k and more)")
    p.add_argument("--threads", type=int, default=0, help="OpenMP threads (0: default)")
    p.add_argument("--radius", type=float, default=0.01)
    args = p.parse_args()
    rng = np.random.default_rng(0)
    print(
        f"graspmix {graspmix.__version__}, PCL {graspmix.build_info().get('pcl', '?')}, "
        f"{os.cpu_count()} cores, load average {os.getloadavg()[0]:.1f}, radius {args.radius} m"
    )
    print(
        f"{'object':<14}{'points':>8}{'neighbours':>12}{'median s':>10}{'normals':>9}{'orient':>8}{'curv':>8}{'min s':>8}"
    )
    for name, make in [("sphere 3.5cm", sphere), ("mug cylinder", closed_cylinder)]:
        for n in args.sizes:
            P = make(n, rng)
            graspmix.compute_surface_features(P, args.radius, n_threads=args.threads)  # warm-up
            runs = []
            for _ in range(args.repeats if n < 100000 else min(args.repeats, 3)):
                t = time.perf_counter()
                s = graspmix.compute_surface_features(P, args.radius, n_threads=args.threads)
                runs.append((time.perf_counter() - t, s.timings))
            med = float(np.median([r[0] for r in runs]))
            stage = {k: float(np.median([r[1][k] for r in runs])) for k in ("normals", "orientation", "curvatures")}
            print(
                f"{name:<14}{n:>8}{int(np.median(s.neighbours)):>12}{med:>10.3f}{stage['normals']:>9.3f}"
                f"{stage['orientation']:>8.3f}{stage['curvatures']:>8.3f}{min(r[0] for r in runs):>8.3f}",
                flush=True,
            )


if __name__ == "__main__":
    main()
