"""Summary and report of an experiment run, rebuilt from its attempts.csv and protocol.json alone.

    graspmix.experiment.report.build_report("runs/paper")   # summary.json, report.md, report.html, *.png

Figures: success rate per condition and method with 95% confidence intervals over trials (and the
per-trial rates as dots), the stacked runtime bars of the paper's Fig. runtime (medians over objects of
query density estimation, sampling and ranking, optimising the top 10), and the table of the paired
t-tests GMM vs KDE per condition.
"""

from __future__ import annotations

import base64
import html
import json
import math
from collections import Counter, defaultdict
from pathlib import Path

import numpy as np

from ..io import SUMMARY_FORMAT
from ..io.checks import check_output_path, quote
from ..model.grasps import STAGE_LABELS, STAGES
from ..model.settings import METHOD_LABELS, METHODS
from ..viz.experiment import plot_runtime, plot_success
from .log import CSV_NAME, RECORDED_COLUMNS, read_rows
from .protocol import CONDITIONS, PROTOCOL_FIELDS, load_protocol, protocol_from_json
from .stats import mean_ci, paired_ttest

REASONS = ("success", "not held", "no contact", "start in collision", "synthesis failed")


def provenance_text(prov: dict) -> str:
    """ "graspmix VERSION, commit HASH." of a run's provenance (its report's closing sentence)."""
    return f"graspmix {prov.get('graspmix', '?')}, commit {prov.get('commit') or 'unknown'}."


def command_block(prov: dict) -> list:
    """The report block showing the command that made the run, when it was recorded."""
    return [("code", prov["command"])] if prov.get("command") else []


def finite_json(x):
    """JSON has no nan/inf: None for them."""
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if isinstance(x, dict):
        return {k: finite_json(v) for k, v in x.items()}
    if isinstance(x, (list, tuple)):
        return [finite_json(v) for v in x]
    return x


def summarize(rows: list[dict], protocol_doc: dict) -> dict:
    """summary.json's content from the attempt rows and the protocol document."""
    proto = dict(protocol_doc["protocol"])
    # A protocol.json written before condition_definitions existed (or edited) names its conditions only.
    defs = proto.get("condition_definitions") or {}
    proto["condition_definitions"] = {c: defs.get(c) or vars(CONDITIONS[c]) for c in proto["conditions"]}
    objects, trials = proto["objects"], proto["trials"]
    conditions = [c for c in proto["conditions"]]
    methods = [m for m in proto["methods"]]
    expected = len(objects) * trials * len(conditions) * len(methods)
    rows = _unique(rows)
    success, ttests, reasons = _success_rates(rows, conditions, methods, len(objects), trials)
    return finite_json(
        {
            "format": SUMMARY_FORMAT,
            "protocol": proto,
            "provenance": protocol_doc.get("provenance", {}),
            "attempts": {"done": len(rows), "expected": expected, "complete": len(rows) == expected},
            "success_rate": success,
            "ttest_gmm_vs_kde": ttests,
            "outcomes": reasons,
            "runtime": _runtime(rows, conditions, methods),
            "per_object_success_rate": _per_object(rows, objects, methods),
        }
    )


def _unique(rows: list[dict]) -> list[dict]:
    """De-duplicate by key (a CSV edited by hand could repeat one): the first row wins."""
    by_key = {}
    for r in rows:
        by_key.setdefault((r["object"], r["trial"], r["condition"], r["method"]), r)
    return list(by_key.values())


def _success_rates(rows, conditions, methods, n_objects: int, trials: int) -> tuple[dict, dict, dict]:
    """(success rates per condition and method, t-tests GMM vs KDE per condition, outcome counts)."""
    cells = defaultdict(list)  # (condition, method, trial) -> successes
    for r in rows:
        cells[(r["condition"], r["method"], r["trial"])].append(r["success"])
    success, ttests, reasons = {}, {}, {}
    for c in conditions:
        success[c] = {}
        complete_trials = {}
        for m in methods:
            success[c][m], complete_trials[m] = _rate_entry(cells, c, m, n_objects, trials)
            reasons.setdefault(c, {})[m] = dict(
                Counter(r["reason"] for r in rows if r["condition"] == c and r["method"] == m)
            )
        if "gmm" in methods and "kde" in methods:
            ttests[c] = _ttest_entry(success[c], sorted(complete_trials["gmm"] & complete_trials["kde"]))
    return success, ttests, reasons


