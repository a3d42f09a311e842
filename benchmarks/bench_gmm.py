"""GaussianMixture.fit and score_samples against scikit-learn on the same data.

    python3 benchmarks/bench_gmm.py [--repeats 5]

Both fit full covariances with the same K, tol and max_iter from the same initial means (one
k-means++ draw by scikit-learn's kmeans_plusplus), so both run the same EM to the same optimum and
the times compare the implementations, not the luck of two initialisations. Prints the median wall time of each, the ratio
(scikit-learn / graspmix: above 1 means graspmix is faster), iterations, and both mean log-likelihoods.
"""

import argparse
import statistics
import time

import graspmix
import numpy as np
from sklearn.cluster import kmeans_plusplus
from sklearn.mixture import GaussianMixture as SkGaussianMixture


def data(n, d, k, seed):
    rng = np.random.default_rng(seed)
    centres = rng.normal(scale=3.0, size=(k, d))
    labels = rng.integers(k, size=n)
    return centres[labels] + rng.normal(size=(n, d)) @ (0.3 * rng.normal(size=(d, d)) + np.eye(d))


def median_time(fn, repeats):
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=5)
    args = ap.parse_args()
    print(
        f"{'N':>7} {'d':>2} {'K':>2} | {'fit graspmix':>12} {'fit sklearn':>11} {'ratio':>6} {'iters':>7} | "
        f"{'score graspmix':>14} {'score sklearn':>13} {'ratio':>6} | {'loglik graspmix':>15} {'loglik sklearn':>14}"
    )
    for n in (2000, 20000):
        for k in (2, 5):
            d = 8
            X = data(n, d, k, seed=n + k)
            kw = dict(n_components=k, tol=1e-3, max_iter=100, reg_covar=1e-6)
            init, _ = kmeans_plusplus(X, k, random_state=0)
            ours = graspmix.GaussianMixture(**kw, seed=0)
            ref = SkGaussianMixture(**kw, covariance_type="full", means_init=init, random_state=0)
            t_fit_ours = median_time(lambda ours=ours, X=X, init=init: ours.fit(X, means_init=init), args.repeats)
            t_fit_ref = median_time(lambda ref=ref, X=X: ref.fit(X), args.repeats)
            t_score_ours = median_time(lambda ours=ours, X=X: ours.score_samples(X), args.repeats * 4)
            t_score_ref = median_time(lambda ref=ref, X=X: ref.score_samples(X), args.repeats * 4)
            print(
                f"{n:>7} {d:>2} {k:>2} | {t_fit_ours * 1e3:>10.2f}ms {t_fit_ref * 1e3:>9.2f}ms "
                f"{t_fit_ref / t_fit_ours:>6.2f} {ours.n_iter_:>3}/{ref.n_iter_:<3} | "
                f"{t_score_ours * 1e3:>12.3f}ms {t_score_ref * 1e3:>11.3f}ms {t_score_ref / t_score_ours:>6.2f} | "
                f"{ours.score(X):>15.5f} {ref.score(X):>14.5f}"
            )


if __name__ == "__main__":
    main()
