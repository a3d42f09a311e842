"""The paper's Fig. runtime: the synthesis stages of GMM and KDE on the test objects' noise-free clouds,
medians over objects, and KDE / GMM."""

from __future__ import annotations

import json
import math
import os
from pathlib import Path

import numpy as np

from ..io import BENCHMARK_FORMAT, git_commit, package_version
from ..io.checks import check_output_folder
from ..model.grasps import STAGE_LABELS, STAGES
from ..model.options import SynthesisOptions
from ..model.settings import METHODS
from ..viz.experiment import plot_runtime
from .attempt import acquire_unit, cached_model, synthesize_on
from .progress import Progress
from .protocol import Protocol

_SHARED = ("segmentation", "features")  # stages before the synthesiser's, the same for both methods


def _time_objects(p: Protocol, objects: list[str], progress: bool) -> dict:
    """method -> stage -> per-object seconds."""
    per_object = {m: {s: [] for s in (*STAGES, *_SHARED, "total")} for m in METHODS}
    bar = Progress(len(objects) * len(METHODS), enabled=progress)
    for i, obj in enumerate(objects):
        acq = acquire_unit(p, obj, 0, False)  # condition A's cloud (the preset's cameras and what it keeps)
        for m in METHODS if i % 2 == 0 else METHODS[::-1]:  # alternate which method runs first
            model = cached_model(str(p.model_path(m).resolve()))
            g = synthesize_on(model, acq, p, obj, 0, "A")
            for s in (*STAGES, *_SHARED):
                per_object[m][s].append(float(g.timing[s]))
            per_object[m]["total"].append(float(sum(g.timing[s] for s in STAGES)))
            bar.update(1)
    bar.close()
    return per_object


def benchmark(
    objects: list[str],
    out: str | Path | None = None,
    *,
    synthesis: SynthesisOptions | None = None,
    seed: int = 0,
    progress: bool = True,
    preset: str = "defaults",
) -> dict:
    """Fig. runtime: per object, a noise-free acquisition and one synthesis per method with `synthesis` (None: the
    experiment preset's: "paper" the paper's, "defaults" the library's) on the preset's clouds; stage times, their
    medians over objects per method and the ratio KDE / GMM. Writes benchmark.json and benchmark.png into out if
    given."""
    p = Protocol.preset(preset, objects=list(objects), trials=1, seed=seed, synthesis=synthesis)
    n_samples, n_optimise = p.synthesis.sampling.n_samples, p.synthesis.sampling.n_optimise
    p.check_inputs()
    if out is not None:
        check_output_folder(out, "out")
    load_before = os.getloadavg()
    per_object = _time_objects(p, objects, progress)
    medians = {m: {s: float(np.median(v)) for s, v in per_object[m].items()} for m in METHODS}
    ratio = {
        s: medians["kde"][s] / medians["gmm"][s] if medians["gmm"][s] > 0 else math.nan for s in (*STAGES, "total")
    }
    result = {
        "format": BENCHMARK_FORMAT,
        "graspmix": package_version(),
        "commit": git_commit(),
        "objects": list(objects),
        "n_samples": n_samples,
        "n_optimise": n_optimise,
        "preset": preset,
        "annealing_iterations": p.synthesis.annealing.iterations,
        "note": "total = query + sampling + optimisation (the paper's Fig. runtime); segmentation and features "
        "(shared by both methods) are listed apart",
        "median_s": medians,
        "ratio_kde_over_gmm": ratio,
        "per_object_s": per_object,
        "machine": {
            "cpu_count": os.cpu_count(),
            "load_average_before": list(load_before),
            "load_average_after": list(os.getloadavg()),
            "OMP_NUM_THREADS": os.environ.get("OMP_NUM_THREADS"),
            "OMP_WAIT_POLICY": os.environ.get("OMP_WAIT_POLICY"),
        },
    }
    if out is not None:
        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        (out / "benchmark.json").write_text(json.dumps(result, indent=1) + "\n")
        plot_runtime(
            medians,
            out / "benchmark.png",
            title=f"Synthesis time, median over {len(objects)} objects ({n_samples} grasps)",
        )
    return result


def format_benchmark(result: dict) -> str:
    """The benchmark's medians as a text table (ms)."""
    med, ratio = result["median_s"], result["ratio_kde_over_gmm"]
    lines = [
        f"runtime per object (median over {len(result['objects'])} objects, {result['n_samples']} grasps, "
        f"top {result['n_optimise']} optimised), ms:",
        f"{'stage':<28} {'GMM':>9} {'KDE':>9} {'KDE/GMM':>8}",
    ]
    for s in (*STAGES, "total"):
        label = STAGE_LABELS.get(s, "total (the three stages)")
        lines.append(f"{label:<28} {med['gmm'][s] * 1e3:>9.1f} {med['kde'][s] * 1e3:>9.1f} {ratio[s]:>8.2f}")
    for s in _SHARED:
        lines.append(f"{f'({s}, shared)':<28} {med['gmm'][s] * 1e3:>9.1f} {med['kde'][s] * 1e3:>9.1f}")
    return "\n".join(lines)
