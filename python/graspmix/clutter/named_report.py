"""Summary and report of a named-target run (graspmix.clutter.named), from named_attempts.csv and clutter.json.

Per mode and method: success = the named object lifted alone / attempts; "a neighbour instead" = one
object lifted and not the named one; the outcomes; the picks with no eligible target (not attempts). 95%
intervals: Wilson's; with several targets per scene, on the effective number of attempts (the scenes'
design effect, graspmix.experiment.stats.clustered_rate), as the clearing task's.
"""

from __future__ import annotations

from collections import Counter, defaultdict
from pathlib import Path

import numpy as np

from ..experiment.report import command_block, finite_json, provenance_text
from ..experiment.stats import RateCI, clustered_rate, wilson_ci
from ..io import CLUTTER_SUMMARY_FORMAT
from ..io.checks import quote
from .named import NAMED_CSV, NAMED_CSV_NAME, NAMED_OUTCOMES, NO_TARGET, TARGET_RULE, TIME_COLUMNS
from .protocol import check_row, input_words


def _rate(successes: list[int], trials: list[int]) -> dict:
    """Pooled rate over scenes: Wilson's interval, widened by the design effect when a scene holds several
    attempts (one attempt per scene: the attempts are independent, plain Wilson)."""
    kept = [(s, t) for s, t in zip(successes, trials) if t > 0]
    if not kept:
        return {"rate": None, "low": None, "high": None, "successes": 0, "trials": 0, "clusters": 0}
    y, m = [s for s, _ in kept], [t for _, t in kept]
    if max(m) > 1:
        return clustered_rate(y, m).to_dict()
    lo, hi = wilson_ci(sum(y), len(y))
    return RateCI(sum(y) / len(y), lo, hi, sum(y), len(y), len(y), 1.0, 0.95).to_dict()


def _times(rows: list[dict]) -> dict:
    out = {}
    for c in TIME_COLUMNS:
        v = [r[c] for r in rows if r[c] not in (None, "")]
        out[c[2:]] = {"median": float(np.median(v)), "mean": float(np.mean(v)), "n": len(v)} if v else None
    return out


def _cell(rows: list[dict]) -> dict:
    """The results of one mode and method from its rows (one per scene and pick)."""
    by_scene = defaultdict(list)
    for r in rows:
        by_scene[r["scene"]].append(r)
    tried = [r for r in rows if r["outcome"] != NO_TARGET]
    scenes = sorted(by_scene)
    attempts = [[r for r in by_scene[s] if r["outcome"] != NO_TARGET] for s in scenes]
    trials = [len(a) for a in attempts]
    return {
        "success": _rate([sum(r["outcome"] == "success" for r in a) for a in attempts], trials),
        "wrong_object": _rate([sum(r["outcome"] == "wrong object" for r in a) for a in attempts], trials),
        "attempts": len(tried),
        "outcomes": dict(Counter(r["outcome"] for r in tried)),
        # the point selected a segmented object made mostly of another scene object (or of the table)
        "misnamed": sum(r["cluster"] is not None and r["cluster"] != r["target"] for r in tried),
        "excluded": {
            "picks": len(rows) - len(tried),
            "scenes": sum(any(r["outcome"] == NO_TARGET for r in by_scene[s]) for s in scenes),
            "placed": sum(by_scene[s][0]["placed"] for s in scenes),
            "eligible": sum(by_scene[s][0]["eligible"] for s in scenes),
        },
        "times_s": _times(tried),
        "per_scene": {
            str(s): {
                "placed": by_scene[s][0]["placed"],
                "eligible": by_scene[s][0]["eligible"],
                "outcomes": [r["outcome"] for r in sorted(by_scene[s], key=lambda r: r["pick"])],
            }
            for s in scenes
        },  # fmt: skip
    }


def summarize_named(rows: list[dict], doc: dict) -> dict:
    """summary.json's content of a named-target run from its rows and the clutter.json document."""
    proto = doc["protocol"]
    first = {}
    for r in rows:  # a unit rerun after an interrupted write keeps its first row
        first.setdefault((r["mode"], r["scene"], r["method"], r["pick"]), r)
    results = {}
    for mode in proto["modes"]:
        for method in proto["methods"]:
            mine = [r for (mo, _, me, _), r in sorted(first.items()) if mo == mode and me == method]
            if mine:
                results.setdefault(mode, {})[method] = _cell(mine)
    expected = len(proto["modes"]) * proto["scenes"] * len(proto["methods"]) * proto["targets"]
    return finite_json(
        {
            "format": CLUTTER_SUMMARY_FORMAT,
            "task": "named",
            "protocol": proto,
            "provenance": doc.get("provenance", {}),
            "rounds": {"done": len(first), "expected": expected, "complete": len(first) == expected},
            "target_rule": TARGET_RULE,
            "intervals": "95% Wilson score intervals (with several targets per scene, on the effective number "
            "of attempts: attempts / design effect of the scenes)",
            "results": results,
        }
    )


