"""Statistics of the experiments: success rates over trials and the paired t-test GMM vs KDE (the paper's
experiment); binomial rates with Wilson intervals, widened for clustered trials (the clutter protocol).

The unit of replication is the trial (the paper repeats the whole object set 10 times): a trial's
success rate is the fraction of objects whose best grasp held. Confidence intervals of a mean over
trials use Student's t distribution with n - 1 degrees of freedom; the paired test is scipy's
``ttest_rel`` (two-tailed), and its interval is that of the mean of the per-trial differences.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np


@dataclass
class MeanCI:
    """Mean of n values with its (1 - alpha) confidence interval from the t distribution."""

    mean: float
    low: float
    high: float
    std: float  # sample standard deviation (ddof = 1); nan for n < 2
    n: int
    confidence: float

    def to_dict(self) -> dict:
        return asdict(self)


@dataclass
class PairedTTest:
    """Two-tailed paired t-test of a against b (differences a - b)."""

    mean_difference: float
    ci_low: float
    ci_high: float
    t: float
    p: float
    df: int
    n: int
    confidence: float

    def to_dict(self) -> dict:
        return asdict(self)


def _values(x, what: str) -> np.ndarray:
    v = np.asarray(x, dtype=float)
    if v.ndim != 1 or len(v) == 0:
        raise ValueError(f"{what}: expected a non-empty 1-D sequence of numbers, got shape {v.shape}")
    if not np.all(np.isfinite(v)):
        raise ValueError(f"{what}: values must be finite")
    return v


def _check_confidence(confidence: float) -> None:
    if not 0.0 < confidence < 1.0:
        raise ValueError(f"confidence must be in (0, 1), got {confidence}")


def mean_ci(x, confidence: float = 0.95) -> MeanCI:
    """The mean of x and its t-distribution confidence interval (nan bounds for a single value)."""
    from scipy import stats

    _check_confidence(confidence)
    v = _values(x, "x")
    n = len(v)
    m = float(v.mean())
    if n < 2:
        return MeanCI(m, math.nan, math.nan, math.nan, n, confidence)
    sd = float(v.std(ddof=1))
    half = float(stats.t.ppf(0.5 + confidence / 2.0, n - 1)) * sd / math.sqrt(n)
    return MeanCI(m, m - half, m + half, sd, n, confidence)


def paired_ttest(a, b, confidence: float = 0.95) -> PairedTTest:
    """Two-tailed paired t-test of a vs b (scipy.stats.ttest_rel) with the mean difference a - b and its
    confidence interval. Identical samples give t = nan, p = nan (scipy's answer: no variance to test)."""
    from scipy import stats

    _check_confidence(confidence)
    a = _values(a, "a")
    b = _values(b, "b")
    if a.shape != b.shape:
        raise ValueError(f"paired samples must have the same length, got {len(a)} and {len(b)}")
    if len(a) < 2:
        raise ValueError("a paired t-test needs at least 2 pairs")
    d = a - b
    ci = mean_ci(d, confidence)
    if np.ptp(d) <= 1e-12 * max(1.0, float(np.max(np.abs(d)))):
        # No spread of the differences (up to rounding: rates are fractions k / n computed in floating
        # point): scipy would return nan, or a huge t from the rounding noise; say so plainly.
        t, p = (math.nan, math.nan) if abs(d[0]) <= 1e-12 else (math.copysign(math.inf, d[0]), 0.0)
    else:
        res = stats.ttest_rel(a, b)
        t, p = float(res.statistic), float(res.pvalue)
    return PairedTTest(ci.mean, ci.low, ci.high, t, p, len(a) - 1, len(a), confidence)


@dataclass
class RateCI:
    """A rate = successes / trials over clusters of trials (scenes), with its Wilson interval computed on
    the effective number of trials (trials / design_effect, design_effect >= 1)."""

    rate: float
    low: float
    high: float
    successes: int
    trials: int
    clusters: int
    design_effect: float
    confidence: float

    def to_dict(self) -> dict:
        return asdict(self)


def mcnemar_exact(only_a: int, only_b: int) -> float:
    """McNemar's exact test of paired binary outcomes: the two-sided binomial test of the discordant pairs, only_a
    against only_a + only_b at 1/2 (1 when there are none)."""
    from scipy.stats import binomtest

    return 1.0 if only_a + only_b == 0 else float(binomtest(only_a, only_a + only_b, 0.5).pvalue)


def wilson_ci(successes: float, n: float, confidence: float = 0.95) -> tuple[float, float]:
    """Wilson's score interval of a binomial proportion successes / n (n may be an effective, non-integer
    count). It stays inside [0, 1] and is not degenerate at 0 or n successes, unlike the Wald interval."""
    from scipy import stats

    _check_confidence(confidence)
    if not (math.isfinite(n) and n > 0) or not 0 <= successes <= n:
        raise ValueError(f"wilson_ci: need 0 <= successes <= n and n > 0, got {successes} of {n}")
    z = float(stats.norm.ppf(0.5 + confidence / 2.0))
    p, z2 = successes / n, z * z
    centre = (p + z2 / (2 * n)) / (1 + z2 / n)
    half = z / (1 + z2 / n) * math.sqrt(p * (1 - p) / n + z2 / (4 * n * n))
    # It holds p; rounding must not put an end on the wrong side of it (at p = 1, centre + half came to
    # 0.9999999999999999, a negative error bar for the clutter report's plot).
    return max(0.0, min(p, centre - half)), min(1.0, max(p, centre + half))


def clustered_rate(successes, trials, confidence: float = 0.95) -> RateCI:
    """The pooled rate sum(successes) / sum(trials) over clusters (one entry per scene) with a Wilson
    interval that accounts for trials within a cluster not being independent (attempts and objects of one
    scene share its clutter, and a scene's failures end it): the design effect is the ratio of the
    between-cluster (linearised ratio-estimator) variance to the binomial variance, never below 1, and the
    Wilson interval uses trials / design_effect trials (Kish's effective sample size)."""
    y = np.asarray(successes, dtype=float)
    m = np.asarray(trials, dtype=float)
    if y.ndim != 1 or y.shape != m.shape or len(y) == 0:
        raise ValueError("clustered_rate: successes and trials must be non-empty 1-D sequences of equal length")
    if not (np.all(np.isfinite(m)) and np.all(m >= 0) and np.all((y >= 0) & (y <= m))) or m.sum() <= 0:
        raise ValueError("clustered_rate: need 0 <= successes <= trials in every cluster and some trials")
    n, k = float(m.sum()), len(m)
    p = float(y.sum()) / n
    deff = 1.0
    binomial_var = p * (1 - p) / n
    if k >= 2 and binomial_var > 0:
        cluster_var = k / (k - 1) * float(np.sum((y - p * m) ** 2)) / (n * n)
        deff = max(1.0, cluster_var / binomial_var)
    low, high = wilson_ci(p * n / deff, n / deff, confidence)
    return RateCI(p, low, high, int(round(y.sum())), int(round(n)), k, deff, confidence)
