"""Times the visibility model on one 640x480 view: building it (from a depth image, an organized cloud, the
unorganized points) and classifying a million points; prints medians. One OpenMP thread unless --threads.

The view: a depth camera 0.8 m from a table seen at 45 degrees with three boxes on it (ray-cast in numpy,
fx = fy = 525 px, every 50th pixel without a return); the million points are uniform in the boxes' region.

    python benchmarks/bench_visibility.py [--repeats 7] [--points 1000000] [--threads 1]
"""

from __future__ import annotations

import argparse
import os

import numpy as np
from bench_common import load_average, machine_line, median_seconds

BOXES = [
    ((-0.10, -0.05, 0.0), (0.0, 0.05, 0.12)),
    ((0.05, -0.08, 0.0), (0.12, 0.0, 0.06)),
    ((0.0, 0.08, 0.0), (0.08, 0.15, 0.2)),
]


def camera_pose(eye, target):
    """T_world_camera (4 x 4) of a camera at eye looking at target, world z up; x right, y down, z forward."""
    z = np.subtract(target, eye) / np.linalg.norm(np.subtract(target, eye))
    x = np.cross(z, [0, 0, 1.0])
    x /= np.linalg.norm(x)
    T = np.eye(4)
    T[:3, :3] = np.c_[x, np.cross(z, x), z]
    T[:3, 3] = eye
    return T


def render(K, T):
    """Depth image (H, W) of the table z = 0 and BOXES, at each pixel centre."""
    h, w = K.height, K.width
    v, u = np.mgrid[0:h, 0:w]
    rays = np.stack([(u - K.cx) / K.fx, (v - K.cy) / K.fy, np.ones((h, w))], axis=-1) @ T[:3, :3].T
    o = T[:3, 3]
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(rays[..., 2] < 0, -o[2] / rays[..., 2], np.inf)
        for lo, hi in BOXES:
            a, b = (np.asarray(lo) - o) / rays, (np.asarray(hi) - o) / rays
            t0, t1 = np.minimum(a, b).max(axis=-1), np.maximum(a, b).min(axis=-1)
            t = np.where((t0 <= t1) & (t0 > 0), np.minimum(t, t0), t)
    depth = t.copy()  # rays have camera z = 1, so t is the depth
    depth.ravel()[::50] = np.nan
    return depth


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=7)
    p.add_argument("--points", type=int, default=1_000_000)
    p.add_argument("--threads", type=int, default=1, help="OMP_NUM_THREADS (set before graspmix loads)")
    args = p.parse_args()
    os.environ["OMP_NUM_THREADS"] = str(args.threads)
    import graspmix
    from graspmix import PinholeCamera, VisibilityModel
    from scipy.spatial.transform import Rotation

    K = PinholeCamera(525.0, 525.0, 319.5, 239.5, 640, 480)
    T = camera_pose([0.0, -0.57, 0.57], [0.0, 0.0, 0.0])
    pose = np.r_[T[:3, 3], Rotation.from_matrix(T[:3, :3]).as_quat()]
    depth = render(K, T)
    organized = K.back_project(depth)
    valid = organized[np.isfinite(organized[..., 0])]
    world = valid @ T[:3, :3].T + T[:3, 3]
    rng = np.random.default_rng(0)
    points = rng.uniform([-0.15, -0.15, -0.02], [0.17, 0.2, 0.25], size=(args.points, 3))

    print(machine_line(graspmix.__version__))
    print(f"view: 640x480, {len(world)} returns; {args.points} query points; medians of {args.repeats} runs")
    models = {
        "from_depth": lambda: VisibilityModel.from_depth(depth, K, pose),
        "from_organized": lambda: VisibilityModel.from_organized(organized, pose),
        "from_points": lambda: VisibilityModel.from_points(world, T[:3, 3]),
    }
    print(
        f"{'model':<16}{'build ms':>10}{'classify s/M':>14}{'distance s/M':>14}{'ns/point':>10}  states (free, surface, unseen)"
    )
    for name, build in models.items():
        built = median_seconds(build, args.repeats)
        model = build()
        classify = median_seconds(lambda m=model: m.classify(points), args.repeats)
        distance = median_seconds(lambda m=model: m.signed_distance(points), args.repeats)
        per_million = 1e6 / args.points
        counts = np.bincount(model.classify(points), minlength=3) / args.points
        print(
            f"{name:<16}{1e3 * built:>10.2f}{classify * per_million:>14.4f}{distance * per_million:>14.4f}"
            f"{1e9 * classify / args.points:>10.1f}  {counts[0]:.3f}, {counts[1]:.3f}, {counts[2]:.3f}",
            flush=True,
        )
    print(f"load average after: {load_average()}")


if __name__ == "__main__":
    main()
