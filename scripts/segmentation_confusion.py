"""Objects found vs placed by segment_scene over one-view clutter scenes, before and after the join rule.

    python3 scripts/segmentation_confusion.py --scenes 20 --out results/segmentation/confusion.json
    python3 scripts/segmentation_confusion.py --lists dev --split --out results/segmentation/split-dev.json

Per object list (clutter_dev: the rule's thresholds were chosen on it; clutter_test: reported only) and mode
(pile, packed): the clutter protocol's scenes (make_scene with its scene seeds, 5 objects), observed as a round
observes them (acquire_scene: one 640x480 camera), segmented with the join rule off and on (and, with --split, the join and split rules on); each cluster judged
against the renderer's per-point object ids (graspmix.clutter.confusion: one object, a piece of one, several
objects). Prints a table and writes the per-scene counts and the totals as JSON.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np
from graspmix.clutter.confusion import confusion_of, total
from graspmix.clutter.protocol import MODES, ClutterProtocol
from graspmix.io import data_path
from graspmix.sim.scene_camera import acquire_scene
from graspmix.sim.scenes import choose_objects, make_scene

COLUMNS = ("scenes", "placed", "visible", "found", "one", "piece", "merged", "other", "missed", "scenes_exact")


def run(lists, modes, scenes, objects, seed, noise, split=False):
    out = {
        "protocol": {
            "lists": lists,
            "modes": modes,
            "scenes": scenes,
            "objects": objects,
            "seed": seed,
            "noise": noise,
            "views": 1,
            "split": split,
        },
        "results": [],
    }
    for name in lists:
        p = ClutterProtocol(object_list=str(data_path("objects", f"clutter_{name}.txt")), objects=objects, seed=seed)
        for mode in modes:
            configs = [(False, False), (True, False)] + ([(True, True)] if split else [])
            rows = {c: [] for c in configs}
            join_ms, split_ms = [], []
            for i in range(scenes):
                s = p.scene_seed(mode, i)
                spec = make_scene(choose_objects(p.object_list_path, objects, s), mode, s)
                acq = acquire_scene(spec, views=1, noise=noise, seed=s)
                for on, cut in configs:
                    c, scene = confusion_of(acq, len(spec.objects), join_occluded=on, split_touching=cut)
                    rows[(on, cut)].append(c)
                    if on and not cut:
                        join_ms.append(1e3 * scene.timing["segmentation.join"])
                    if cut:
                        split_ms.append(1e3 * scene.timing["segmentation.split"])
            for on, cut in configs:
                out["results"].append(
                    {
                        "list": name,
                        "mode": mode,
                        "join": on,
                        "split": cut,
                        "total": total(rows[(on, cut)]),
                        "scenes": [r.to_dict() for r in rows[(on, cut)]],
                    }
                )
                if on and not cut:
                    out["results"][-1]["join_ms"] = {"median": float(np.median(join_ms)), "max": float(np.max(join_ms))}
                if cut:
                    out["results"][-1]["split_ms"] = {
                        "median": float(np.median(split_ms)),
                        "max": float(np.max(split_ms)),
                    }
    return out


def table(out) -> str:
    lines = [
        "| objects | mode | join rule | split rule | " + " | ".join(COLUMNS) + " |",
        "|" + " --- |" * (len(COLUMNS) + 4),
    ]
    for r in out["results"]:
        t = r["total"]
        lines.append(
            f"| {r['list']} | {r['mode']} | {'on' if r['join'] else 'off'} | {'on' if r.get('split') else 'off'} | "
            + " | ".join(str(t[c]) for c in COLUMNS)
            + " |"
        )
    return "\n".join(lines)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--lists", default="dev,test", help="clutter object lists: dev, test or both")
    ap.add_argument("--modes", default=",".join(MODES))
    ap.add_argument("--scenes", type=int, default=20, help="scenes per list and mode")
    ap.add_argument("--objects", type=int, default=5, help="objects placed per scene")
    ap.add_argument("--seed", type=int, default=0, help="the clutter protocol's seed (its scene seeds)")
    ap.add_argument("--noise", action="store_true", help="the depth noise model")
    ap.add_argument("--split", action="store_true", help="also the join and split rules on (split_touching)")
    ap.add_argument("--out", type=Path, help="write the counts as JSON here")
    a = ap.parse_args()
    lists, modes = a.lists.split(","), a.modes.split(",")
    if any(n not in ("dev", "test") for n in lists) or any(m not in MODES for m in modes) or a.scenes < 1:
        raise SystemExit(
            "segmentation_confusion: --lists is dev and/or test, --modes pile and/or packed, --scenes >= 1"
        )
    t0 = time.time()
    out = run(lists, modes, a.scenes, a.objects, a.seed, a.noise, a.split)
    print(table(out))
    for r in out["results"]:
        for rule in ("join", "split"):
            if f"{rule}_ms" in r:
                ms = r[f"{rule}_ms"]
                print(
                    f"{r['list']} {r['mode']}: {rule} rule {ms['median']:.1f} ms median, {ms['max']:.1f} ms max per scene"
                )
    print(f"({time.time() - t0:.0f} s)")
    if a.out:
        a.out.parent.mkdir(parents=True, exist_ok=True)
        a.out.write_text(json.dumps(out, indent=1))
        print(f"wrote {a.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
