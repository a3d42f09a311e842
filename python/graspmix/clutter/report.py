"""Summary and report of a clutter-removal run, rebuilt from clutter_attempts.csv and clutter.json alone.

Per mode and method (and per scene): GSR = successful grasps / attempts; DR = successful grasps / objects
placed (VGN's percent_cleared and GIGA's declutter rate: every success removes one object); "cleared" =
objects no longer in the scene at the end / placed (also counts objects lifted two at a time or knocked
off the table, which DR does not credit). 95% intervals: Wilson's score interval (bounded, not degenerate
at 0% or 100%, unlike a bootstrap over few scenes), on the effective number of attempts or objects, that
is divided by the design effect of the scenes (graspmix.experiment.stats.clustered_rate): attempts and
objects of one scene are not independent (a failure can end a scene and leave all its objects), and the
design effect widens the interval by what the spread between scenes shows.
"""

from __future__ import annotations

import json
from collections import Counter, defaultdict
from pathlib import Path

import numpy as np

from ..experiment.report import command_block, finite_json, provenance_text, render_markdown
from ..experiment.stats import clustered_rate
from ..io import CLUTTER_SUMMARY_FORMAT
from ..io.checks import check_output_path, quote
from .named import NAMED_CSV_NAME
from .named_report import named_blocks, named_results_table, read_named_rows, summarize_named
from .protocol import (
    CLUTTER_CSV,
    CLUTTER_CSV_NAME,
    OUTCOMES,
    STOPS,
    TIME_COLUMNS,
    check_row,
    input_words,
    load_clutter_protocol,
)


def rounds_of(rows: list[dict]) -> dict:
    """(mode, scene, method) -> the round's rows in attempt order, for rounds that ended (a row has a stop);
    a repeated attempt (a round rerun after an interrupted write) keeps its first row."""
    by_round = defaultdict(dict)
    for r in rows:
        by_round[(r["mode"], r["scene"], r["method"])].setdefault(r["attempt"], r)
    out = {}
    for key, attempts in by_round.items():
        ordered = [attempts[a] for a in sorted(attempts)]
        if any(r["stop"] for r in ordered):
            out[key] = ordered[: next(i for i, r in enumerate(ordered) if r["stop"]) + 1]
    return out


def _scene_entry(rows: list[dict]) -> dict:
    successes = sum(r["success"] for r in rows)
    return {
        "placed": rows[0]["placed"],
        "attempts": len(rows),
        "successes": successes,
        "remaining": rows[-1]["after"],
        "gsr": successes / len(rows),
        "dr": successes / rows[0]["placed"],
        "stop": rows[-1]["stop"],
    }


def _times(rows: list[dict]) -> dict:
    """Per stage the median and mean over attempts (s), over the attempts that ran the stage."""
    out = {}
    for c in TIME_COLUMNS:
        v = [r[c] for r in rows if r[c] not in (None, "")]
        out[c[2:]] = {"median": float(np.median(v)), "mean": float(np.mean(v)), "n": len(v)} if v else None
    return out


def _cell(rounds: dict) -> dict:
    """The results of one mode and method from its rounds {scene: rows}."""
    scenes = {s: _scene_entry(rows) for s, rows in sorted(rounds.items())}
    e = list(scenes.values())
    rows = [r for s in sorted(rounds) for r in rounds[s]]
    placed = [x["placed"] for x in e]
    gsr = clustered_rate([x["successes"] for x in e], [x["attempts"] for x in e])
    dr = clustered_rate([x["successes"] for x in e], placed)
    cleared = clustered_rate([x["placed"] - x["remaining"] for x in e], placed)
    return {
        "gsr": gsr.to_dict(),
        "dr": dr.to_dict(),
        "cleared": cleared.to_dict(),
        "outcomes": {o: n for o, n in Counter(r["outcome"] for r in rows).items()},
        "stops": {s: n for s, n in Counter(x["stop"] for x in e).items()},
        "attempts_per_scene": float(np.mean([x["attempts"] for x in e])),
        "times_s": _times(rows),
        "per_scene": {str(s): x for s, x in scenes.items()},
    }


def summarize(rows: list[dict], doc: dict) -> dict:
    """summary.json's content from the attempt rows and the clutter.json document."""
    proto = doc["protocol"]
    rounds = rounds_of(rows)
    results = {}
    for mode in proto["modes"]:
        for method in proto["methods"]:
            mine = {s: r for (mo, s, me), r in rounds.items() if mo == mode and me == method}
            if mine:
                results.setdefault(mode, {})[method] = _cell(mine)
    expected = len(proto["modes"]) * proto["scenes"] * len(proto["methods"])
    return finite_json(
        {
            "format": CLUTTER_SUMMARY_FORMAT,
            "protocol": proto,
            "provenance": doc.get("provenance", {}),
            "rounds": {"done": len(rounds), "expected": expected, "complete": len(rounds) == expected},
            "intervals": "95% Wilson score intervals on the effective number of trials (trials / design effect "
            "of the scenes, at least 1)",
            "results": results,
        }
    )


def _pct(e: dict) -> str:
    return f"{100 * e['rate']:.1f}% [{100 * e['low']:.1f}, {100 * e['high']:.1f}]"


