"""Times segment_scene (plus a target selection) against prepare_cloud on the same single 640x480 view of
a table with objects (pybullet, the acquisition's noise model); prints medians and the difference.
Target (issue 12): segmentation costs < 10 ms more than prepare_cloud.

    python benchmarks/bench_segmentation.py [--repeats 7] [--width 640 --height 480] [--no-noise]
"""

from __future__ import annotations

import argparse
import statistics
import time

import graspmix
import numpy as np
from graspmix.sim.acquisition import AcquisitionSettings, Camera, acquire


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--repeats", type=int, default=7)
    p.add_argument("--width", type=int, default=640)
    p.add_argument("--height", type=int, default=480)
    p.add_argument("--object", default="objects/mug.urdf")
    p.add_argument("--no-noise", action="store_true")
    args = p.parse_args()
    cam = Camera(eye=(0.5, 0.1, 0.45), width=args.width, height=args.height)
    acq = acquire(
        args.object, noise=not args.no_noise, seed=0, settings=AcquisitionSettings(cameras=[cam], keep="scene")
    )
    pts, vp = acq.points, acq.viewpoints
    seg, seg_select, prep = [], [], []
    for _ in range(args.repeats):
        t = time.perf_counter()
        scene = graspmix.segment_scene(pts, vp)
        scene.select("nearest")
        seg_select.append(time.perf_counter() - t)
        seg.append(scene.result.seconds)
        prep.append(graspmix.prepare_cloud(pts).seconds)
    ms = lambda v: 1e3 * statistics.median(v)  # noqa: E731
    print(
        f"cloud: {len(pts)} points ({args.width}x{args.height}, noise {not args.no_noise}), {len(scene.objects)} objects, plane {np.round(scene.plane, 4)}"
    )
    print(f"prepare_cloud (voxel, outliers, RANSAC plane)  median {ms(prep):8.1f} ms")
    print(f"segment_scene (C++ seconds)                    median {ms(seg):8.1f} ms")
    print(f"segment_scene + Scene + select('nearest')      median {ms(seg_select):8.1f} ms")
    print(
        f"difference (segment_scene + selection - prepare_cloud): {ms(seg_select) - ms(prep):+.1f} ms (target < +10 ms)"
    )


if __name__ == "__main__":
    main()
