"""The clutter-removal protocol's figure: GSR and DR per mode and method with their 95% intervals, and
the outcomes of the attempts."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .plots import pyplot

METHOD_COLOURS = {"gmm": "#1f77b4", "kde": "#ff7f0e", "topdown": "#7f7f7f"}
OUTCOME_COLOURS = {
    "success": "#55a868",
    "start in collision": "#c44e52",
    "no contact": "#8172b2",
    "not held": "#ccb974",
    "two objects lifted": "#64b5cd",
    "synthesis failed": "#4c4c4c",
}


def _rate_panel(ax, summary: dict, key: str, label: str) -> None:
    modes = list(summary["results"])
    methods = list(dict.fromkeys(m for per in summary["results"].values() for m in per))
    width = 0.8 / max(len(methods), 1)
    for i, m in enumerate(methods):
        xs, v, lo, hi = [], [], [], []
        for j, mode in enumerate(modes):
            e = summary["results"][mode].get(m)
            if e is None:
                continue
            r = e[key]
            xs.append(j + (i - (len(methods) - 1) / 2) * width)
            v.append(100 * r["rate"])
            lo.append(100 * (r["rate"] - r["low"]))
            hi.append(100 * (r["high"] - r["rate"]))
        ax.bar(xs, v, width * 0.9, yerr=[lo, hi], capsize=3, color=METHOD_COLOURS.get(m, "#999999"), label=m, zorder=2)
    ax.set_xticks(range(len(modes)))
    ax.set_xticklabels(modes)
    ax.set_ylim(0, 100)
    ax.set_ylabel(f"{label} (%)")
    ax.grid(axis="y", alpha=0.3, zorder=0)
    ax.set_title(f"{label}, 95% CI", fontsize=9)


def _outcome_panel(ax, summary: dict) -> None:
    cells = [(mode, m, c) for mode, per in summary["results"].items() for m, c in per.items()]
    bottom = np.zeros(len(cells))
    for o, colour in OUTCOME_COLOURS.items():
        v = np.array([c["outcomes"].get(o, 0) for _, _, c in cells], dtype=float)
        if v.any():
            ax.bar(range(len(cells)), v, 0.6, bottom=bottom, color=colour, label=o)
            bottom += v
    ax.set_xticks(range(len(cells)))
    ax.set_xticklabels([f"{mode}\n{m}" for mode, m, _ in cells], fontsize=8)
    ax.set_ylabel("attempts")
    ax.legend(fontsize=6, loc="upper right")
    ax.set_title("Outcomes", fontsize=9)


def plot_clutter(summary: dict, path: str | Path) -> None:
    """summary: a clutter run's summary.json content."""
    plt = pyplot()
    fig, axes = plt.subplots(1, 3, figsize=(11, 3.6))
    _rate_panel(axes[0], summary, "gsr", "grasp success rate")
    _rate_panel(axes[1], summary, "dr", "declutter rate")
    axes[0].legend(fontsize=8, loc="lower right")
    _outcome_panel(axes[2], summary)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