def _pct(e: dict) -> str:
    if e["rate"] is None:
        return "n/a"
    return f"{100 * e['rate']:.1f}% [{100 * e['low']:.1f}, {100 * e['high']:.1f}]"


def named_results_table(summary: dict) -> list[list[str]]:
    """Rows (a header first): per mode and method the success rate and the neighbours lifted instead."""
    head = [
        "mode",
        "method",
        "scenes",
        "attempts",
        "success (95% CI)",
        "a neighbour instead (95% CI)",
        "excluded picks",
    ]
    out = [head]
    for mode, per in summary["results"].items():
        for method, c in per.items():
            n, wrong = len(c["per_scene"]), f"{c['outcomes'].get('wrong object', 0)}: {_pct(c['wrong_object'])}"
            out.append(
                [mode, method, str(n), str(c["attempts"]), _pct(c["success"]), wrong, str(c["excluded"]["picks"])]
            )
    return out


def _outcome_table(summary: dict) -> list[list[str]]:
    out = [["mode", "method", *NAMED_OUTCOMES, "misnamed"]]
    for mode, per in summary["results"].items():
        for method, c in per.items():
            out.append([mode, method, *[str(c["outcomes"].get(o, 0)) for o in NAMED_OUTCOMES], str(c["misnamed"])])
    return out


def _other_tables(summary: dict) -> tuple[list, list]:
    excl = [["mode", "method", "objects placed", "eligible", "picks without a target", "scenes with one"]]
    times = [["mode", "method", *[f"{c[2:]} (ms)" for c in TIME_COLUMNS]]]
    for mode, per in summary["results"].items():
        for method, c in per.items():
            x, t = c["excluded"], c["times_s"]
            excl.append([mode, method, str(x["placed"]), str(x["eligible"]), str(x["picks"]), str(x["scenes"])])
            ms = ["n/a" if t[s[2:]] is None else f"{1e3 * t[s[2:]]['median']:.0f}" for s in TIME_COLUMNS]
            times.append([mode, method, *ms])
    return excl, times


def named_blocks(summary: dict) -> list[tuple]:
    """report.md of a named-target run, as experiment.report.render_markdown's blocks."""
    p, prov, r = summary["protocol"], summary["provenance"], summary["rounds"]
    excl, times = _other_tables(summary)
    blocks = [
        ("h1", "graspmix named-target report"),
        (
            "p",
            f"{p['scenes']} scenes x modes {','.join(p['modes'])} x methods {','.join(p['methods'])} x "
            f"{p['targets']} named object(s) per scene: {r['done']} of {r['expected']} attempts"
            + ("" if r["complete"] else " (INCOMPLETE run)")
            + f". {p['objects']} objects per scene from {Path(p['object_list']).name}; {p['views']} view(s) {input_words(p)}, "
            f"{'with' if p['noise'] else 'no'} depth noise; grasps close {p['closing']}. The target is drawn "
            f"{summary['target_rule']}, and named as point:x,y,z, its observed point nearest the top centre of "
            "that box; one attempt per target on the untouched scene. " + provenance_text(prov),
        ),
    ]
    blocks += command_block(prov)
    blocks += [
        ("h2", "The named object lifted"),
        (
            "p",
            "success = the named object lifted alone / attempts; a neighbour instead = one object lifted, not "
            f"the named one. {summary['intervals']}.",
        ),  # fmt: skip
        ("table", named_results_table(summary)),
        ("h2", "Outcomes of the attempts"),
        ("p", "misnamed: the point selected a segmented object made mostly of another object's points."),
        ("table", _outcome_table(summary)),
        ("h2", "Targets"),
        ("table", excl),
        ("h2", "Stage times (median per attempt)"),
        ("table", times),
    ]
    return blocks


def check_named_rows(rows: list[dict], proto: dict, path: Path) -> None:
    """Every row belongs to the protocol and has a known outcome: a CSV edited by hand is an error."""
    for i, r in enumerate(rows, start=1):
        check_row(r, i, proto, (*NAMED_OUTCOMES, NO_TARGET), path)
        if r["pick"] is None or not 0 <= r["pick"] < proto["targets"]:
            raise ValueError(f"{path}: row {i}: pick {quote(r['pick'])} is not in 0..{proto['targets'] - 1}")
        if r["placed"] is None or r["eligible"] is None:
            raise ValueError(f"{path}: row {i}: placed {quote(r['placed'])}, eligible {quote(r['eligible'])}")


def read_named_rows(run_dir: Path, doc: dict) -> list[dict]:
    from ..experiment.log import read_rows

    path = run_dir / NAMED_CSV_NAME
    rows = read_rows(path, NAMED_CSV)
    check_named_rows(rows, doc["protocol"], path)
    return rows
