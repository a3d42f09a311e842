"""Synthesis time against the number of grasp types of a GMM model (expected: linear).

    python3 benchmarks/bench_types.py [--repeats 3]

Models of 1, 2 and 4 types are learnt from the bundled WSG 50 demonstrations (the box top grasp and the
mug side grasp; 4 types: both twice, under other names). Each synthesises the default 200 grasps per type
and optimises its best 10 on the bundled mug scene (data/mug.pcd) and on the two demonstration clouds.
Prints, per model, the median over clouds (of the median over repeats) of the synthesis stages (query,
sampling and ranking, optimisation: summed over types; segmentation and features are done once), and the
median over clouds of that time over the sum of its types' times as single-type models (1: linear; the
types differ in cost, so the count of types alone is no yardstick).
"""

import argparse
import statistics

import graspmix

STAGES = ["query", "sampling", "optimisation"]


def models() -> dict:
    """name -> (model, how many box and mug types it has)."""
    box, mug = (str(graspmix.data_path("demos", f)) for f in ("box_wsg50.json", "mug_side_wsg50.json"))
    return {
        "box": (graspmix.learn([box]), (1, 0)),
        "mug side": (graspmix.learn([mug]), (0, 1)),
        "box + mug side": (graspmix.learn([box, mug]), (1, 1)),
        "both twice": (graspmix.learn([box, mug, f"box2={box}", f"mug2={mug}"]), (2, 2)),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args()
    clouds = {
        "mug scene": (graspmix.data_path("mug.pcd"), {}),
        "box demo": (graspmix.data_path("demos", "box.pcd"), {"segmentation.find_plane": False}),
        "mug demo": (graspmix.data_path("demos", "mug_side.pcd"), {"segmentation.find_plane": False}),
    }
    per = {}  # (model, cloud) -> median over repeats of the stages' sum
    built = models()
    for n, (model, _) in built.items():
        for name, (cloud, kw) in clouds.items():
            options = [graspmix.SynthesisOptions().updated({**kw, "seed": r}) for r in range(args.repeats)]
            runs = [model.synthesize(cloud, o).timing for o in options]
            per[n, name] = statistics.median(sum(t[s] for s in STAGES) for t in runs)
    print(f"{'model':<16} {'types':>5} {'stages (ms)':>12} {'/ sum of its types alone':>25}")
    for n, (model, (boxes, mugs)) in built.items():
        med = statistics.median(per[n, c] for c in clouds)
        ratio = statistics.median(per[n, c] / (boxes * per["box", c] + mugs * per["mug side", c]) for c in clouds)
        print(f"{n:<16} {len(model.types):>5} {med * 1e3:>12.1f} {ratio:>25.2f}")
    print(
        f"medians over {len(clouds)} clouds (each the median of {args.repeats} repeats); the ratio is the median "
        "over clouds of the stages' time over the sum of the single-type models' times (linear: 1)"
    )


if __name__ == "__main__":
    main()
