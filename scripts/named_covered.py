"""How often a "covered" named point marks the attempts of a named run that lifted a neighbour, and how often a success.

    python scripts/named_covered.py RUN [--csv OUT.csv]

RUN: a `graspmix_cli clutter --task named` run (its clutter.json and named_attempts.csv[.gz]). Every attempt that
returned a grasp is rebuilt as `named_segments_figure.py` rebuilds it (the scene placed and observed again, segmented
with the attempt's seed and target), and the points of the segment the named point selects are counted that lie
within R of the named point horizontally and more than H above it: something on top of, or leaning over, the point
the user named. Printed: per (R, H, at least N such points), the attempts it marks by outcome. No code of the library
changes; this measures a rule before anyone writes it.
"""

from __future__ import annotations

import argparse
import csv
import sys
from collections import Counter
from pathlib import Path

import numpy as np
from named_segments_figure import load_named_run, rebuilt_segment

RADII = (0.02, 0.04)  # m, horizontally from the named point
HEIGHTS = (0.015, 0.03)  # m, above the named point
AT_LEAST = (1, 10)  # points
KEYS = [(r, h) for r in RADII for h in HEIGHTS]  # covered_counts' keys, in its order


def covered_counts(points: np.ndarray, point: np.ndarray) -> dict[tuple[float, float], int]:
    """{(R, H): the points within R of `point` horizontally and more than H above it}."""
    horizontal = np.linalg.norm(points[:, :2] - point[:2], axis=1)
    above = points[:, 2] - point[2]
    return {(r, h): int(np.sum((horizontal < r) & (above > h))) for r, h in KEYS}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run", type=Path)
    ap.add_argument("--csv", type=Path, help="one row per attempt: scene, pick, outcome, the counts")
    args = ap.parse_args()

    if args.csv and not args.csv.parent.is_dir():
        sys.exit(f"{args.csv}: no such folder for the CSV")
    p, model, rows = load_named_run(args.run)
    rows = [r for r in rows if r["grasp"]]
    kinds = {(r["mode"], r["method"]) for r in rows}
    if len(kinds) > 1:
        sys.exit(f"{args.run}: attempts of {len(kinds)} modes or methods; give a run of one mode and one method")
    measured = []
    for k, r in enumerate(rows):
        _, point, obj, _ = rebuilt_segment(p, model, r)
        measured.append((r, covered_counts(obj.points, np.asarray(point, dtype=float))))
        if (k + 1) % 50 == 0 or k + 1 == len(rows):
            print(f"[{k + 1}/{len(rows)}] attempts rebuilt", flush=True)
    outcomes = Counter(r["outcome"] for r, _ in measured)
    print(
        f"{args.run.name}: {len(measured)} attempts with a grasp, " + ", ".join(f"{o} {n}" for o, n in outcomes.items())
    )
    print("| within R | more than H above | at least N points | attempts marked | by outcome |")
    print("| --- | --- | --- | --- | --- |")
    for r_, h in KEYS:
        for n in AT_LEAST:
            marked = Counter(r["outcome"] for r, c in measured if c[(r_, h)] >= n)
            by = ", ".join(f"{o} {m}" for o, m in marked.most_common()) or "none"
            print(f"| {100 * r_:g} cm | {100 * h:g} cm | {n} | {sum(marked.values())} | {by} |")
    if args.csv:
        with args.csv.open("w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["scene", "pick", "outcome"] + [f"R{100 * r_:g}cm_H{100 * h:g}cm" for r_, h in KEYS])
            for r, c in measured:
                w.writerow([r["scene"], r["pick"], r["outcome"]] + [c[key] for key in KEYS])
        print(f"wrote {args.csv}")


if __name__ == "__main__":
    main()
