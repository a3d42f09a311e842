"""Comparisons across experiment runs that share objects, trials and seeds: one setting varied at a time.

A cell is (run folder, condition, method). Two cells compare by the paper's test (a two-tailed paired t-test
over the trials of the per-trial success rates, scipy.stats.ttest_rel) and, since the objects are the larger
sample, by a paired t-test over the objects of their success rates averaged over the trials. Runs of one
protocol but for one setting (`graspmix_cli experiment --pixel-noise 0`, a model learnt with other settings)
share the acquisition and synthesis seeds, so the pairs differ in that setting alone.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from .log import CSV_NAME, read_rows
from .stats import mcnemar_exact, paired_ttest


@dataclass(frozen=True)
class Cell:
    """The successes of one condition and method in a run: (trials, objects) 0/1, the outcome counts, and
    each attempt's outcome (trials, objects) as text."""

    success: np.ndarray
    objects: tuple
    reasons: dict
    outcomes: np.ndarray

    @property
    def rate(self) -> float:
        return float(self.success.mean())


def load_rows(run_dir: str | Path) -> list[dict]:
    return read_rows(Path(run_dir) / CSV_NAME)


def cell(rows: list[dict], condition: str, method: str) -> Cell:
    """The (trials, objects) success matrix of a condition and method; ValueError if an attempt is missing
    (a comparison of incomplete runs would pair unlike things)."""
    sel = [r for r in rows if r["condition"] == condition and r["method"] == method]
    if not sel:
        raise ValueError(f"no attempts of condition {condition} and method {method}")
    objects = tuple(sorted({r["object"] for r in sel}))
    trials = sorted({r["trial"] for r in sel})
    m = np.full((len(trials), len(objects)), -1, dtype=int)
    outcomes = np.full(m.shape, "", dtype=object)
    oi, ti = {o: i for i, o in enumerate(objects)}, {t: i for i, t in enumerate(trials)}
    for r in sel:
        m[ti[r["trial"]], oi[r["object"]]] = int(r["success"])
        outcomes[ti[r["trial"]], oi[r["object"]]] = r["reason"]
    if np.any(m < 0):
        raise ValueError(f"condition {condition}, method {method}: {int(np.sum(m < 0))} attempts missing")
    return Cell(m, objects, dict(Counter(r["reason"] for r in sel)), outcomes)


@dataclass(frozen=True)
class Difference:
    """a - b in success rate (fraction): the paper's test over trials and the test over objects."""

    difference: float
    trials: dict  # PairedTTest over the trials' rates
    objects: dict  # PairedTTest over the objects' rates (mean over trials)

    def to_dict(self) -> dict:
        return asdict(self)


def difference(a: Cell, b: Cell) -> Difference:
    """a - b, paired by trial and by object; the cells must cover the same objects and trials."""
    if a.objects != b.objects or a.success.shape != b.success.shape:
        raise ValueError("the two cells cover different objects or trials: not paired")
    by_trial = paired_ttest(a.success.mean(axis=1), b.success.mean(axis=1)).to_dict()
    by_object = paired_ttest(a.success.mean(axis=0), b.success.mean(axis=0)).to_dict()
    return Difference(a.rate - b.rate, by_trial, by_object)


def outcome_shares(c: Cell) -> dict:
    """reason -> share of the cell's attempts."""
    n = c.success.size
    return {k: v / n for k, v in sorted(c.reasons.items(), key=lambda kv: -kv[1])}


@dataclass(frozen=True)
class OutcomeChange:
    """How often an outcome happens in a and in b over the same attempts, and the exact McNemar test of the
    discordant pairs (two-sided binomial test of only_a against only_a + only_b at 1/2)."""

    outcome: str
    share_a: float
    share_b: float
    only_a: int
    only_b: int
    p: float


def outcome_change(a: Cell, b: Cell, outcome: str) -> OutcomeChange:
    """Paired by (trial, object): the attempts ending in `outcome` in a but not in b, and the reverse."""
    if a.objects != b.objects or a.outcomes.shape != b.outcomes.shape:
        raise ValueError("the two cells cover different objects or trials: not paired")
    ia, ib = a.outcomes == outcome, b.outcomes == outcome
    only_a, only_b = int(np.sum(ia & ~ib)), int(np.sum(ib & ~ia))
    return OutcomeChange(outcome, float(ia.mean()), float(ib.mean()), only_a, only_b, mcnemar_exact(only_a, only_b))