def _rate_entry(cells, c: str, m: str, n_objects: int, trials: int) -> tuple[dict, set]:
    """The success entry of condition c and method m, and the trials complete for it."""
    per_trial, complete = {}, []
    for t in range(trials):
        s = cells.get((c, m, t))
        if s:
            per_trial[t] = float(np.mean(s))
            if len(s) == n_objects:
                complete.append(t)
    rates = [per_trial[t] for t in sorted(per_trial)]
    entry = {
        "per_trial": {str(t): v for t, v in sorted(per_trial.items())},
        "trials_complete": len(complete),
        "successes": int(sum(sum(cells.get((c, m, t), [])) for t in range(trials))),
        "attempts": int(sum(len(cells.get((c, m, t), [])) for t in range(trials))),
    }
    if rates:
        ci = mean_ci(rates)
        entry.update(mean=ci.mean, ci_low=ci.low, ci_high=ci.high, std=ci.std, n_trials=ci.n)
    return entry, set(complete)


def _ttest_entry(per_method: dict, paired: list) -> dict:
    if len(paired) < 2:
        return {"note": f"needs at least 2 trials complete for both methods, has {len(paired)}"}
    a = [per_method["gmm"]["per_trial"][str(t)] for t in paired]
    b = [per_method["kde"]["per_trial"][str(t)] for t in paired]
    tt = paired_ttest(a, b).to_dict()
    tt["significant_at_0.05"] = bool(tt["p"] is not None and not math.isnan(tt["p"]) and tt["p"] < 0.05)
    tt["trials"] = paired
    return tt


def _runtime(rows, conditions, methods) -> dict:
    """Runtime: the paper's figure includes optimisation, so take the attempts of conditions with it
    (all attempts if none has). Per object the median over its attempts, then the median over objects."""
    opt_conditions = [c for c in conditions if CONDITIONS[c].optimise] or conditions
    runtime = {
        "conditions": opt_conditions,
        "statistic": "median over objects of the per-object median",
        "median_s": {},
        "ratio_kde_over_gmm": {},
    }
    for m in methods:
        per_obj = defaultdict(lambda: defaultdict(list))
        for r in rows:
            if r["method"] != m or r["condition"] not in opt_conditions or r["t_query"] is None:
                continue
            for s in (*STAGES, "features"):
                per_obj[r["object"]][s].append(r[f"t_{s}"])
            per_obj[r["object"]]["total"].append(sum(r[f"t_{s}"] for s in STAGES))
            per_obj[r["object"]]["execution"].append(r["t_execution"])
            per_obj[r["object"]]["acquisition"].append(r["t_acquisition"])
        if per_obj:
            keys = (*STAGES, "features", "total", "execution", "acquisition")
            runtime["median_s"][m] = {s: float(np.median([np.median(v[s]) for v in per_obj.values()])) for s in keys}
            runtime["n_objects"] = len(per_obj)
    if "gmm" in runtime["median_s"] and "kde" in runtime["median_s"]:
        g, k = runtime["median_s"]["gmm"], runtime["median_s"]["kde"]
        runtime["ratio_kde_over_gmm"] = {s: (k[s] / g[s] if g[s] > 0 else math.nan) for s in (*STAGES, "total")}
    return runtime


def _per_object(rows, objects, methods) -> dict:
    per_object = {}
    for o in objects:
        per_object[o] = {}
        for m in methods:
            s = [r["success"] for r in rows if r["object"] == o and r["method"] == m]
            per_object[o][m] = float(np.mean(s)) if s else None
    return per_object


# ---- the report --------------------------------------------------------------------------------


def _pct(x) -> str:
    return "n/a" if x is None else f"{100 * x:.1f}"


def _pct_ci(e: dict) -> str:
    if not e or e.get("mean") is None:
        return "n/a"
    if e.get("ci_low") is None:
        return f"{_pct(e['mean'])}%"
    return f"{_pct(e['mean'])}% [{_pct(e['ci_low'])}, {_pct(e['ci_high'])}]"


