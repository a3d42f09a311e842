"""Renders named-object runs (`graspmix_cli clutter --task named`) as one markdown table, each against the first:
the attempts, how many lifted the named object (95% Wilson interval), how many lifted a neighbour instead (alone or
with the target), the outcomes, and, on the attempts both runs made (the same scene and pick), the attempts gained
and lost and McNemar's exact p (attempts pair when their scene seed, named object and point agree).

    python scripts/named_table.py NAME=RUN NAME=RUN ...

RUN is a run folder (named_attempts.csv or named_attempts.csv.gz).
"""

from __future__ import annotations

import argparse
import sys
from collections import Counter
from pathlib import Path

from graspmix.clutter.named import NO_TARGET, named_rows
from graspmix.experiment.stats import mcnemar_exact, wilson_ci

NEIGHBOUR = ("wrong object", "two objects lifted")


def load(run: Path) -> dict:
    """(mode, scene, method, pick) -> the attempt's row (picks with no eligible target are no attempts)."""
    return {(r["mode"], r["scene"], r["method"], r["pick"]): r for r in named_rows(run) if r["outcome"] != NO_TARGET}


def same_attempt(a: dict, b: dict) -> bool:
    return a["scene_seed"] == b["scene_seed"] and a["target"] == b["target"] and a["point"] == b["point"]


def row(name: str, runs: dict, base: str) -> str:
    rows = runs[name]
    n = len(rows)
    ok = sum(r["success"] == 1 for r in rows.values())
    lo, hi = wilson_ci(ok, n)
    outcomes = Counter(r["outcome"] for r in rows.values())
    neighbour = sum(outcomes[k] for k in NEIGHBOUR)
    text = ", ".join(f"{k} {v}" for k, v in outcomes.most_common() if k != "success")
    paired = ""
    if name != base:
        # the same attempt: the same scene (its seed) and the same named object
        both = {k for k in runs[base].keys() & rows.keys() if same_attempt(runs[base][k], rows[k])}
        a = {k for k in both if runs[base][k]["success"] == 1}
        b = {k for k in both if rows[k]["success"] == 1}
        gained, lost = len(b - a), len(a - b)
        if both:
            paired = f"+{gained} / -{lost}, p = {mcnemar_exact(lost, gained):.2g}"
            paired += "" if len(both) == n else f" (on the {len(both)} shared attempts)"
        else:
            paired = "no shared attempts (other scenes)"
    return f"| {name} | {n} | {ok}, {100 * ok / n:.1f}% [{100 * lo:.1f}, {100 * hi:.1f}] | {neighbour} | {text} | {paired} |"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", metavar="NAME=RUN")
    args = ap.parse_args(argv)
    runs = {}
    try:
        for spec in args.runs:
            name, sep, path = spec.partition("=")
            if not sep or not name or not path:
                raise ValueError(f"{spec!r}: expected NAME=RUN")
            runs[name] = load(Path(path))
    except ValueError as e:
        print(f"named_table: {e}", file=sys.stderr)
        return 2
    base = next(iter(runs))
    print(
        f"| run | attempts | lifted the named object (95% CI) | a neighbour lifted | other outcomes | "
        f"paired vs {base}: gained / lost, McNemar |"
    )
    print("| --- | --- | --- | --- | --- | --- |")
    for name in runs:
        print(row(name, runs, base))
    return 0


if __name__ == "__main__":
    sys.exit(main())
