"""The experiment's figures: success rates per condition and method, and the paper's Fig. runtime."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..model.grasps import STAGE_LABELS, STAGES
from ..model.settings import METHOD_LABELS, METHODS
from .plots import pyplot

COLOURS = {"gmm": "#1f77b4", "kde": "#ff7f0e"}
STAGE_COLOURS = {"query": "#4c72b0", "sampling": "#55a868", "optimisation": "#c44e52"}


def _condition_tick(summary: dict, c: str) -> str:
    """The label of condition c from the protocol's condition definitions (noise, optimisation)."""
    d = summary["protocol"]["condition_definitions"][c]
    return f"{c}\n{'noise' if d['noise'] else 'no noise'}, {'opt.' if d['optimise'] else 'no opt.'}"


def plot_success(summary: dict, path: str | Path) -> None:
    """Success rate per condition and method: mean over trials, 95% CI bars, per-trial rates as dots.
    summary: an experiment's summary.json content."""
    plt = pyplot()
    conds = list(summary["success_rate"])
    methods = [m for m in METHODS if any(m in summary["success_rate"][c] for c in conds)]
    fig, ax = plt.subplots(figsize=(1.6 + 1.5 * len(conds), 3.6))
    width = 0.8 / max(len(methods), 1)
    rng = np.random.default_rng(0)  # jitter of the dots only
    for i, m in enumerate(methods):
        xs, means, lo, hi = [], [], [], []
        for j, c in enumerate(conds):
            e = summary["success_rate"][c].get(m)
            if not e or e.get("mean") is None:
                continue
            x = j + (i - (len(methods) - 1) / 2) * width
            xs.append(x)
            means.append(100 * e["mean"])
            lo.append(100 * (e["mean"] - e["ci_low"]) if e.get("ci_low") is not None else 0)
            hi.append(100 * (e["ci_high"] - e["mean"]) if e.get("ci_high") is not None else 0)
            pts = 100 * np.asarray(list(e["per_trial"].values()))
            ax.scatter(x + rng.uniform(-width / 5, width / 5, len(pts)), pts, s=8, color="k", alpha=0.5, zorder=3)
        ax.bar(xs, means, width * 0.9, yerr=[lo, hi], capsize=3, color=COLOURS[m], label=METHOD_LABELS[m], zorder=2)
    ax.set_xticks(range(len(conds)))
    ax.set_xticklabels([_condition_tick(summary, c) for c in conds], fontsize=8)
    ax.set_ylabel("success rate (%)")
    ax.set_ylim(0, 100)
    ax.grid(axis="y", alpha=0.3, zorder=0)
    ax.legend(fontsize=8, loc="upper right")
    n = summary["protocol"]["trials"]
    ax.set_title(f"Success rate per condition: mean of {n} trials, 95% CI (dots: trials)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_runtime(medians: dict, path: str | Path, title: str = "") -> None:
    """The paper's Fig. runtime: stacked bars of the median stage times per method (seconds)."""
    plt = pyplot()
    methods = [m for m in METHODS if m in medians]
    fig, ax = plt.subplots(figsize=(4.2, 3.6))
    bottom = np.zeros(len(methods))
    for s in STAGES:
        v = np.array([medians[m][s] for m in methods])
        ax.bar(
            [METHOD_LABELS[m] for m in methods], v, 0.55, bottom=bottom, color=STAGE_COLOURS[s], label=STAGE_LABELS[s]
        )
        bottom += v
    for i, b in enumerate(bottom):
        ax.text(i, b, f"{b * 1e3:.0f} ms", ha="center", va="bottom", fontsize=8)
    ax.set_ylabel("time (s)")
    ax.set_ylim(0, max(bottom.max() * 1.2, 1e-3))
    ax.legend(fontsize=7, loc="upper left")
    ax.set_title(title or "Synthesis time per object (medians)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