def _num(x, fmt="{:.3g}") -> str:
    return "n/a" if x is None else fmt.format(x)


def findings_table(summary: dict) -> list[list[str]]:
    """Rows (with a header row) of the findings table: per condition the success rates, the difference and
    the paired t-test."""
    out = [
        [
            "condition",
            "GMM success (95% CI)",
            "KDE success (95% CI)",
            "GMM - KDE (95% CI), points",
            "t",
            "p (two-tailed)",
        ]
    ]
    for c, per in summary["success_rate"].items():
        tt = summary["ttest_gmm_vs_kde"].get(c, {})
        if "mean_difference" in tt:
            diff = (
                f"{100 * tt['mean_difference']:+.1f} [{_num(tt['ci_low'] and 100 * tt['ci_low'], '{:+.1f}')}, "
                f"{_num(tt['ci_high'] and 100 * tt['ci_high'], '{:+.1f}')}]"
            )
            t, p = _num(tt["t"], "{:.2f}"), _num(tt["p"], "{:.2g}")
        else:
            diff, t, p = "n/a", "n/a", "n/a"
        out.append([f"{c}: {CONDITIONS[c].description}", _pct_ci(per.get("gmm")), _pct_ci(per.get("kde")), diff, t, p])
    return out


def runtime_table(summary: dict) -> list[list[str]]:
    rt = summary["runtime"]
    med, ratio = rt.get("median_s", {}), rt.get("ratio_kde_over_gmm", {})
    out = [["stage", "GMM (ms)", "KDE (ms)", "KDE / GMM"]]
    for s in (*STAGES, "total"):
        out.append(
            [
                STAGE_LABELS.get(s, "total of the three"),
                *[_num(med[m][s] * 1e3, "{:.1f}") if m in med else "n/a" for m in METHODS],
                _num(ratio.get(s), "{:.2f}"),
            ]
        )
    for s, label in (
        ("features", "surface features (shared, not in total)"),
        ("execution", "grasp execution in Bullet"),
        ("acquisition", "4-camera acquisition"),
    ):
        out.append([label, *[_num(med[m][s] * 1e3, "{:.1f}") if m in med else "n/a" for m in METHODS], ""])
    return out


def outcomes_table(summary: dict) -> list[list[str]]:
    out = [["condition", "method", *REASONS]]
    for c, per in summary["outcomes"].items():
        for m, counts in per.items():
            extra = {k: v for k, v in counts.items() if k not in REASONS}
            row = [c, METHOD_LABELS[m], *[str(counts.get(k, 0)) for k in REASONS]]
            if extra:
                row[-1] += " (other: " + ", ".join(f"{k} {v}" for k, v in extra.items()) + ")"
            out.append(row)
    return out


def md_table(rows: list[list[str]]) -> str:
    """A Markdown table of rows of cells, the first row the header."""
    lines = ["| " + " | ".join(rows[0]) + " |", "|" + "|".join(" --- " for _ in rows[0]) + "|"]
    lines += ["| " + " | ".join(r) + " |" for r in rows[1:]]
    return "\n".join(lines)


def _html_table(rows: list[list[str]]) -> str:
    head = "".join(f"<th>{html.escape(h)}</th>" for h in rows[0])
    body = "".join("<tr>" + "".join(f"<td>{html.escape(c)}</td>" for c in r) + "</tr>" for r in rows[1:])
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def _clouds_text(proto: dict) -> str:
    """The cameras and what an acquisition kept."""
    cameras = "1 camera above the table" if proto["views"] == 1 else f"{proto['views']} cameras"
    kept = {
        "scene": "the whole depth images",
        "image": "the depth image with its intrinsics and pose (image space)",
    }.get(proto["cloud"], "the object's pixels")
    return f"{cameras}, {kept}"


