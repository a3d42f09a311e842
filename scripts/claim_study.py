#!/usr/bin/env python3
"""Renders the tables of docs/paper-claim.md from the runs in results/, between markers

    <!-- NAME:begin -->
    <!-- NAME:end -->

(NAME: claim, sweep, fair, noise, failures, changes, starts, closing), so the page's numbers come from runs, never from a hand.

    python scripts/claim_study.py [--results results] [--doc docs/paper-claim.md]

Reads results/paper-old-demo (the paper protocol on the models learnt from the demonstration as the
old recorder wrote it, which every other run here used), results/noise-study/{lateral-only,depth-only} (conditions B, D with
one part of the noise model), results/sweep/sweep.json (the settings sweep on the development objects) and,
if present, results/paper-fair (the paper protocol with the settings the sweep chose).
"""

from __future__ import annotations

import argparse
import functools
import gzip
import json
import re
import sys
import tempfile
from pathlib import Path

import numpy as np
from graspmix.experiment.compare import Cell, cell, difference, outcome_change, outcome_shares
from graspmix.experiment.log import read_rows
from graspmix.experiment.report import findings_table, md_table
from graspmix.model import Grasp
from graspmix.model.grasp_frames import rotation_matrices
from graspmix.sim.execution import load_hand

NOISE_RUNS = {"lateral only": "noise-study/lateral-only", "depth only": "noise-study/depth-only"}
REASONS = ("success", "start in collision", "no contact", "not held")
# The paper protocol's run that the other runs here are paired with: made with the same models (learnt from
# the demonstration the old recorder wrote); results/paper is the run on today's models.
PAPER = "paper-old-demo"


@functools.lru_cache(maxsize=None)
def rows_of(run: Path) -> list[dict]:
    """attempts.csv of a run folder, or its gzipped copy (results/ keeps them gzipped)."""
    if (run / "attempts.csv").is_file():
        return read_rows(run / "attempts.csv")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "attempts.csv"
        path.write_bytes(gzip.decompress((run / "attempts.csv.gz").read_bytes()))
        return read_rows(path)


def noise_runs(results: Path) -> dict:
    """label -> rows of the runs with one part of the noise model (conditions B, D), those that exist."""
    return {label: rows_of(results / f) for label, f in NOISE_RUNS.items() if (results / f).is_dir()}


def pct(x: float) -> str:
    return f"{100 * x:.1f}%"


def diff_text(d) -> str:
    t, o = d.trials, d.objects
    return f"{100 * d.difference:+.1f} (p {t['p']:.2g} / {o['p']:.2g})"


def claim_block(results: Path) -> str:
    s = json.loads((results / PAPER / "summary.json").read_text())
    return md_table(findings_table(s))


def noise_block(results: Path) -> str:
    """Per noise setting and optimisation: each method's success, GMM - KDE, and each method's cost of the
    noise against the same trials without noise (paired; p over trials / over objects)."""
    paper = rows_of(results / PAPER)
    runs = {"none": (paper, "A", "C"), "lateral + depth (the paper's)": (paper, "B", "D")}
    runs.update({label: (rows, "B", "D") for label, rows in noise_runs(results).items()})
    out = [["noise", "optimisation", "GMM", "KDE", "GMM - KDE, points (p trials / objects)",
            "GMM: noise cost", "KDE: noise cost"]]  # fmt: skip
    figure = []
    for opt, k in (("with", 1), ("without", 2)):
        base = {m: cell(paper, "A" if k == 1 else "C", m) for m in ("gmm", "kde")}
        for label, entry in runs.items():
            rows, cond = entry[0], entry[k]
            c = {m: cell(rows, cond, m) for m in ("gmm", "kde")}
            cost = ["" if label == "none" else diff_text(difference(c[m], base[m])) for m in ("gmm", "kde")]
            out.append([label, opt, pct(c["gmm"].rate), pct(c["kde"].rate),
                        diff_text(difference(c["gmm"], c["kde"])), *cost])  # fmt: skip
            figure.append((label, opt, c))
    plot_noise_parts(figure, results / "noise-study" / "noise_parts.png")
    return md_table(out) + "\n\n![success per noise setting](../results/noise-study/noise_parts.png)"


