"""A named target among several objects, lifted or not (graspmix.clutter.named): one attempt per scene of the
clutter protocol, the library's synthesis defaults, one camera.

    python3 scripts/named_target.py --mode packed,pile --scenes 20 --out results/one-view/named.json
    python3 scripts/named_target.py --list dev --scenes 10 --out runs/named-dev.json     # the development list

Prints the success rate (Wilson 95% interval) and every outcome per mode; writes the attempts and the summary as JSON.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

from graspmix import GraspModel, SynthesisOptions, default_model_path
from graspmix.clutter.named import attempt, choose_target, summarise
from graspmix.clutter.protocol import ClutterProtocol
from graspmix.experiment.protocol import derive_seed
from graspmix.io import data_path
from graspmix.sim.scene_camera import acquire_scene
from graspmix.sim.scenes import choose_objects, make_scene


def run(args) -> dict:
    p = ClutterProtocol(object_list=str(data_path("objects", f"clutter_{args.list}.txt")), objects=args.objects)
    model = GraspModel.load(args.model or default_model_path("gmm"))
    rows = []
    t0 = time.perf_counter()
    for mode in args.mode.split(","):
        for i in range(args.scenes):
            s = p.scene_seed(mode, i)
            spec = make_scene(choose_objects(p.object_list_path, args.objects, s), mode, s)
            acq = acquire_scene(spec, views=1, noise=args.noise, seed=s)
            target = choose_target(acq.labels, len(spec.objects), derive_seed(s, "named target"))
            if target is None:
                continue
            options = SynthesisOptions(seed=derive_seed(s, "named synthesis"))
            if args.no_completion:
                options = options.updated({"completion": None})
            rows.append(attempt(model, spec, acq, target, options, mode, i, s))
            print(
                f"[{mode} {i + 1}/{args.scenes}] {rows[-1].outcome} ({time.perf_counter() - t0:.0f} s)", file=sys.stderr
            )
    return {
        "protocol": {
            "list": args.list,
            "modes": args.mode.split(","),
            "scenes": args.scenes,
            "objects": args.objects,
            "noise": args.noise,
            "completion": not args.no_completion,
            "views": 1,
            "model": Path(args.model or default_model_path("gmm")).name,
        },
        "summary": summarise(rows),
        "attempts": [r.to_dict() for r in rows],
    }


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--mode", default="packed", help="pile, packed or both (comma-separated)")
    ap.add_argument("--scenes", type=int, default=20)
    ap.add_argument("--objects", type=int, default=5)
    ap.add_argument("--list", choices=("dev", "test"), default="test", help="clutter_dev.txt or clutter_test.txt")
    ap.add_argument("--noise", action="store_true", help="the depth noise model")
    ap.add_argument("--model", help="a model file (default: the bundled GMM)")
    ap.add_argument("--no-completion", action="store_true", help="the synthesis without completion (the ablation)")
    ap.add_argument("--out", type=Path, required=True)
    args = ap.parse_args()
    out = run(args)
    for key, s in out["summary"].items():
        lo, hi = s["ci95"]
        counts = ", ".join(f"{k} {v}" for k, v in s["outcomes"].items() if v)
        print(
            f"{key}: {s['success']}/{s['attempts']} = {100 * s['rate']:.1f}% [{100 * lo:.1f}, {100 * hi:.1f}]; {counts}"
        )
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(out, indent=1) + "\n")
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