def _synthesis_text(syn: dict) -> str:
    """The experts beyond the paper's that the synthesis ran (none: the paper's synthesis)."""
    extra = []
    if syn["collision"]["model"] == "occupancy":
        extra.append("the occupancy collision model")
    if syn["approach"] is not None:
        a = syn["approach"]
        extra.append(
            f"the clear approach (stand-off {100 * a['stand_off']:g} cm, clearance {1000 * a['clearance']:g} mm)"
        )
    if syn["contact_quality"] is not None:
        extra.append(f"the contact quality (friction {syn['contact_quality']['friction']:g})")
    if syn.get("grasp_depth") is not None:
        extra.append(f"the grasp depth (at least {1000 * syn['grasp_depth']['min_depth']:g} mm)")
    return ("Synthesis with " + ", ".join(extra) + ". ") if extra else "The paper's synthesis. "


def _noise_text(proto: dict) -> str:
    """The noise model of the conditions with noise: sigma_p and sigma_d."""
    sp, sd = proto["pixel_noise_std"], proto["depth_noise_std"]
    parts = "" if sp > 0 and sd > 0 else (" (depth noise only)" if sd > 0 else " (lateral shift only)")
    return f"Noise model (conditions with noise): sigma_p = {sp:g} px, sigma_d = {1000 * sd:g} mm{parts}. "


def _blocks(summary: dict) -> list[tuple]:
    prov = summary["provenance"]
    # Every field, the defaults where the file leaves one out (as the run read it).
    p = protocol_from_json(summary["protocol"])
    proto = {f: getattr(p, f) for f in PROTOCOL_FIELDS}
    syn = p.synthesis.to_dict()
    att = summary["attempts"]
    rt = summary["runtime"]
    blocks = [
        ("h1", "graspmix experiment report"),
        (
            "p",
            f"{len(proto['objects'])} objects x {proto['trials']} trials x conditions "
            f"{','.join(proto['conditions'])} x methods {','.join(proto['methods'])}: "
            f"{att['done']} of {att['expected']} attempts"
            + ("" if att["complete"] else " (INCOMPLETE run)")
            + f". {syn['sampling']['n_samples']} grasps sampled per attempt, the best {syn['sampling']['n_optimise']} "
            f"annealed ({syn['annealing']['iterations']} iterations, initial temperature "
            f"{syn['annealing']['initial_temperature']}, "
            f"linear decay) in conditions with optimisation; the best grasp is executed "
            + (
                "with the fingers closing until they stop on the object (force-limited). "
                if proto.get("closing", "full") == "full"
                else "with the simulation's default closing (just past the synthesised grasp joints). "
            )
            + f"Clouds: {_clouds_text(proto)}, points within {1000 * syn['segmentation']['table_clearance']:.0f} mm "
            f"of the support plane dropped, the same for both methods. {_synthesis_text(syn)}{_noise_text(proto)}"
            + provenance_text(prov),
        ),
    ]
    blocks += command_block(prov)
    blocks += [
        ("h2", "Success rates and paired t-tests (GMM vs KDE)"),
        (
            "p",
            "Success rate of a trial = successful grasps / objects. Means over trials with 95% confidence "
            "intervals (t distribution); differences in percentage points with the 95% CI of the mean "
            "per-trial difference; two-tailed paired t-test over trials (scipy.stats.ttest_rel).",
        ),
        ("table", findings_table(summary)),
        ("img", "success_rates.png", "Success rate per condition and method"),
        ("h2", "Runtime (the paper's Fig. runtime)"),
        (
            "p",
            f"Medians over {rt.get('n_objects', 0)} objects (per object the median over its attempts in "
            f"conditions {','.join(rt['conditions'])}) of the synthesis stages.",
        ),
        ("table", runtime_table(summary)),
        ("img", "runtime.png", "Stacked runtime per method"),
        ("h2", "Outcomes of the executed grasps"),
        ("table", outcomes_table(summary)),
    ]
    return blocks


def render_markdown(blocks) -> str:
    out = []
    for b in blocks:
        if b[0] == "h1":
            out.append(f"# {b[1]}")
        elif b[0] == "h2":
            out.append(f"## {b[1]}")
        elif b[0] == "p":
            out.append(b[1])
        elif b[0] == "code":
            out.append(f"```\n{b[1]}\n```")
        elif b[0] == "table":
            out.append(md_table(b[1]))
        elif b[0] == "img":
            out.append(f"![{b[2]}]({b[1]})")
    return "\n\n".join(out) + "\n"


