"""Wall time of one grasp execution in Bullet (C++) and of one 4-camera acquisition (pybullet).

    python benchmarks/bench_sim.py [--objects 20] [--repeats 3]

Executions: on the first --objects test objects (data/objects/test60.txt), a top grasp over the object's
centre (held: the full close, lift and hold) and one beside it (stops after closing: "no contact"), each
--repeats times; the object is loaded once per object, as the experiment loop does. Acquisitions: the same
objects with the noise model on. The estimate of the paper's experiment counts 60 objects x 10 trials x
4 conditions x 2 methods = 4,800 executions and 60 x 10 x 2 (noise on/off) = 1,200 acquisitions.
"""

import argparse
import time

import numpy as np
from graspmix import sim
from graspmix.io import test_objects
from graspmix.sim import acquisition


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--objects", type=int, default=20)
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    objects = test_objects()[: args.objects]
    held, full, early, steps, acq = [], [], [], [], []
    for k, obj in enumerate(objects):
        print(f"[bench] {k + 1}/{len(objects)} {obj}", flush=True)
        o = sim.load_object(obj)
        pose = sim.rest_pose(obj)
        v, _ = o.model.collision_mesh(o.model.link_names[0])
        top = v[:, 2].max() + pose[2]
        good = sim.top_grasp(pose[:2], 0.055, 0.0, tip_height=max(0.01, top - 0.06))
        beside = sim.top_grasp(pose[:2] + [0.0, 0.2], 0.055, 0.0)
        for _ in range(args.repeats):
            t = time.perf_counter()
            r = sim.execute(o, good, object_pose=pose)
            dt = time.perf_counter() - t
            if r.reason in ("success", "not held"):
                full.append(dt)
                steps.append(r.steps)
            held.append(r.success)
            t = time.perf_counter()
            sim.execute(o, beside, object_pose=pose)
            early.append(time.perf_counter() - t)
        t = time.perf_counter()
        acquisition.acquire(obj, noise=True, seed=k)
        acq.append(time.perf_counter() - t)
    print(
        f"execution (full close + lift + hold, {int(np.median(steps))} steps of 1/240 s): median "
        f"{np.median(full) * 1e3:.1f} ms (min {np.min(full) * 1e3:.1f}, max {np.max(full) * 1e3:.1f}) over {len(full)}"
    )
    print(f"execution stopped after closing (no contact): median {np.median(early) * 1e3:.1f} ms over {len(early)}")
    print(
        f"4-camera acquisition (320x240, noise on): median {np.median(acq) * 1e3:.0f} ms "
        f"(min {np.min(acq) * 1e3:.0f}, max {np.max(acq) * 1e3:.0f}) over {len(acq)}"
    )
    print(f"top grasps over the centre held: {np.mean(held):.0%}")
    total = 4800 * np.median(full) + 1200 * np.median(acq)
    print(
        f"estimate for the experiment's simulation (4,800 full executions + 1,200 acquisitions): {total / 60:.1f} min "
        f"(targets: execution < 200 ms, acquisition < 1 s)"
    )


if __name__ == "__main__":
    main()
