"""What the benchmarks share: the median time of a call, and the lines that say what the machine was doing."""

from __future__ import annotations

import os
import statistics
import time


def median_seconds(fn, repeats: int) -> float:
    """The median wall time (s) of `repeats` calls of fn, after one warm-up call."""
    fn()
    runs = []
    for _ in range(repeats):
        t = time.perf_counter()
        fn()
        runs.append(time.perf_counter() - t)
    return statistics.median(runs)


def load_average() -> str:
    return ", ".join(f"{v:.2f}" for v in os.getloadavg())


def machine_line(version: str) -> str:
    """graspmix's version, the OpenMP settings, the CPUs and the load: the first line a benchmark prints."""
    return (
        f"graspmix {version}, OMP_NUM_THREADS={os.environ.get('OMP_NUM_THREADS', 'unset')}, "
        f"OMP_WAIT_POLICY={os.environ.get('OMP_WAIT_POLICY', 'unset')}, {os.cpu_count()} CPUs, "
        f"load average {load_average()}"
    )
