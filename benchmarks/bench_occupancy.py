"""Times the occupancy collision model against the surface model on one 640x480 view of an object on a
table: the map's construction (OctoMap ray insertion and baking) and W's evaluations per second over
the same batch of wrists sampled around the object; prints medians and the ratio.

    python benchmarks/bench_occupancy.py [--repeats 5] [--hands 2000] [--resolution 0.005] [--object X]
"""

from __future__ import annotations

import argparse
import statistics
import time

import graspmix
import numpy as np
from graspmix import SynthesisOptions
from graspmix.model.experts import collision_expert, occupancy_map
from graspmix.sim.acquisition import AcquisitionSettings, Camera, acquire


def random_wrists(centre: np.ndarray, n: int, rng: np.random.Generator) -> np.ndarray:
    """n wrists within 12 cm of centre, uniformly random orientations."""
    q = rng.normal(size=(n, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    return np.c_[centre + rng.uniform(-0.12, 0.12, size=(n, 3)), q]


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--hands", type=int, default=2000)
    p.add_argument("--resolution", type=float, default=SynthesisOptions().occupancy.resolution)
    p.add_argument("--object", default="objects/mug.urdf")
    args = p.parse_args()
    cam = Camera(eye=(0.0, -0.55, 0.55), width=640, height=480)
    acq = acquire(args.object, noise=False, seed=0, settings=AcquisitionSettings(cameras=[cam], keep="scene"))
    scene = graspmix.segment_scene(acq.points, acq.viewpoints)
    opts = SynthesisOptions().updated({"occupancy.resolution": args.resolution})
    hand = graspmix.GraspModel.load(graspmix.default_model_path()).hand
    build = []
    for _ in range(args.repeats):
        t = time.perf_counter()
        occ = occupancy_map(acq.points, acq.viewpoints, scene.points, scene.plane, opts)
        build.append(time.perf_counter() - t)
    experts = {
        "surface": collision_expert(hand, scene.points, scene.plane, opts),
        "occupancy": collision_expert(hand, scene.points, scene.plane, opts, occ),
    }
    rng = np.random.default_rng(0)
    wrists = random_wrists(scene.points.mean(axis=0), args.hands, rng)
    joints = np.tile(np.asarray(hand.joint_limits, float).mean(axis=1), (args.hands, 1))  # half open
    rates = {}
    for name, e in experts.items():
        times = []
        for _ in range(args.repeats):
            t = time.perf_counter()
            e.evaluate_batch(wrists, joints)
            times.append(time.perf_counter() - t)
        rates[name] = args.hands / statistics.median(times)
    s = occ.stats
    print(f"cloud: {len(acq.points)} points (640x480, one camera), {len(scene.points)} object points")
    print(
        f"occupancy map: resolution {args.resolution * 1e3:.1f} mm, {tuple(occ.dims)} cells, {s['n_rays']} rays, "
        f"{s['n_free']} free / {s['n_occupied']} occupied / {s['n_unknown']} unknown; "
        f"build median {1e3 * statistics.median(build):.1f} ms"
    )
    for name, r in rates.items():
        print(f"{name:9s} W: {r:10.0f} evaluations/s (batch of {args.hands})")
    print(f"ratio occupancy / surface: {rates['occupancy'] / rates['surface']:.2f}")


if __name__ == "__main__":
    main()
