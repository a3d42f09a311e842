"""Every grasp of each hand on the first clouds of bench_hands.py, written without timings, so that two builds can
be compared bit for bit (a speed-up must not change a grasp):

    python benchmarks/hands_grasps.py MODELS_DIR OUT.json [--objects 3] [--seed 0] [--cache DIR]
    cmp before.json after.json

MODELS_DIR, --cache and the clouds as bench_hands.py's; the WSG 50's bundled model and each hand of --hands. Per
hand and cloud, GraspSet.to_json() less its "timing_s" (and the hand by its file name): every grasp's wrist, joints, log-likelihood, experts and
frames, and the frame settings. Floats are written as repr writes them (exactly).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import sys
from pathlib import Path

import graspmix
from graspmix.io import data_path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_hands import HANDS, WSG, make_clouds  # noqa: E402


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("models_dir", type=Path, help="what scripts/hand_models.py wrote")
    ap.add_argument("out", type=Path, help="the JSON file to write")
    ap.add_argument("--hands", default=",".join(HANDS))
    ap.add_argument("--objects", type=int, default=3)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--cache", type=Path, default=None, help="folder to keep the clouds in between runs")
    args = ap.parse_args(argv)
    models = {WSG: graspmix.GraspModel.load(data_path("models", "box_wsg50_gmm.json"))}
    for name in [h for h in args.hands.split(",") if h]:
        models[name] = graspmix.GraspModel.load(args.models_dir / name / "model.json")
    clouds = make_clouds(args.objects, args.seed, args.cache)
    options = graspmix.SynthesisOptions(seed=args.seed)
    out = {}
    for name, model in models.items():
        out[name] = []
        for obj, pts, vp in clouds:
            doc = model.synthesize(pts, options, viewpoints=vp).to_json()
            doc.pop("timing_s")
            doc["hand"] = Path(doc["hand"]).name  # two checkouts compare
            out[name].append({"object": obj, **doc})
        text = json.dumps(out[name], sort_keys=True)
        print(f"  {name}: {sum(len(d['grasps']) for d in out[name])} grasps, sha256 "
              f"{hashlib.sha256(text.encode()).hexdigest()[:16]}", flush=True)  # fmt: skip
    args.out.write_text(json.dumps(out, sort_keys=True) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
