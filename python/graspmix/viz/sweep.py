"""The figure of a settings sweep: success against each parameter's value, per method and condition."""

from __future__ import annotations

from pathlib import Path

from .experiment import COLOURS
from .plots import pyplot

_MARKERS = ["o", "s", "^", "D"]


def plot_sweep(result: dict, path: str | Path) -> None:
    """One panel per parameter: each value's success (95% interval, objects as clusters) per method (colour)
    and condition (marker), the values evenly spaced, the default's tick in bold. result: sweep.json."""
    plt = pyplot()
    params = result["parameters"]
    conds = list(result["conditions"])
    fig, axes = plt.subplots(1, len(params), figsize=(3.2 * len(params) + 0.6, 3.4), squeeze=False, sharey=True)
    for ax, (name, entry) in zip(axes[0], params.items()):
        for m, me in entry["methods"].items():
            values = [p["value"] for p in me["points"]]
            for k, c in enumerate(conds):
                xs, ys, err = [], [], [[], []]
                for i, p in enumerate(me["points"]):
                    e = p["conditions"].get(c)
                    if e is None:
                        continue
                    x = i + (k - (len(conds) - 1) / 2) * 0.08
                    xs.append(x)
                    ys.append(100 * e["rate"])
                    err[0].append(100 * (e["rate"] - e["ci_low"]))
                    err[1].append(100 * (e["ci_high"] - e["rate"]))
                ax.errorbar(
                    xs, ys, yerr=err, color=COLOURS[m], marker=_MARKERS[k % len(_MARKERS)], capsize=2, lw=1,
                    label=f"{result['methods'][m]} {c}",
                )  # fmt: skip
            ax.set_xticks(range(len(values)))
            ax.set_xticklabels([f"{v:g}" for v in values], rotation=30)
            for tick, v in zip(ax.get_xticklabels(), values):
                if v == entry["default"]:
                    tick.set_fontweight("bold")
        ax.set_title(name, fontsize=9)
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("success (%)")
    handles, labels = axes[0][0].get_legend_handles_labels()
    for ax in axes[0][1:]:
        h, lab = ax.get_legend_handles_labels()
        handles += [x for x, y in zip(h, lab) if y not in labels]
        labels += [y for y in lab if y not in labels]
    fig.legend(handles, labels, loc="lower center", ncol=min(len(labels), 6), fontsize=8)
    fig.suptitle(f"{len(result['objects'])} development objects x {result['trials']} trials (default in bold)")
    fig.tight_layout(rect=(0, 0.12, 1, 0.95))
    fig.savefig(path, dpi=110)
    plt.close(fig)
