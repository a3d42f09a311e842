"""How far below each named object's true top the executed grasp's fingertips reached, against the outcome: is a
grasp that catches only the object's top few millimetres the one that slips?

    python scripts/named_grasp_depth.py RUN [--scenes N]

RUN is a `graspmix_cli clutter --task named` folder (clutter.json gives the scenes; named_attempts.csv(.gz) the
executed grasps). For every attempt that lifted the target or was not held, the scene is placed again (its seed),
the target's true top is the top of its collision mesh's box at its pose (clutter.named.object_tops), and the
grasp's fingertip point (the exports' T_world_tcp, graspmix.model.grasp_frames) is measured below it along the
vertical. Printed: per band of that depth, the attempts and how many were not held; and the same split by the
object's height (under 45 mm: flat). --scenes: only the first N scenes (default all).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

BANDS_MM = (-1000, 5, 10, 15, 20, 30, 1000)
FLAT_M = 0.045


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run", type=Path)
    ap.add_argument("--scenes", type=int, default=None)
    args = ap.parse_args(argv)

    from graspmix.clutter.named import named_rows, object_tops
    from graspmix.clutter.protocol import clutter_protocol_from_json
    from graspmix.model.grasp_frames import FrameMaker
    from graspmix.sim.execution import load_hand
    from graspmix.sim.scenes import choose_objects, make_scene

    p = clutter_protocol_from_json(json.loads((args.run / "clutter.json").read_text())["protocol"])
    hand = load_hand(None)
    frames = FrameMaker(hand)
    depth, tops, held = [], [], []
    for r in named_rows(args.run):
        if r["outcome"] not in ("success", "not held") or not r["grasp"]:
            continue
        if args.scenes is not None and int(r["scene"]) >= args.scenes:
            continue
        seed = p.scene_seed(r["mode"], int(r["scene"]))
        spec = make_scene(choose_objects(p.object_list_path, p.objects, seed), r["mode"], seed)
        top = object_tops(spec)[int(r["target"])]
        g = json.loads(r["grasp"])
        wrist = np.asarray(g["T_world_wrist"], dtype=float)
        f = frames.frames(wrist[None], hand.joints_array(g["grasp_joints"])[None])[0]
        depth.append(1000 * (top[2] - f["T_world_tcp"][2]))
        tops.append(top[2])
        held.append(r["outcome"] == "success")
    depth, tops, held = np.array(depth), np.array(tops), np.array(held, dtype=bool)
    print(f"{args.run}: {len(held)} attempts lifted or not held, {(~held).sum()} not held")
    print("| fingertips below the object's top (mm) | all: attempts | not held | flat (< 45 mm): attempts | not held |")
    print("| --- | --- | --- | --- | --- |")
    for lo, hi in zip(BANDS_MM[:-1], BANDS_MM[1:]):
        band = (depth >= lo) & (depth < hi)
        flat = band & (tops < FLAT_M)
        name = f"under {hi}" if lo == BANDS_MM[0] else (f"{lo} or more" if hi == BANDS_MM[-1] else f"{lo}-{hi}")
        print(f"| {name} | {band.sum()} | {(~held[band]).sum()} | {flat.sum()} | {(~held[flat]).sum()} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