def plot_noise_parts(cells: list, path: Path) -> None:
    """Success per noise setting, with and without optimisation, per method: the mean over the trials with the
    95% interval over the objects (each object's success averaged over its trials)."""
    from graspmix.experiment.stats import mean_ci
    from graspmix.viz.experiment import COLOURS
    from graspmix.viz.plots import pyplot

    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.6), sharey=True)
    for ax, opt in zip(axes, ("with", "without")):
        entries = [(label, c) for label, o, c in cells if o == opt]
        for i, (_, c) in enumerate(entries):
            for j, m in enumerate(("gmm", "kde")):
                ci = mean_ci(c[m].success.mean(axis=0))
                x = i + (j - 0.5) * 0.35
                ax.bar(x, 100 * ci.mean, 0.33, color=COLOURS[m], label=m.upper() if i == 0 else None)
                ax.errorbar(x, 100 * ci.mean, yerr=[[100 * (ci.mean - ci.low)], [100 * (ci.high - ci.mean)]],
                            color="k", capsize=3, lw=1)  # fmt: skip
        ax.set_xticks(np.arange(len(entries)))
        ax.set_xticklabels([label.replace(" (the paper's)", "\n(the paper's)") for label, _ in entries], fontsize=8)
        ax.set_title(f"{opt} optimisation", fontsize=10)
        ax.set_ylim(50, 100)
        ax.grid(axis="y", alpha=0.3)
    axes[0].set_ylabel("success (%), 95% CI over objects")
    axes[0].legend(loc="lower left")
    fig.suptitle("The noise model taken apart: 60 test objects x 10 trials per bar", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def failures_block(results: Path) -> str:
    """Outcome shares per noise setting (with optimisation) and method."""
    paper = rows_of(results / PAPER)
    runs = {"none (A)": (paper, "A"), "the paper's (B)": (paper, "B")}
    runs.update({f"{label} (B)": (rows, "B") for label, rows in noise_runs(results).items()})
    cells: dict[tuple, Cell] = {}
    reasons: list[str] = list(REASONS)
    for label, (rows, cond) in runs.items():
        for m in ("gmm", "kde"):
            cells[(label, m)] = cell(rows, cond, m)
            reasons += [r for r in cells[(label, m)].reasons if r not in reasons]
    reasons = [r for r in reasons if any(r in c.reasons for c in cells.values())]
    out = [["noise", "method", *reasons]]
    for (label, m), c in cells.items():
        sh = outcome_shares(c)
        out.append([label, m.upper(), *(pct(sh.get(r, 0.0)) for r in reasons)])
    return md_table(out)


def changes_block(results: Path) -> str:
    """Per method and noise setting (with optimisation), each failure class against no noise over the same
    attempts: its share without and with the noise, and the exact McNemar test of the attempts that changed."""
    paper = rows_of(results / PAPER)
    runs = {"the paper's": (paper, "B")}
    runs.update({label: (rows, "B") for label, rows in noise_runs(results).items()})
    out = [["method", "noise", *(f"{r}: none -> noise (p)" for r in REASONS[1:])]]
    for m in ("gmm", "kde"):
        base = cell(paper, "A", m)
        for label, (rows, cond) in runs.items():
            c = cell(rows, cond, m)
            cells = []
            for r in REASONS[1:]:
                ch = outcome_change(base, c, r)
                cells.append(f"{pct(ch.share_a)} -> {pct(ch.share_b)} ({ch.p:.2g})")
            out.append([m.upper(), label, *cells])
    return md_table(out)


def approach_z(wrist) -> float:
    """The world z of the bundled hand's approach axis (-1: straight down) at a wrist pose [x, y, z, qx, qy, qz, qw]."""
    return float((rotation_matrices(np.asarray(wrist[3:])[None])[0] @ load_hand().approach_axis)[2])


def starts_block(results: Path) -> str:
    """What the grasps that started in collision penetrate (pybullet at the pre-grasp, the same URDFs): per
    run, condition and method, the attempts per (object or plane, link) and the median depth."""
    from graspmix.sim.pybullet_reference import start_penetrations

    paper = rows_of(results / PAPER)
    runs = [("none (A)", paper, "A"), ("the paper's (B)", paper, "B")]
    runs += [(f"{label} (B)", rows, "B") for label, rows in noise_runs(results).items()]
    out = [["noise", "method", "started in collision", "approach axis z (median)",
            "what the hand penetrates: attempts (median depth)"]]  # fmt: skip
    for label, rows, cond in runs:
        for m in ("gmm", "kde"):
            sel = [
                r for r in rows if r["condition"] == cond and r["method"] == m and r["reason"] == "start in collision"
            ]
            depths: dict = {}
            for r in sel:
                for key, d in start_penetrations(r["object"], Grasp.from_dict(json.loads(r["grasp"]))).items():
                    depths.setdefault(key, []).append(d)
            parts = [
                f"{what} / {link}: {len(d)} ({1000 * float(np.median(d)):.1f} mm)"
                for (what, link), d in sorted(depths.items(), key=lambda kv: -len(kv[1]))
            ]
            approach = [approach_z(json.loads(r["grasp"])["T_world_wrist"]) for r in sel]
            az = f"{float(np.median(approach)):+.2f}" if approach else ""
            out.append([label, m.upper(), str(len(sel)), az, "; ".join(parts)])
    return md_table(out)


def sweep_block(results: Path) -> str:
    s = json.loads((results / "sweep" / "sweep.json").read_text())
    out = [["setting", "method", "default", "success per value (mean of the conditions)", "best on dev"]]
    for name, e in s["parameters"].items():
        for m, me in e["methods"].items():
            vals = ", ".join(f"{p['value']:g}: {100 * p['mean']:.1f}%" for p in me["points"])
            out.append([name, m.upper(), f"{e['default']:g}", vals, f"{me['best']:g}"])
    head = (
        f"{len(s['objects'])} development objects x {s['trials']} trials x conditions "
        f"{','.join(s['conditions'])}; each value run with every other setting at its default.\n\n"
    )
    return head + md_table(out)


def fair_block(results: Path) -> str:
    path = results / "paper-fair" / "summary.json"
    if not path.is_file():
        return "(no run with other settings: the sweep chose the defaults for both methods)"
    paper, fair = rows_of(results / PAPER), rows_of(results / "paper-fair")
    gains = [["condition", "GMM: default -> chosen, points (p trials / objects)", "KDE: default -> chosen"]]
    for c in json.loads(path.read_text())["success_rate"]:
        gains.append([c, *(diff_text(difference(cell(fair, c, m), cell(paper, c, m))) for m in ("gmm", "kde"))])
    return (
        md_table(findings_table(json.loads(path.read_text()))) + "\n\nEach method's gain from its chosen settings on "
        f"the same attempts (`results/paper-fair` against `results/{PAPER}`):\n\n" + md_table(gains)
    )


def closing_block(results: Path) -> str:
    """The paper protocol with --closing learnt: the paper's settings, and each method's chosen settings."""
    out = []
    for folder, what in (
        ("paper-learnt-closing", "the paper's settings"),
        ("paper-fair-learnt-closing", "the chosen settings"),
    ):
        path = results / folder / "summary.json"
        if path.is_file():
            commit = json.loads(path.read_text())["provenance"].get("commit", "?")[:7]
            out.append(
                f"`results/{folder}` ({what}, commit `{commit}`):\n\n"
                + md_table(findings_table(json.loads(path.read_text())))
            )
    return "\n\n".join(out) or "(no run with --closing learnt)"


BLOCKS = {"claim": claim_block, "sweep": sweep_block, "fair": fair_block, "noise": noise_block,
          "failures": failures_block, "changes": changes_block, "starts": starts_block,
          "closing": closing_block}  # fmt: skip


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--results", type=Path, default=Path("results"))
    ap.add_argument("--doc", type=Path, default=Path("docs/paper-claim.md"))
    args = ap.parse_args()
    text = args.doc.read_text()
    for name, render in BLOCKS.items():
        pattern = re.compile(rf"(<!-- {name}:begin -->\n).*?(<!-- {name}:end -->)", re.S)
        if not pattern.search(text):
            print(f"{args.doc}: no {name} markers", file=sys.stderr)
            return 2
        block = render(args.results)
        text = pattern.sub(lambda m, b=block: m.group(1) + b + "\n" + m.group(2), text)
    args.doc.write_text(text)
    print(f"wrote {args.doc}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
