"""How far lighter sampling settings take the whole path on one object's depth image (issue 26's 20 ms target).

    python benchmarks/bench_lighter.py [--repeats 9] [--cache DIR]

The single-object depth images of bench_realtime.py (the same scenes, seeds and cache), GMM, target "largest":
per variant of the sampling settings, the median over the scenes of each scene's median whole call and of its
stages. The variants lighten what the defaults draw and anneal, down to half the annealing steps and half the query
samples; none of them is measured here for grasp success (a variant that would become a default must be measured on
the development sets first). What no variant changes (the segmentation, the surface features and the maps) is the
path's floor. A stage a call did not time (occupancy without a map) counts 0. Without --cache the clouds of every
bench_realtime.py scene kind are made first. Figures only: nothing here asserts a time.
"""

from __future__ import annotations

import argparse
import os
import statistics
from pathlib import Path

import bench_realtime as realtime
import graspmix
from graspmix.io import data_path

VARIANTS = {
    "defaults": {},
    "oversample 1": {"sampling.oversample": 1},
    "100 samples, oversample 1, 5 annealed": {
        "sampling.n_samples": 100,
        "sampling.oversample": 1,
        "sampling.n_optimise": 5,
    },
    "the same, 50 annealing steps, 250 query samples": {
        "sampling.n_samples": 100,
        "sampling.oversample": 1,
        "sampling.n_optimise": 5,
        "annealing.iterations": 50,
        "query.n_samples": 250,
    },
}
STAGES = ("segmentation", "occupancy", "features", "query", "sampling", "optimisation", "outside", "whole")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=9)
    ap.add_argument("--cache", type=Path, help="bench_realtime.py's cache of scene clouds")
    args = ap.parse_args()
    if args.repeats < 1:
        ap.error("--repeats must be at least 1")

    scenes = realtime.make_clouds(argparse.Namespace(quick=False, seed=0, noise=True, cache=args.cache))
    scenes = scenes["single object, 1 depth image"]
    model = graspmix.GraspModel.load(data_path("models", "box_wsg50_gmm.json"))
    print(realtime.machine("start"))
    print(f"GMM, target largest, {len(scenes)} single-object depth images, medians of {args.repeats} calls each")
    print(f"{'variant':48s}" + "".join(f"{s:>13s}" for s in STAGES) + "   (ms)")
    # Per scene every variant in turn, so that a drift of the host's load falls on all of them alike.
    per_stage: dict[str, dict[str, list[float]]] = {name: {} for name in VARIANTS}
    for _, _, inputs in scenes:
        for name, changes in VARIANTS.items():
            times, _ = realtime.time_synthesis(model, inputs, args.repeats, 0, **changes)
            for stage in STAGES:
                per_stage[name].setdefault(stage, []).append(statistics.median(times.get(stage, [0.0])))
    for name in VARIANTS:
        print(f"{name:48s}" + "".join(f"{1000 * statistics.median(per_stage[name][s]):13.1f}" for s in STAGES))
    print(realtime.machine("end"))
    print(f"OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', '(unset)')}")


if __name__ == "__main__":
    main()
