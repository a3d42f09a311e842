#!/usr/bin/env python3
"""Splits objects for the clutter-removal protocol: data/objects/clutter_dev.txt (to choose settings on) and
data/objects/clutter_test.txt (reported only), disjoint from each other and from the paper's test60.txt.

Candidates and filters are select_test_objects.py's (one-link mesh objects of pybullet_data that fit the
WSG 50: narrowest horizontal width 15-100 mm, height 20-200 mm as they rest, convexity >= 0.2), less the
60 test objects, and no larger than MAX_SIZE across (five of them share a pile in a 30 cm workspace,
VGN's). A seeded permutation of those (numpy default_rng(seed)) gives the dev objects first, then the
test objects: a random split, so neither half was chosen by any result.

Run from the repository root: python3 scripts/select_clutter_objects.py [--dev 30 --test 60 --seed 0]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from select_test_objects import HEIGHT, MIN_CONVEXITY, WIDTH, describe_candidates, fits_wsg50  # noqa: E402

MAX_SIZE = 0.15  # m, largest bounding-box side
TEST60 = Path("data/objects/test60.txt")


def header(name: str, n: int, pool: int, fit: int, args) -> str:
    return (
        f"# {n} clutter-removal {name} objects (paths relative to pybullet_data), written by\n"
        f"# scripts/select_clutter_objects.py --dev {args.dev} --test {args.test} --seed {args.seed}.\n"
        f"# Candidates: the one-link mesh objects of pybullet_data that fit the WSG 50 (width "
        f"{WIDTH[0] * 1e3:.0f}-{WIDTH[1] * 1e3:.0f} mm,\n# height {HEIGHT[0] * 1e3:.0f}-{HEIGHT[1] * 1e3:.0f} mm, "
        f"convexity >= {MIN_CONVEXITY}: {fit}), not in test60.txt, at most {MAX_SIZE * 1e3:.0f} mm across "
        f"({pool});\n# a seeded permutation (seed {args.seed}) of those: the first {args.dev} are clutter_dev.txt, "
        f"the next {args.test} clutter_test.txt.\n"
        f"# clutter_dev.txt is for choosing settings; clutter_test.txt is reported only. The three lists are disjoint.\n"
    )


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dev", type=int, default=30)
    ap.add_argument("--test", type=int, default=60)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out-dir", default="data/objects")
    args = ap.parse_args(argv)
    test60 = {line.strip() for line in TEST60.read_text().splitlines() if line.strip() and not line.startswith("#")}
    fit = [r for r in describe_candidates() if fits_wsg50(r)]
    pool = sorted(r["path"] for r in fit if r["path"] not in test60 and r["size"] <= MAX_SIZE)
    if len(pool) < args.dev + args.test:
        raise SystemExit(f"only {len(pool)} objects qualify, {args.dev + args.test} wanted")
    order = np.random.default_rng(args.seed).permutation(len(pool))
    split = {"dev": sorted(pool[i] for i in order[: args.dev])}
    split["test"] = sorted(pool[i] for i in order[args.dev : args.dev + args.test])
    for name, objects in split.items():
        out = Path(args.out_dir) / f"clutter_{name}.txt"
        out.write_text(header(name, len(objects), len(pool), len(fit), args) + "".join(f"{o}\n" for o in objects))
        print(f"[select] wrote {out} ({len(objects)} objects)", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
