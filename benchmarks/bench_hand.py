"""Throughput of the WSG 50's batched fk and of the collision expert against a 5k-point cloud.

    python benchmarks/bench_hand.py [--points 5000] [--hands 20000] [--repeats 5] [--seed 0]

The cloud is a mug-sized cylinder (radius 4 cm, height 12 cm, side and top cap) standing on a table
z = 0, the support plane passed to the expert. Wrists are sampled on a sphere around it, approaching its
axis, at distances where roughly half of the grasps collide, as in annealing. Figures are medians over
repeats; OMP_NUM_THREADS bounds the threads (the batched calls are OpenMP-parallel).
"""

import argparse
import os
import time

import graspmix
import numpy as np
from graspmix.io import data_path
from scipy.spatial.transform import Rotation


def mug_cloud(n, rng):
    side = int(n * 0.8)
    a = rng.uniform(0, 2 * np.pi, side)
    z = rng.uniform(0, 0.12, side)
    pts = [np.c_[0.04 * np.cos(a), 0.04 * np.sin(a), z]]
    r = 0.04 * np.sqrt(rng.uniform(0, 1, n - side))
    b = rng.uniform(0, 2 * np.pi, n - side)
    pts.append(np.c_[r * np.cos(b), r * np.sin(b), np.full(n - side, 0.12)])
    return np.vstack(pts)


def wrists_around(n, rng):
    """Wrists whose approach axis (z) points at the mug's axis, from distances 12-26 cm."""
    d = rng.normal(size=(n, 3))
    d[:, 2] = np.abs(d[:, 2])
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    target = np.c_[np.zeros(n), np.zeros(n), rng.uniform(0.02, 0.12, n)]
    dist = rng.uniform(0.12, 0.26, n)
    pos = target + d * dist[:, None]
    z = -d
    helper = np.where(np.abs(z[:, 2:3]) < 0.9, [[0, 0, 1.0]], [[1.0, 0, 0]])
    x = np.cross(helper, z)
    x /= np.linalg.norm(x, axis=1, keepdims=True)
    spin = rng.uniform(0, 2 * np.pi, n)
    y = np.cross(z, x)
    x, y = np.cos(spin)[:, None] * x + np.sin(spin)[:, None] * y, -np.sin(spin)[:, None] * x + np.cos(spin)[:, None] * y
    R = np.stack([x, y, z], axis=2)
    return np.c_[pos, Rotation.from_matrix(R).as_quat()]


def median_rate(fn, n, repeats):
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return n / np.median(times), np.median(times)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--points", type=int, default=5000)
    ap.add_argument("--hands", type=int, default=20000)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args()
    rng = np.random.default_rng(args.seed)

    hand = graspmix.Hand.from_urdf(data_path("hands", "wsg50.urdf"))
    cloud = mug_cloud(args.points, rng)
    wrists = wrists_around(args.hands, rng)
    joints = rng.uniform(0.0, 0.055, (args.hands, 1))

    t0 = time.perf_counter()
    expert = graspmix.CollisionExpert(hand, cloud, plane=[0, 0, 1, 0])
    build = time.perf_counter() - t0

    print(
        f"graspmix {graspmix.__version__}: WSG 50 ({hand.n_links} links), cloud of {len(cloud)} points, "
        f"{args.hands} hands, OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'unset')}, "
        f"{os.cpu_count()} CPUs, median of {args.repeats}"
    )
    rate, t = median_rate(lambda: hand.fk_batch(wrists, joints), args.hands, args.repeats)
    print(f"fk_batch:                  {rate:12,.0f} hands/s   ({t * 1e3:.1f} ms per batch)")
    rate, t = median_rate(lambda: expert.evaluate_batch(wrists, joints), args.hands, args.repeats)
    res = expert.evaluate_batch(wrists, joints)
    print(
        f"collision evaluate_batch:  {rate:12,.0f} evals/s   ({t * 1e3:.1f} ms per batch; "
        f"{100 * (1 - res.collision_free.mean()):.0f}% in collision, index built in {build * 1e3:.1f} ms, "
        f"cell {expert.cell_size * 1e3:.1f} mm)"
    )
    n_single = min(2000, args.hands)
    rate, t = median_rate(
        lambda: [expert.evaluate(wrists[i], joints[i]) for i in range(n_single)], n_single, args.repeats
    )
    print(f"collision evaluate (one call per hand, from Python): {rate:,.0f} evals/s")
    print("target: >= 20,000 collision evaluations per second (batched)")


if __name__ == "__main__":
    main()
