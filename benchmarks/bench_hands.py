"""Synthesis time per cloud with each hand against the WSG 50's, on the same clouds (issue 27: <= 2x).

    python benchmarks/bench_hands.py MODELS_DIR [--objects 12] [--repeats 3] [--seed 0] [--cache DIR]
        [--hands panda,xarm,pr2] [--experts]

MODELS_DIR is what scripts/hand_models.py wrote (MODELS_DIR/NAME/model.json); the WSG 50's model is the bundled
data/models/box_wsg50_gmm.json. The clouds: the first --objects held-out objects of data/objects/clutter_test.txt,
each alone on the table ("packed" scenes, graspmix.sim.scenes.make_scene, seeded), seen by the ring of four
simulated cameras with the depth noise model (graspmix.sim.scene_camera.acquire_scene, as
benchmarks/bench_realtime.py makes them). For every hand: GraspModel.synthesize(cloud, SynthesisOptions(seed),
viewpoints=..., target="all") once to warm up per cloud, then --repeats times; printed per hand: the median over
clouds of the per-cloud median of every stage of GraspSet.timing and of the whole call, and the ratio of the
whole call's median to the WSG 50's. --experts adds the same without contact quality and without the clear
approach (SynthesisOptions(contact_quality=None), (approach=None)): what each costs. Figures only: nothing here
asserts a time. The first line says the threads and the load average.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

import graspmix
import numpy as np
from graspmix.io import data_path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_common import load_average, machine_line  # noqa: E402

HANDS = ("panda", "xarm", "pr2")
WSG = "wsg50"


def make_clouds(n_objects: int, seed: int, cache: Path | None) -> list[tuple[str, np.ndarray, np.ndarray]]:
    """[(object, points, viewpoints)]: each of the first n held-out objects alone, four noisy views."""
    from graspmix.sim import scene_camera, scenes

    objects = [line.strip() for line in data_path("objects", "clutter_test.txt").read_text().splitlines()]
    objects = [o for o in objects if o and not o.startswith("#")][:n_objects]
    out = []
    for i, obj in enumerate(objects):
        key = f"hands-{Path(obj).stem}-s{seed + i}-v4-noise"
        path = cache / f"{key}.npz" if cache else None
        if path is not None and path.exists():
            with np.load(path) as f:
                pts, vp = f["points"], f["viewpoints"]
        else:
            spec = scenes.make_scene([obj], "packed", seed + i)
            acq = scene_camera.acquire_scene(spec, views=4, noise=True, seed=seed + i, keep="scene")
            pts, vp = np.ascontiguousarray(acq.points), np.ascontiguousarray(acq.viewpoints)
            if path is not None:
                path.parent.mkdir(parents=True, exist_ok=True)
                np.savez_compressed(path, points=pts, viewpoints=vp)
        out.append((Path(obj).stem, pts, vp))
        print(f"  cloud {len(out)}/{n_objects}: {obj}, {len(pts)} points", flush=True)
    return out


def time_hand(model, clouds, options, repeats: int) -> dict[str, list[float]]:
    """{stage: [per-cloud median seconds]} over the clouds (GraspSet.timing's stages and "whole")."""
    per_cloud: dict[str, list[float]] = {}
    for _, pts, vp in clouds:
        model.synthesize(pts, options, viewpoints=vp)
        runs: dict[str, list[float]] = {}
        for _ in range(repeats):
            t0 = time.perf_counter()
            grasps = model.synthesize(pts, options, viewpoints=vp)
            whole = time.perf_counter() - t0
            for stage, t in {**dict(grasps.timing), "whole": whole}.items():
                runs.setdefault(stage, []).append(float(t))
        for stage, ts in runs.items():
            per_cloud.setdefault(stage, []).append(statistics.median(ts))
    return per_cloud


def print_table(title: str, results: dict[str, dict[str, list[float]]]) -> None:
    print(f"\n## {title}: median over clouds of the per-cloud median (ms)")
    stages = [s for s in next(iter(results.values())) if s != "whole"] + ["whole"]
    print(f"{'hand':<8}" + "".join(f"{s[:12]:>13}" for s in stages) + f"{'x WSG 50':>10}")
    base = statistics.median(results[WSG]["whole"]) if WSG in results else float("nan")
    for hand, times in results.items():
        cells = "".join(f"{1e3 * statistics.median(times.get(s, [float('nan')])):>13.1f}" for s in stages)
        print(f"{hand:<8}{cells}{statistics.median(times['whole']) / base:>10.2f}")


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("models_dir", type=Path, help="what scripts/hand_models.py wrote")
    ap.add_argument("--hands", default=",".join(HANDS))
    ap.add_argument("--objects", type=int, default=12, help="held-out objects (first of clutter_test.txt)")
    ap.add_argument("--repeats", type=int, default=3)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--cache", type=Path, default=None, help="folder to keep the clouds in between runs")
    ap.add_argument("--experts", action="store_true", help="also time without contact quality, without approach")
    args = ap.parse_args(argv)
    print(machine_line(graspmix.__version__))
    models = {WSG: graspmix.GraspModel.load(data_path("models", "box_wsg50_gmm.json"))}
    for name in [h for h in args.hands.split(",") if h]:
        models[name] = graspmix.GraspModel.load(args.models_dir / name / "model.json")
    clouds = make_clouds(args.objects, args.seed, args.cache)
    base = graspmix.SynthesisOptions(seed=args.seed)
    variants = {"default options": base}
    if args.experts:
        variants["without contact quality"] = base.updated({"contact_quality": None})
        variants["without clear approach"] = base.updated({"approach": None})
    for title, options in variants.items():
        results = {}
        for name, model in models.items():
            results[name] = time_hand(model, clouds, options, args.repeats)
            print(f"  {title}: {name} done, load average {load_average()}", flush=True)
        print_table(f"{title}, {len(clouds)} clouds, {args.repeats} repeats", results)
    print(f"\nload average at the end: {load_average()}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
