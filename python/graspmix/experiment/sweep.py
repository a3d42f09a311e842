"""How sensitive each method's success is to its own settings: one experiment per setting value, varied one at
a time around the defaults, on a development list of objects (never the objects a result is reported on).

    sweep = Sweep(Protocol(objects=dev, trials=3, conditions=["A", "B"]),
                  {"n_components": [1, 2, 3], "kde_position_bandwidth": [0.0025, 0.005, 0.01]})
    result = run_sweep(sweep, "runs/sweep", jobs=2)     # sweep.json, sweep.png; one experiment folder a value

A learning setting (K of GMM's contact mixtures, KDE's kernel bandwidths) gets a model learnt from the
protocol's demonstration with that value (the bundled box demonstration unless the protocol names models); a
synthesis or acquisition setting (K_Q, N_Q, the noise model...) is a field of the protocol. Each parameter
runs only for the methods it belongs to; the defaults run once, for every method. All variants share the
protocol's seeds, so their differences are paired (the same clouds and synthesis seeds).
"""

from __future__ import annotations

import dataclasses
import json
from dataclasses import dataclass
from operator import attrgetter
from pathlib import Path

import numpy as np

from ..io import data_path
from ..io.checks import quote
from ..model.options import SynthesisOptions
from ..model.settings import METHOD_LABELS, METHODS, LearnSettings
from .protocol import CONDITIONS, Protocol
from .stats import clustered_rate

SWEEP_NAME = "sweep.json"
DEFAULTS = "defaults"
DEMONSTRATION = ("demos", "box_wsg50.json")  # the bundled models' demonstration (scripts/make_example_data.py)

# What each sweepable setting belongs to: (methods it changes, "learn", "protocol" or the SynthesisOptions
# field it names, e.g. "synthesis:query.n_components").
PARAMETERS = {
    "n_components": (("gmm",), "learn"),
    "gmm_reg_covar": (("gmm",), "learn"),
    "kde_position_bandwidth": (("kde",), "learn"),
    "kde_orientation_bandwidth": (("kde",), "learn"),
    "kde_feature_bandwidth": (("kde",), "learn"),
    "query_components": (("gmm",), "synthesis:query.n_components"),
    "query_samples": (METHODS, "synthesis:query.n_samples"),
    "n_samples": (METHODS, "synthesis:sampling.n_samples"),
    "pixel_noise_std": (METHODS, "protocol"),
    "depth_noise_std": (METHODS, "protocol"),
}


def _option_path(name: str) -> str | None:
    """The SynthesisOptions field a synthesis parameter names, else None."""
    kind = PARAMETERS[name][1]
    return kind.partition(":")[2] if kind.startswith("synthesis:") else None


def _protocol_value(p, name: str):
    """The parameter's value in a Protocol (or, with the class, its default)."""
    path = _option_path(name)
    if path is None:
        return getattr(p, name)
    return attrgetter(path)(p.synthesis if isinstance(p, Protocol) else SynthesisOptions())


def parameter_type(name: str) -> type:
    """int or float: the type of the setting's default (counts are ints)."""
    owner = LearnSettings if PARAMETERS[name][1] == "learn" else Protocol
    default = getattr(owner, name) if owner is LearnSettings else _protocol_value(Protocol, name)
    return int if isinstance(default, int) else float


@dataclass
class Sweep:
    base: Protocol  # the objects (a development list), trials, conditions and methods; its values are the defaults
    parameters: dict  # name -> values, each varied alone with every other setting at its default

    def __post_init__(self):
        if not isinstance(self.parameters, dict) or not self.parameters:
            raise ValueError("a sweep needs at least one parameter with values")
        for name, values in self.parameters.items():
            if name not in PARAMETERS:
                raise ValueError(f"unknown sweep parameter {quote(name)} (known: {', '.join(PARAMETERS)})")
            if not isinstance(values, (list, tuple)) or not values:
                raise ValueError(f"sweep parameter {name}: no values")
            if not set(PARAMETERS[name][0]) & set(self.base.methods):
                raise ValueError(f"sweep parameter {name} belongs to {','.join(PARAMETERS[name][0])}, not run here")
            if PARAMETERS[name][1] == "learn" and self.base.models:
                raise ValueError(f"sweep parameter {name} learns from the bundled demonstration: give no models")
            for v in values:
                self.variant_protocol(name, v, Path("."), check_only=True)  # bad values fail before any work

    def default_value(self, name: str):
        methods, kind = PARAMETERS[name]
        return getattr(LearnSettings, name) if kind == "learn" else _protocol_value(self.base, name)

    def variants(self) -> list[tuple[str, object]]:
        """(parameter, value) pairs to run, the defaults first as (DEFAULTS, None); a value equal to the
        default is the defaults' run."""
        out = [(DEFAULTS, None)]
        for name, values in self.parameters.items():
            out += [(name, v) for v in values if v != self.default_value(name)]
        return out

    def variant_protocol(self, name: str, value, models_dir: Path, check_only: bool = False) -> Protocol:
        """The protocol of one variant: its methods, and its protocol field or its learnt model."""
        if name == DEFAULTS:
            return self.base
        methods, kind = PARAMETERS[name]
        run_methods = [m for m in self.base.methods if m in methods]
        if kind == "protocol":
            return dataclasses.replace(self.base, methods=run_methods, **{name: value})
        if _option_path(name) is not None:
            synthesis = self.base.synthesis.updated({_option_path(name): value})
            return dataclasses.replace(self.base, methods=run_methods, synthesis=synthesis)
        from ..model.grasp_model import GraspModel, check_learn_numbers

        check_learn_numbers(**{name: value})
        if check_only:
            return self.base

        models = dict(self.base.models)
        for m in run_methods:
            path = models_dir / f"{m}_{name}={value}.json"
            if not path.is_file():
                GraspModel.learn(str(data_path(*DEMONSTRATION)), m, **{name: value}).save(path)
            models[m] = str(path.resolve())
        return dataclasses.replace(self.base, methods=run_methods, models=models)


