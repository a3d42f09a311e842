"""The noise study's outputs (graspmix.experiment.noise_effects): figures of the features, the weighted
frame jitter and the scalar measures per setting and method, and a compact text table."""

from __future__ import annotations

import numpy as np

from .noise_effects import MEASURES, log_curvatures, weighted_median

DEMO_COLOURS = ("tab:green", "tab:purple", "tab:olive")
SETTING_COLOURS = {"clean": "black", "lateral": "tab:blue", "depth": "tab:orange", "full": "tab:red"}
SURFACE_LABELS = {
    "n_surface": "query surface points (after voxel grid)",
    "flat_fraction": "query points with k1 < 1e-3",
}
MEASURE_LABELS = {
    "effective_fraction": "M_i(r): effective points / points",
    "effective_points": "M_i(r): effective points exp(H)",
    "top10_weight": "M_i(r): weight on top 10% points",
    "jitter_mean": "M_i(r)-weighted jitter angle (rad)",
    "jitter_undetermined": "M_i(r) weight with jitter > pi/2",
    "weighted_k1": "M_i(r)-weighted median k1 of query points",
    "max_log_density": "max over points of log M_i(r)",
    "query_spread": "Q_i samples: RMS spread (m)",
    "query_means_spread": "Q_i components: RMS spread (m)",
    "query_components": "Q_i: effective components",
}


def plot_features(result: dict, demo: dict, path) -> None:
    """log10 k1 and k2 of the query points per setting (pooled, each unit weighing 1) over the
    demonstration's contact points' features per link (weighted by contact weight)."""
    from ..viz.plots import pyplot

    plt = pyplot()
    h = result["histograms"]
    bins = np.asarray(h["log10_curvature_bins"])
    centres, width = (bins[:-1] + bins[1:]) / 2, np.diff(bins)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    for i, (ax, key) in enumerate(zip(axes, ("k1", "k2"))):
        for j, (link, (r, w)) in enumerate(demo.items()):
            ax.hist(log_curvatures(r)[:, i], bins, weights=w / w.sum(), alpha=0.3, color=DEMO_COLOURS[j % 3],
                    label=f"demonstration contacts: {link}")  # fmt: skip
        for s, counts in h[key].items():
            c = np.asarray(counts)
            ax.step(centres, c / c.sum(), where="mid", color=SETTING_COLOURS.get(s), label=f"query points: {s}")
        ax.set_xlabel(f"log10 {key} (PCL principal curvature; first bin: <= 1e{bins[1]:.3g})")
        ax.set_ylabel(f"share of points per {width[0]:.3g}-decade bin")
        ax.set_yscale("log")
        ax.set_ylim(1e-5, 1.5)
    axes[0].legend(fontsize=7, loc="upper left")
    fig.suptitle("Curvature features of the query points by noise setting, and of the demonstration's contacts")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_jitter(result: dict, path) -> None:
    """The M_i(r)-weighted distribution of the frame jitter angle per setting, one panel per method."""
    from ..viz.plots import pyplot

    plt = pyplot()
    h = result["histograms"]
    bins = np.asarray(h["log10_jitter_bins"])
    centres = (bins[:-1] + bins[1:]) / 2
    methods = result["methods"]
    fig, axes = plt.subplots(1, len(methods), figsize=(5.5 * len(methods), 4), squeeze=False)
    for ax, m in zip(axes[0], methods):
        for s, d in h["jitter"].items():
            c = np.asarray(d[m])
            ax.step(centres, c / max(c.sum(), 1e-300), where="mid", color=SETTING_COLOURS.get(s), label=s)
        ax.set_title(f"{m.upper()}: jitter angle weighted by M_i(r)")
        ax.set_xlabel(f"log10 of pi exp(-s ((k1 - k2) / k1)^2) (rad; first bin: <= 1e{bins[1]:.3g})")
        ax.axvline(np.log10(np.pi / 2), color="grey", lw=0.8, ls=":")  # beyond: the heading is mostly undetermined
        ax.set_yscale("log")
        ax.set_ylabel("share of weight")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_measures(result: dict, path) -> None:
    """Median and interquartile range over units of every scalar measure, per setting and method."""
    from ..viz.plots import pyplot

    plt = pyplot()
    summary = result["summary"]
    settings = result["settings"]
    methods = result["methods"]
    fig, axes = plt.subplots(3, 4, figsize=(16, 10.5))
    for ax, k in zip(axes.ravel(), MEASURES):
        for j, m in enumerate(methods):
            x = np.arange(len(settings)) + (j - (len(methods) - 1) / 2) * 0.15
            q = [summary[s][m][k] for s in settings]
            med = np.array([np.nan if v["median"] is None else v["median"] for v in q])
            lo = med - np.array([np.nan if v["q1"] is None else v["q1"] for v in q])
            hi = np.array([np.nan if v["q3"] is None else v["q3"] for v in q]) - med
            ax.errorbar(x, med, yerr=[lo, hi], fmt="o", capsize=3, label=m.upper(), color=f"C{j}")
        ax.set_xticks(range(len(settings)), settings)
        ax.set_title(MEASURE_LABELS[k], fontsize=9)
        if k == "query_components":
            ax.set_yscale("log")  # K_Q components (GMM) against N_Q kernels (KDE)
    axes[0, 0].legend()
    for ax, key in zip(axes.ravel()[len(MEASURES) :], ("n_surface", "flat_fraction")):
        q = [summary[s][key] for s in settings]
        med = np.array([v["median"] for v in q], dtype=float)
        err = [med - np.array([v["q1"] for v in q], dtype=float), np.array([v["q3"] for v in q], dtype=float) - med]
        ax.errorbar(range(len(settings)), med, yerr=err, fmt="s", capsize=3, color="grey")
        ax.set_xticks(range(len(settings)), settings)
        ax.set_title(SURFACE_LABELS[key], fontsize=9)
    for ax in axes.ravel()[len(MEASURES) + len(SURFACE_LABELS) :]:
        ax.set_visible(False)
    fig.suptitle("What noise does inside the pipeline: median and IQR over objects x trials")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def table(result: dict) -> str:
    """A compact text table: per measure, the median [q1, q3] per setting, GMM and KDE."""
    summary = result["summary"]
    settings = result["settings"]
    methods = result["methods"]
    lines = [f"{'measure':<22}{'method':<7}" + "".join(f"{s:>30}" for s in settings)]
    for k in MEASURES:
        for m in methods:
            cells = []
            for s in settings:
                q = summary[s][m][k]
                cells.append("--" if q["median"] is None else f"{q['median']:.3g} [{q['q1']:.3g}, {q['q3']:.3g}]")
            lines.append(f"{k:<22}{m:<7}" + "".join(f"{c:>30}" for c in cells))
    for key in ("n_surface", "median_k1", "median_k2", "flat_fraction", "n_targets"):
        cells = [
            f"{summary[s][key]['median']:.3g}" if summary[s][key]["median"] is not None else "--" for s in settings
        ]
        lines.append(f"{key:<29}" + "".join(f"{c:>30}" for c in cells))
    lines.append(f"{'failed units':<29}" + "".join(f"{summary[s]['errors']:>30}" for s in settings))
    return "\n".join(lines)


