"""Renders experiment runs of the same objects, trials and seeds as one ablation table: per run and method the
success rate per condition, over all its attempts with a 95% Wilson interval, the share of "start in collision"
per condition, and the paired comparison with a base run (the same clouds and synthesis seeds: McNemar's exact
test on the attempts one run lifts and the other drops). Optionally writes it into a markdown page (the tables of
docs/experiment.md, which lists the command of each) between

    <!-- ablation:begin -->
    <!-- ablation:end -->

so the page's numbers come from run folders, never from a hand.

    python scripts/ablation_table.py --base NAME NAME=RUN NAME=RUN ... [--trials N] [--doc docs/experiment.md --marker ablation]

A RUN is an experiment folder (attempts.csv or attempts.csv.gz); --trials keeps the first N trials of every run
(a run of 10 trials against ablations of 2).
"""

import argparse
import csv
import gzip
import re
import sys
from pathlib import Path

from graspmix.experiment.stats import mcnemar_exact, wilson_ci

CONDITIONS = "ABCD"


def load(run: Path, trials: int | None) -> dict:
    """(object, trial, condition, method) -> (success, reason) of a run folder's attempts."""
    path = run / "attempts.csv"
    opener = open if path.is_file() else gzip.open
    path = path if path.is_file() else run / "attempts.csv.gz"
    with opener(path, "rt", newline="") as f:
        rows = list(csv.DictReader(f))
    return {
        (r["object"], r["trial"], r["condition"], r["method"]): (int(r["success"]), r["reason"])
        for r in rows
        if trials is None or int(r["trial"]) < trials
    }


def mcnemar(base: dict, other: dict, method: str) -> str:
    keys = [k for k in other if k in base and k[3] == method]
    if not keys:
        return "n/a (no such attempts in the base run)"
    up = sum(other[k][0] > base[k][0] for k in keys)
    down = sum(other[k][0] < base[k][0] for k in keys)
    return f"+{up} / -{down}, p = {mcnemar_exact(up, down):.2g}"


def rows_of(name: str, runs: dict, base: str) -> list:
    out = []
    for method in ("gmm", "kde"):
        rs = {k: v for k, v in runs[name].items() if k[3] == method}
        if not rs:
            continue
        conds = [c for c in CONDITIONS if any(k[2] == c for k in rs)]
        rate, sic = [], []
        for c in CONDITIONS:
            cell = [v for k, v in rs.items() if k[2] == c]
            rate.append(f"{100 * sum(s for s, _ in cell) / len(cell):.1f}" if cell else "")
            sic.append(f"{100 * sum(r == 'start in collision' for _, r in cell) / len(cell):.1f}" if cell else "")
        k, n = sum(s for s, _ in rs.values()), len(rs)
        lo, hi = wilson_ci(k, n)
        paired = "" if name == base else mcnemar(runs[base], runs[name], method)
        out.append(
            [name, method.upper(), *rate, f"{100 * k / n:.1f} [{100 * lo:.1f}, {100 * hi:.1f}]", str(n)]
            + [" / ".join(x for x, c in zip(sic, CONDITIONS) if c in conds), paired]
        )
    return out


def table(runs: dict, base: str) -> str:
    head = ["run", "method", *CONDITIONS, "all (95% CI)", "attempts", "start in collision, % (per condition)"]
    head.append(f"paired vs {base}: gained / lost, McNemar")
    lines = ["| " + " | ".join(head) + " |", "|" + " --- |" * len(head)]
    for name in runs:
        lines += ["| " + " | ".join(r) + " |" for r in rows_of(name, runs, base)]
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", help="NAME=RUN_FOLDER")
    ap.add_argument("--base", required=True, help="the NAME the others are paired with")
    ap.add_argument("--trials", type=int, help="keep the first N trials of every run")
    ap.add_argument("--doc", type=Path, help="write the table between the marker comments of this markdown page")
    ap.add_argument("--marker", default="ablation", help="the markers' name (default ablation)")
    a = ap.parse_args(argv)
    runs = {}
    for spec in a.runs:
        name, _, folder = spec.partition("=")
        if not folder:
            ap.error(f"expected NAME=RUN_FOLDER, got {spec!r}")
        runs[name] = load(Path(folder), a.trials)
    if a.base not in runs:
        ap.error(f"--base {a.base!r} is not one of the runs")
    text = table(runs, a.base)
    print(text)
    if a.doc:
        begin, end = f"<!-- {a.marker}:begin -->", f"<!-- {a.marker}:end -->"
        doc = a.doc.read_text()
        if begin not in doc or end not in doc:
            print(f"{a.doc}: no {begin} ... {end} markers", file=sys.stderr)
            return 2
        doc = re.sub(re.escape(begin) + ".*?" + re.escape(end), lambda _: f"{begin}\n{text}\n{end}", doc, flags=re.S)
        a.doc.write_text(doc)
    return 0


if __name__ == "__main__":
    sys.exit(main())
