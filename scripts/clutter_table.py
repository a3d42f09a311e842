"""Renders clutter-removal runs (their summary.json) as one markdown table: per run, mode and method the attempts,
GSR and DR with their 95% intervals, and the outcomes.

    python scripts/clutter_table.py NAME=RUN NAME=RUN ... [--doc docs/one-view.md --marker clutter]
"""

from __future__ import annotations

import argparse
import json
import re
import sys
from pathlib import Path


def rows(name: str, run: Path) -> list[str]:
    d = json.loads((run / "summary.json").read_text())
    out = []
    for mode, by_method in d["results"].items():
        for method, r in by_method.items():
            g, dr = r["gsr"], r["dr"]
            outcomes = ", ".join(f"{k} {v}" for k, v in sorted(r["outcomes"].items(), key=lambda kv: -kv[1]))
            out.append(
                f"| {name} | {mode} | {method.upper()} | {g['trials']} | {100 * g['rate']:.1f} "
                f"[{100 * g['low']:.1f}, {100 * g['high']:.1f}] | {100 * dr['rate']:.1f} "
                f"[{100 * dr['low']:.1f}, {100 * dr['high']:.1f}] | {outcomes} |"
            )
    return out


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", help="NAME=RUN folder")
    ap.add_argument("--doc", type=Path, help="write the table between the marker comments of this markdown page")
    ap.add_argument("--marker", default="clutter")
    a = ap.parse_args()
    lines = [
        "| run | mode | method | attempts | GSR, % (95% CI) | DR, % (95% CI) | outcomes |",
        "| --- | --- | --- | --- | --- | --- | --- |",
    ]
    for spec in a.runs:
        name, _, run = spec.partition("=")
        lines += rows(name, Path(run))
    text = "\n".join(lines)
    if a.doc is None:
        print(text)
        return 0
    doc = a.doc.read_text()
    begin, end = f"<!-- {a.marker}:begin -->", f"<!-- {a.marker}:end -->"
    if begin not in doc or end not in doc:
        print(f"{a.doc}: no {begin} ... {end} markers", file=sys.stderr)
        return 2
    a.doc.write_text(
        re.sub(re.escape(begin) + ".*?" + re.escape(end), lambda _: f"{begin}\n{text}\n{end}", doc, flags=re.S)
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