EFFECTS_FORMAT = "graspmix.noise_effects/1"


def write_outputs(result: dict, demo: dict, out, provenance: dict) -> list:
    """out/effects.json (the summary and histograms), the three figures and out/units.json (the per-unit
    rows); returns the paths."""
    import json
    from pathlib import Path

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    doc = {"format": EFFECTS_FORMAT, "provenance": provenance, **{k: v for k, v in result.items() if k != "units"}}
    doc["demonstration_contacts"] = {
        link: {"n": int(len(w)), "weighted_median_k": [weighted_median(r[:, i], w) for i in range(2)]}
        for link, (r, w) in demo.items()
    }
    paths = [out / "effects.json", out / "features.png", out / "jitter.png", out / "measures.png"]
    paths[0].write_text(json.dumps(doc, indent=1) + "\n")
    # The per-unit rows (object, trial, setting; per method and link every measure): compact, beside it.
    units = {"format": EFFECTS_FORMAT, "provenance": provenance, "units": _rounded(result["units"])}
    paths.append(out / "units.json")
    paths[-1].write_text(json.dumps(units, separators=(",", ":")) + "\n")
    plot_features(result, demo, paths[1])
    plot_jitter(result, paths[2])
    plot_measures(result, paths[3])
    return paths


def _rounded(x):
    """Floats to 6 significant digits, in nested lists and dicts."""
    if isinstance(x, float):
        return float(f"{x:.6g}")
    if isinstance(x, dict):
        return {k: _rounded(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_rounded(v) for v in x]
    return x
