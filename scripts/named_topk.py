"""The best K grasps of every named-target attempt of a clutter run, each executed: is a failure the ranking's (a
lower-ranked grasp lifts the object) or the candidates' (none does)? And which of a grasp's terms tell the grasps
that lift from those that do not, within one attempt?

    python scripts/named_topk.py RUN OUT.csv [--top 10] [--mode packed] [--scenes A:B] [--set part.field=value ...]

RUN is a `graspmix_cli clutter --task named` folder (its clutter.json gives the scenes, the targets, the seeds and
the synthesis options; --set changes the options). For each attempt the synthesis is repeated as the run made it,
and its best --top grasps are executed one at a time on the untouched scene as the run executes the first. OUT.csv
has a row per (attempt, rank): the outcome, log L, every term of the grasp's experts table, the approach's tilt from
straight down (degrees), the opening and the tool centre point's height. The summary printed at the end: how many
attempts the best grasp lifts, how many any of the --top lifts, and for each term the probability that, within an
attempt with both, a grasp that lifts scores higher on it than one that does not.
"""

from __future__ import annotations

import argparse
import csv
import json
import sys
from collections import defaultdict
from pathlib import Path

import numpy as np


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run")
    ap.add_argument("out")
    ap.add_argument("--top", type=int, default=10)
    ap.add_argument("--mode", default="packed")
    ap.add_argument("--scenes", default=None, metavar="A:B", help="only scenes A to B-1 (all by default)")
    ap.add_argument("--set", action="append", default=[], metavar="PART.FIELD=VALUE")
    args = ap.parse_args(argv)

    from graspmix.clutter.named import classify, named_scene, point_target
    from graspmix.clutter.protocol import clutter_protocol_from_json
    from graspmix.experiment.attempt import cached_model
    from graspmix.sim.scenes import execute_in_scene

    p = clutter_protocol_from_json(json.loads((Path(args.run) / "clutter.json").read_text())["protocol"])
    changes = {}
    for item in args.set:
        key, _, value = item.partition("=")
        changes[key] = json.loads(value)
    model = cached_model(str(p.model_path("gmm").resolve()))
    first, last = 0, p.scenes
    if args.scenes:
        try:
            first, last = (int(x) for x in args.scenes.split(":"))
        except ValueError:
            ap.error(f"--scenes must be A:B (two integers), got {args.scenes!r}")
        if not 0 <= first < last <= p.scenes:
            ap.error(f"--scenes {args.scenes}: need 0 <= A < B <= {p.scenes} (the run has scenes 0 to {p.scenes - 1})")
    rows = []
    for scene in range(first, last):
        ns = named_scene(p, args.mode, scene)
        spec, obs = ns.spec, ns.obs
        for pick, target in enumerate(ns.picks):
            opts = p.synthesis.updated({"seed": p.stage_seed("synthesis", args.mode, scene, pick), **changes})
            text = point_target(ns.point(target))
            grasps = p.synthesize(model, obs, opts, target=text)  # as the run gave its planner the camera
            grasps.add_frames()
            marks = ""
            for rank in range(min(args.top, len(grasps))):
                g = grasps[rank]
                ex = execute_in_scene(spec, g, closing=p.closing)
                outcome = classify(str(ex.result.reason), ex.lifted, target)
                down = float(np.clip(-np.asarray(g.approach)[2], -1.0, 1.0))
                row = {"scene": scene, "pick": pick, "target": spec.objects[target].urdf, "rank": rank + 1}
                row.update(outcome=outcome, success=int(outcome == "success"), log_likelihood=g.log_likelihood)
                row.update(tilt=float(np.degrees(np.arccos(down))), opening=g.opening_width, tcp_z=g.T_world_tcp[2])
                row.update(g.experts)
                rows.append(row)
                marks += "x" if row["success"] else "."
            print(f"scene {scene} pick {pick}: {marks}", flush=True)
    keys = list(dict.fromkeys(k for r in rows for k in r))
    with open(args.out, "w", newline="") as f:
        w = csv.DictWriter(f, keys)
        w.writeheader()
        w.writerows(rows)
    summarise(rows)
    return 0


def summarise(rows: list[dict]) -> None:
    attempts = defaultdict(list)
    for r in rows:
        attempts[(r["scene"], r["pick"])].append(r)
    best = sum(a[0]["success"] for a in attempts.values())
    anyone = sum(any(r["success"] for r in a) for a in attempts.values())
    top = max(len(a) for a in attempts.values())
    print(f"{len(attempts)} attempts: the best grasp lifts the target in {best}, one of the best {top} in {anyone}")
    mixed = [a for a in attempts.values() if 0 < sum(r["success"] for r in a) < len(a)]
    terms = [k for k in rows[0] if k not in ("scene", "pick", "target", "rank", "outcome", "success")]
    print(f"within the {len(mixed)} attempts with both: P(a grasp that lifts scores higher than one that does not)")
    for term in terms:
        wins = n = 0.0
        for a in mixed:
            good = [float(r.get(term, np.nan)) for r in a if r["success"]]
            bad = [float(r.get(term, np.nan)) for r in a if not r["success"]]
            for x in good:
                for y in bad:
                    if np.isfinite(x) and np.isfinite(y):
                        n += 1
                        wins += (x > y) + 0.5 * (x == y)
        if n:
            print(f"  {term:28s} {wins / n:.2f}")


if __name__ == "__main__":
    sys.exit(main())