def results_table(summary: dict) -> list[list[str]]:
    """Rows (a header first) of the findings: per mode and method GSR, DR, cleared with 95% CIs."""
    if summary.get("task") == "named":
        return named_results_table(summary)
    out = [["mode", "method", "scenes", "attempts", "GSR (95% CI)", "DR (95% CI)", "cleared (95% CI)"]]
    for mode, per in summary["results"].items():
        for method, c in per.items():
            n = len(c["per_scene"])
            out.append(
                [mode, method, str(n), str(c["gsr"]["trials"]), _pct(c["gsr"]), _pct(c["dr"]), _pct(c["cleared"])]
            )
    return out


def _count_table(summary: dict, key: str, names: tuple) -> list[list[str]]:
    out = [["mode", "method", *names]]
    for mode, per in summary["results"].items():
        for method, c in per.items():
            out.append([mode, method, *[str(c[key].get(n, 0)) for n in names]])
    return out


def _times_table(summary: dict) -> list[list[str]]:
    out = [["mode", "method", *[f"{c[2:]} (ms)" for c in TIME_COLUMNS]]]
    for mode, per in summary["results"].items():
        for method, c in per.items():
            t = c["times_s"]
            out.append(
                [
                    mode,
                    method,
                    *["n/a" if t[s[2:]] is None else f"{1e3 * t[s[2:]]['median']:.0f}" for s in TIME_COLUMNS],
                ]
            )
    return out


def _blocks(summary: dict) -> list[tuple]:
    p, prov, r = summary["protocol"], summary["provenance"], summary["rounds"]
    blocks = [
        ("h1", "graspmix clutter-removal report"),
        (
            "p",
            f"{p['scenes']} scenes x modes {','.join(p['modes'])} x methods {','.join(p['methods'])}: {r['done']} "
            f"of {r['expected']} rounds" + ("" if r["complete"] else " (INCOMPLETE run)") + f". {p['objects']} "
            f"objects per scene from {Path(p['object_list']).name}; {p['views']} view(s) {input_words(p)}, "
            f"{'with' if p['noise'] else 'no'} depth noise; grasps close {p['closing']}. A round ends when the "
            "table is clear, after 2 failures in a row, or when the planner finds no grasp (VGN's rules)"
            + (f", or after {_limit(p)} attempts" if _limit(p) else "")
            + ". "
            + provenance_text(prov),
        ),
    ]
    blocks += command_block(prov)
    blocks += [
        ("h2", "Grasp success rate (GSR) and declutter rate (DR)"),
        (
            "p",
            "GSR = successes / attempts; DR = successes / objects placed; cleared = objects gone / placed. "
            + summary["intervals"]
            + ".",
        ),
        ("table", results_table(summary)),
        ("img", "clutter.png", "GSR and DR per mode and method, and the outcomes"),
        ("h2", "Outcomes of the attempts"),
        ("table", _count_table(summary, "outcomes", OUTCOMES)),
        ("h2", "Why the rounds ended"),
        ("table", _count_table(summary, "stops", STOPS)),
        ("h2", "Stage times (median per attempt)"),
        ("table", _times_table(summary)),
    ]
    return blocks


def check_rows(rows: list[dict], proto: dict, path: Path) -> None:
    """Every row belongs to the protocol and has a known outcome: a CSV edited by hand is an error."""
    for i, r in enumerate(rows, start=1):
        check_row(r, i, proto, OUTCOMES, path)
        if r["stop"] not in ("", *STOPS) or not r["placed"]:
            raise ValueError(f"{path}: row {i}: stop {quote(r['stop'])}, placed {quote(r['placed'])}")


def build_clutter_report(run_dir) -> dict:
    """Reads a clutter run folder; writes summary.json, clutter.png (not for the named task) and report.md;
    returns the summary."""
    from ..viz.clutter import plot_clutter

    run_dir = Path(run_dir)
    doc = load_clutter_protocol(run_dir)
    named = doc["protocol"].get("task", "clear") == "named"
    rows = (read_named_rows if named else read_rows_checked)(run_dir, doc)
    for name in ("summary.json", "report.md") + (() if named else ("clutter.png",)):
        check_output_path(run_dir / name, "report")
    summary = (summarize_named if named else summarize)(rows, doc)
    if not summary["results"]:
        raise ValueError(f"{run_dir / (NAMED_CSV_NAME if named else CLUTTER_CSV_NAME)}: no round has ended yet")
    (run_dir / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")
    if not named:
        plot_clutter(summary, run_dir / "clutter.png")
    (run_dir / "report.md").write_text(render_markdown((named_blocks if named else _blocks)(summary)))
    return summary


def read_rows_checked(run_dir: Path, doc: dict) -> list[dict]:
    from ..experiment.log import read_rows

    path = run_dir / CLUTTER_CSV_NAME
    rows = read_rows(path, CLUTTER_CSV)
    check_rows(rows, doc["protocol"], path)
    return rows


def _limit(p: dict) -> int:
    """The attempt cap of a protocol document (ClutterProtocol.attempt_limit; 0: none)."""
    m = p.get("max_attempts", 0)
    return p["objects"] + 2 if m < 0 else m