def _html(blocks, folder: Path) -> str:
    parts = [
        "<!DOCTYPE html><html><head><meta charset='utf-8'><title>graspmix experiment report</title>",
        "<style>body{font-family:sans-serif;max-width:60em;margin:2em auto;}table{border-collapse:collapse;}"
        "td,th{border:1px solid #ccc;padding:3px 8px;font-size:90%;}pre{background:#f4f4f4;padding:6px;}"
        "</style></head><body>",
    ]
    for b in blocks:
        if b[0] in ("h1", "h2"):
            parts.append(f"<{b[0]}>{html.escape(b[1])}</{b[0]}>")
        elif b[0] == "p":
            parts.append(f"<p>{html.escape(b[1])}</p>")
        elif b[0] == "code":
            parts.append(f"<pre>{html.escape(b[1])}</pre>")
        elif b[0] == "table":
            parts.append(_html_table(b[1]))
        elif b[0] == "img":
            data = base64.b64encode((folder / b[1]).read_bytes()).decode()
            parts.append(f"<p><img alt='{html.escape(b[2])}' src='data:image/png;base64,{data}'></p>")
    parts.append("</body></html>")
    return "\n".join(parts) + "\n"


def check_rows(rows: list[dict], proto: dict, path: Path) -> None:
    """Every row belongs to the protocol (an object, trial, condition and method of it) and has an outcome:
    a CSV edited by hand is an error naming its row, not a wrong summary."""
    known = {"object": set(proto["objects"]), "condition": set(proto["conditions"]), "method": set(proto["methods"])}
    for i, r in enumerate(rows, start=1):
        empty = [c for c in RECORDED_COLUMNS if r[c] is None]
        if empty:
            raise ValueError(f"{path}: row {i}: {', '.join(empty)} empty (every attempt records it)")
        for col, values in known.items():
            if r[col] not in values:
                raise ValueError(f"{path}: row {i}: {col} {quote(r[col])} is not in the run's protocol")
        if r["trial"] is None or not 0 <= r["trial"] < proto["trials"]:
            raise ValueError(f"{path}: row {i}: trial {quote(r['trial'])} is not in 0..{proto['trials'] - 1}")
        if r["success"] not in (0, 1):
            raise ValueError(f"{path}: row {i}: success must be 0 or 1, got {quote(r['success'])}")
        # A synthesis that ran has all its times (a failed one none): the runtime figure adds them up.
        times = [f"t_{s}" for s in (*STAGES, "features")]
        given = [t for t in times if r[t] is not None]
        if given and len(given) < len(times):
            missing = ", ".join(t for t in times if r[t] is None)
            raise ValueError(f"{path}: row {i}: {missing} empty while {given[0]} is given")


def build_report(run_dir: str | Path) -> dict:
    """Reads attempts.csv and protocol.json of a run folder; writes summary.json, success_rates.png,
    runtime.png, report.md and report.html; returns the summary."""
    run_dir = Path(run_dir)
    if not run_dir.is_dir():
        raise ValueError(f"{run_dir}: no such run folder")
    doc = load_protocol(run_dir)
    rows = read_rows(run_dir / CSV_NAME)
    if not rows:
        raise ValueError(f"{run_dir / CSV_NAME}: no attempts yet")
    check_rows(rows, doc["protocol"], run_dir / CSV_NAME)
    for name in ("summary.json", "success_rates.png", "runtime.png", "report.md", "report.html"):
        check_output_path(run_dir / name, "report")
    summary = summarize(rows, doc)
    (run_dir / "summary.json").write_text(json.dumps(summary, indent=1) + "\n")
    plot_success(summary, run_dir / "success_rates.png")
    if summary["runtime"]["median_s"]:
        plot_runtime(
            summary["runtime"]["median_s"],
            run_dir / "runtime.png",
            title=f"Synthesis time per object, median over {summary['runtime'].get('n_objects', 0)} objects",
        )
    blocks = _blocks(summary)
    if not summary["runtime"]["median_s"]:
        blocks = [b for b in blocks if not (b[0] == "img" and b[1] == "runtime.png")]
    (run_dir / "report.md").write_text(render_markdown(blocks))
    (run_dir / "report.html").write_text(_html(blocks, run_dir))
    return summary
