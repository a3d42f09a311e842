"""Repeats of issue 27's trial (`scripts/hands_trial.py OUT --seed S`, one run per seed) in one table per hand.

    python scripts/hands_trial_table.py RUN [RUN ...]

Each RUN is a hands_trial.py output folder (its results.json). The runs must be repeats of one trial: the same
objects, objects file, views, noise, closing, executor and hands, and no acquisition seed twice; they differ in the
seeds, so each repeat sees each object in a new noisy cloud and the synthesis draws anew. Printed per hand: how many
objects it lifted in each run (in the order given), the pooled rate with a 95% interval clustered by object (the
repeats of one object are not independent: an object a hand seldom holds tends to fail again), each object it
failed on with how often, and the median over runs of the synthesis time ratio to the WSG 50.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
from collections import Counter, defaultdict
from pathlib import Path

KEYS = ("objects", "summary", "attempts", "seed")
SAME = ("objects_file", "views", "noise", "closing", "executor")  # what repeats of one trial share


def load_run(run: Path) -> dict:
    """A hands_trial.py results.json; exits with one line naming the run when it is missing or not one."""
    from hands_trial import RESULTS_FORMAT

    path = run / "results.json"
    try:
        doc = json.loads(path.read_text())
    except (OSError, ValueError) as e:
        sys.exit(f"{path}: cannot read a hands trial's results ({e})")
    if not isinstance(doc, dict) or doc.get("format") != RESULTS_FORMAT:
        sys.exit(f"{path}: not a hands trial's results (format {RESULTS_FORMAT!r} expected)")
    missing = [k for k in KEYS if k not in doc]
    if missing:
        sys.exit(f"{path}: a hands trial's results without {', '.join(missing)}")
    return doc


def check_repeats(runs: list[Path], docs: list[dict]) -> None:
    """Exits with one line when the runs are not repeats of one trial."""
    first = docs[0]
    objects = [o["object"] for o in first["objects"]]
    seeds: dict[int, Path] = {}
    for r, d in zip(runs, docs):
        if [o["object"] for o in d["objects"]] != objects:
            sys.exit(f"{r}: other objects than {runs[0]}'s; the repeats must be of one list")
        for key in SAME:
            if d.get(key) != first.get(key):
                sys.exit(f"{r}: {key} {d.get(key)!r}, {runs[0]} has {first.get(key)!r}; the repeats must share it")
        if set(d["summary"]) != set(first["summary"]):
            sys.exit(f"{r}: hands {', '.join(d['summary'])}, {runs[0]} has {', '.join(first['summary'])}")
        if d["seed"] in seeds:
            sys.exit(f"{r}: acquisition seed {d['seed']} again ({seeds[d['seed']]} has it): not a repeat")
        seeds[d["seed"]] = r


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("runs", type=Path, nargs="+")
    args = ap.parse_args()

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "python"))
    from graspmix.experiment.stats import clustered_rate

    docs = [load_run(r) for r in args.runs]
    check_repeats(args.runs, docs)
    objects = [o["object"] for o in docs[0]["objects"]]
    seeds = ", ".join(str(d["seed"]) for d in docs)
    print(f"{len(docs)} runs of the trial (acquisition seeds from {seeds}), {len(objects)} objects each")
    print()
    print(
        f"| hand | lifted of {len(objects)}, per run | pooled (95%, clustered by object) | failed (runs) "
        "| time ratio to WSG 50, median |"
    )
    print("| --- | --- | --- | --- | --- |")
    for h in docs[0]["summary"]:
        per_object = defaultdict(int)
        failed = Counter()
        for d in docs:
            for a in d["attempts"][h]:
                per_object[a["object"]] += bool(a["lifted"])
                if not a["lifted"]:
                    failed[Path(a["object"]).stem] += 1  # as hands_trial.py names them
        rate = clustered_rate([per_object[o] for o in objects], [len(docs)] * len(objects))
        per_run = ", ".join(str(d["summary"][h]["lifted"]) for d in docs)
        ratios = [d["summary"][h]["ratio_to_wsg50"] for d in docs if d["summary"][h].get("ratio_to_wsg50") is not None]
        fails = ", ".join(f"{o} ({n})" for o, n in sorted(failed.items())) or "none"
        ratio = f"{statistics.median(ratios):.2f}" if ratios else "n/a"
        print(
            f"| {h} | {per_run} | {rate.successes} of {rate.trials}, {100 * rate.rate:.1f}% "
            f"[{100 * rate.low:.1f}, {100 * rate.high:.1f}] | {fails} | {ratio} |"
        )


if __name__ == "__main__":
    main()
