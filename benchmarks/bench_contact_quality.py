"""Throughput of the contact-quality expert: the WSG 50 closing on a 2k-point mug cloud with exact normals.

    OMP_NUM_THREADS=1 python benchmarks/bench_contact_quality.py [--points 2000] [--grasps 1000] [--repeats 7]

The cloud is a mug-sized cylinder (radius 4 cm, height 12 cm, side and top cap). Wrists approach its axis
from 10-15 cm (the fingers reach 8-15 cm beyond the wrist, so the mug lies between them), spun about the
approach at random; the joints are uniform over 0-45 mm and the pre-grasp opens each by 20 mm, as the
default model's does; a second figure takes only grasps whose fingers start clear of the mug. Figures are
medians over repeats. The issue's budget: about 1,200 grasps per synthesis
(200 samples + 10 x 100 annealing steps) well under 10 ms, i.e. >= ~150k grasps/s.
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
    nrm = [np.c_[np.cos(a), np.sin(a), np.zeros(side)]]
    r = 0.04 * np.sqrt(rng.uniform(0, 1, n - side))
    b = rng.uniform(0, 2 * np.pi, n - side)
    pts.append(np.c_[r * np.cos(b), r * np.sin(b), np.full(n - side, 0.12)])
    nrm.append(np.tile([0.0, 0.0, 1.0], (n - side, 1)))
    return np.vstack(pts), np.vstack(nrm)


def wrists_around(n, rng):
    """Wrists whose approach axis (z) points at the mug's axis from 10-15 cm, spun at random about it."""
    d = rng.normal(size=(n, 3))
    d[:, 2] = np.abs(d[:, 2])
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    target = np.c_[np.zeros(n), np.zeros(n), rng.uniform(0.02, 0.12, n)]
    pos = target + d * rng.uniform(0.10, 0.15, n)[:, None]
    z = -d
    helper = np.where(np.abs(z[:, 2:3]) < 0.9, [[0, 0, 1.0]], [[1.0, 0, 0]])
    x = np.cross(helper, z)
    x /= np.linalg.norm(x, axis=1, keepdims=True)
    y = np.cross(z, x)
    spin = rng.uniform(0, 2 * np.pi, n)[:, None]
    x, y = np.cos(spin) * x + np.sin(spin) * y, -np.sin(spin) * x + np.cos(spin) * y
    return np.c_[pos, Rotation.from_matrix(np.stack([x, y, z], axis=2)).as_quat()]


def median_seconds(fn, repeats):
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return float(np.median(times))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--points", type=int, default=2000)
    ap.add_argument("--grasps", type=int, default=1000)
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args()
    rng = np.random.default_rng(args.seed)

    hand = graspmix.Hand.from_urdf(data_path("hands", "wsg50.urdf"))
    points, normals = mug_cloud(args.points, rng)
    config = graspmix.ConfigModel([0.05], [0.03], [[0.0, 0.055]])
    wrists = wrists_around(args.grasps, rng)
    joints = rng.uniform(0.0, 0.045, (args.grasps, 1))
    t0 = time.perf_counter()
    expert = graspmix.ContactQualityExpert(hand, points, normals, config)
    build = time.perf_counter() - t0

    print(
        f"graspmix {graspmix.__version__}: WSG 50, mug cloud of {len(points)} points, {args.grasps} grasps, "
        f"OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'unset')}, {os.cpu_count()} CPUs, "
        f"median of {args.repeats}; expert built in {build * 1e3:.2f} ms"
    )
    t = median_seconds(lambda: expert.log_value(wrists, joints), args.repeats)
    r = expert.evaluate(wrists, joints)
    touched = (r.patch_size > 0).sum(axis=1)
    print(
        f"log_value (one batch):      {args.grasps / t:12,.0f} grasps/s ({t * 1e3:.2f} ms per batch; "
        f"{np.mean(touched == 2):.0%} two contacts, {np.mean(touched == 1):.0%} one, {np.mean(touched == 0):.0%} none; "
        f"{np.mean(r.log_value == 0):.0%} score 0; mean patch {r.patch_size[r.patch_size > 0].mean():.1f} points)"
    )
    # Most of those grasps start with a finger already in the mug's wall (t = 0: the whole finger's volume is
    # the patch); grasps that survive the collision expert start clear of it.
    pool_w, pool_q = wrists_around(20 * args.grasps, rng), rng.uniform(0.0, 0.045, (20 * args.grasps, 1))
    clear = np.flatnonzero((expert.evaluate(pool_w, pool_q).t > 0).all(axis=1))[: args.grasps]
    t = median_seconds(lambda: expert.log_value(pool_w[clear], pool_q[clear]), args.repeats)
    print(
        f"log_value (clear pre-grasps): {len(clear) / t:10,.0f} grasps/s ({len(clear)} grasps, both fingers at t > 0)"
    )
    chunks = [slice(i, i + 10) for i in range(0, args.grasps, 10)]
    t = median_seconds(lambda: [expert.log_value(wrists[c], joints[c]) for c in chunks], args.repeats)
    print(f"log_value (batches of 10):  {args.grasps / t:12,.0f} grasps/s (annealing's batch size, from Python)")
    print("target: >= ~150,000 grasps/s (1,200 grasps of a synthesis well under 10 ms)")


if __name__ == "__main__":
    main()
