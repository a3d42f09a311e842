"""The figure of a settings sweep: success against each parameter's value, per method and condition."""

from __future__ import annotations

import math
from pathlib import Path

from .experiment import COLOURS
from .plots import pyplot

_MARKERS = ["o", "s", "^", "D"]
_COLUMNS = 4


def _panel(ax, name: str, entry: dict, conds: list, labels: dict) -> None:
    """One parameter: per method the mean over the conditions (thick) and each condition (thin, with its 95%
    interval, objects as clusters), the values evenly spaced, the default's tick in bold."""
    values = []
    for m, me in entry["methods"].items():
        values = [p["value"] for p in me["points"]]
        xs = list(range(len(values)))
        ax.plot(xs, [100 * p["mean"] for p in me["points"]], color=COLOURS[m], lw=2.5, label=f"{labels[m]} mean")
        for k, c in enumerate(conds):
            pts = [(i, p["conditions"][c]) for i, p in enumerate(me["points"]) if c in p["conditions"]]
            dx = (k - (len(conds) - 1) / 2) * 0.06
            ax.errorbar(
                [i + dx for i, _ in pts], [100 * e["rate"] for _, e in pts],
                yerr=[[100 * (e["rate"] - e["ci_low"]) for _, e in pts], [100 * (e["ci_high"] - e["rate"]) for _, e in pts]],
                color=COLOURS[m], marker=_MARKERS[k % len(_MARKERS)], ms=3, lw=0.6, capsize=1.5, alpha=0.4,
                label=f"{labels[m]} {c}",
            )  # fmt: skip
    ax.set_xticks(range(len(values)))
    ax.set_xticklabels([f"{v:g}" for v in values])
    for tick, v in zip(ax.get_xticklabels(), values):
        if v == entry["default"]:
            tick.set_fontweight("bold")
    ax.set_title(name, fontsize=9)
    ax.grid(alpha=0.3)


def plot_sweep(result: dict, path: str | Path) -> None:
    """One panel per parameter (_panel), four to a row. result: sweep.json."""
    plt = pyplot()
    params = result["parameters"]
    conds = list(result["conditions"])
    cols = min(_COLUMNS, len(params))
    rows = math.ceil(len(params) / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(3.3 * cols, 2.8 * rows + 0.9), squeeze=False, sharey=True)
    for ax, (name, entry) in zip(axes.flat, params.items()):
        _panel(ax, name, entry, conds, result["methods"])
    for ax in list(axes.flat)[len(params) :]:
        ax.axis("off")
    for r in range(rows):
        axes[r][0].set_ylabel("success (%)")
    handles = {}
    for ax in axes.flat:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            handles.setdefault(lab, h)
    fig.legend(list(handles.values()), list(handles), loc="lower center", ncol=min(len(handles), 5), fontsize=8)
    fig.suptitle(
        f"{len(result['objects'])} development objects x {result['trials']} trials x conditions "
        f"{','.join(conds)}: success against each setting (the default in bold)",
        fontsize=10,
    )
    fig.tight_layout(rect=(0, 0.09 + 0.02 * (len(handles) > 5), 1, 0.96))
    fig.savefig(path, dpi=110)
    plt.close(fig)