def variant_folder(name: str, value) -> str:
    return DEFAULTS if name == DEFAULTS else f"{name}={value}"


def run_sweep(sweep: Sweep, out: str | Path, **run_options) -> dict:
    """Runs (or resumes) every variant's experiment into out/<parameter>=<value>/ and writes out/sweep.json
    and out/sweep.png; returns the sweep.json content. run_options: experiment.run's keywords."""
    from .runner import run

    out = Path(out)
    (out / "models").mkdir(parents=True, exist_ok=True)
    variants = sweep.variants()
    for i, (name, value) in enumerate(variants):
        if run_options.get("progress", True):
            print(f"sweep {i + 1}/{len(variants)}: {variant_folder(name, value)}", flush=True)
        run(sweep.variant_protocol(name, value, out / "models"), out / variant_folder(name, value), **run_options)
    result = summarize_sweep(sweep, out)
    (out / SWEEP_NAME).write_text(json.dumps(result, indent=1) + "\n")
    from ..viz.sweep import plot_sweep

    plot_sweep(result, out / "sweep.png")
    return result


def _rates(run_dir: Path, conditions, methods) -> dict:
    """condition -> method -> {rate, ci_low, ci_high, successes, attempts} from an experiment's CSV: the
    objects are the clusters of the interval (an object's trials are not independent)."""
    from .compare import cell, load_rows

    rows = load_rows(run_dir)
    out = {}
    for c in conditions:
        for m in methods:
            if any(r["condition"] == c and r["method"] == m for r in rows):
                success = cell(rows, c, m).success
                ci = clustered_rate(success.sum(axis=0), np.full(success.shape[1], success.shape[0]))
                out.setdefault(c, {})[m] = dict(
                    rate=ci.rate, ci_low=ci.low, ci_high=ci.high, successes=ci.successes, attempts=ci.trials
                )
    return out


def _best(points: list, default):
    """The value of the highest mean success (rounded to 1e-9, so float noise does not decide); ties: the
    default, then the first."""
    return max(points, key=lambda p: (round(p["mean"], 9), p["value"] == default))["value"]


def summarize_sweep(sweep: Sweep, out: Path) -> dict:
    """Per parameter and method: each value's success per condition (with the defaults' run at the default
    value), and the value with the highest mean success over the conditions (ties: the default); for a
    setting both methods share (N_Q, the noise), also the best of the two methods' mean ("best_shared")."""
    conds, base = sweep.base.conditions, sweep.base.methods
    default_rates = _rates(out / DEFAULTS, conds, base)
    params = {}
    for name, values in sweep.parameters.items():
        methods = [m for m in base if m in PARAMETERS[name][0]]
        default = sweep.default_value(name)
        entry = {"default": default, "methods": {}}
        for m in methods:
            points = []
            for v in sorted(set(values) | {default}):
                folder = out / variant_folder(DEFAULTS if v == default else name, v)
                rates = default_rates if v == default else _rates(folder, conds, [m])
                per_cond = {c: rates[c][m] for c in conds if c in rates and m in rates[c]}
                mean = sum(e["rate"] for e in per_cond.values()) / max(len(per_cond), 1)
                points.append({"value": v, "mean": mean, "conditions": per_cond})
            entry["methods"][m] = {"points": points, "best": _best(points, default)}
        if len(methods) > 1:  # a setting both methods share: the best of their mean
            per_value = [p["value"] for p in entry["methods"][methods[0]]["points"]]
            means = [
                {"value": v, "mean": sum(entry["methods"][m]["points"][i]["mean"] for m in methods) / len(methods)}
                for i, v in enumerate(per_value)
            ]
            entry["best_shared"] = _best(means, default)
        params[name] = entry
    return {
        "objects": list(sweep.base.objects),
        "trials": sweep.base.trials,
        "conditions": {c: CONDITIONS[c].description for c in conds},
        "methods": {m: METHOD_LABELS[m] for m in base},
        "parameters": params,
    }
