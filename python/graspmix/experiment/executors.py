"""How work units run: in this process, in a pool of local worker processes, or as Ray tasks. Each
calls record(rows) in this process as units finish (in any order: rows do not depend on it).

A unit is run by fn(pdoc, unit, todo) -> rows, a module-level function (workers import it by name):
the experiment's run_unit by default, the clutter protocol's run_round for its rounds."""

from __future__ import annotations

import os
from typing import Callable

from .attempt import run_unit

EXECUTORS = ("local", "ray")


def run_serial(pdoc: dict, work: list, record: Callable, fn: Callable = run_unit) -> None:
    for u, todo in work:
        record(fn(pdoc, u, todo))


def _unit_job(args):
    fn, *rest = args
    return fn(*rest)


def run_pool(pdoc: dict, work: list, jobs: int, record: Callable, fn: Callable = run_unit) -> None:
    import multiprocessing as mp

    # Fresh interpreters (spawn) with one OpenMP thread each: jobs workers share the cores.
    old = os.environ.get("OMP_NUM_THREADS")
    os.environ["OMP_NUM_THREADS"] = "1"
    try:
        pool = mp.get_context("spawn").Pool(jobs)
    finally:
        if old is None:
            os.environ.pop("OMP_NUM_THREADS", None)
        else:
            os.environ["OMP_NUM_THREADS"] = old
    try:
        for rows in pool.imap_unordered(_unit_job, [(fn, pdoc, u, todo) for u, todo in work], chunksize=1):
            record(rows)
    except BaseException:
        # Stopped (Ctrl-C) or failed: the workers' unfinished units are lost anyway, so end them now.
        pool.terminate()
        pool.join()
        raise
    pool.close()
    pool.join()


def check_ray() -> None:
    try:
        import ray  # noqa: F401
    except ImportError:
        raise ValueError("--executor ray needs the ray package (pip install ray)") from None


def run_ray(pdoc: dict, work: list, jobs: int, record: Callable, address: str | None, fn: Callable = run_unit) -> None:
    import ray

    started = False
    if not ray.is_initialized():
        if address:
            ray.init(address=address, log_to_driver=False)
        else:
            ray.init(
                num_cpus=jobs,
                include_dashboard=False,
                log_to_driver=False,
                runtime_env={"env_vars": {"OMP_NUM_THREADS": "1"}},
            )
        started = True
    try:
        task = ray.remote(num_cpus=1)(fn)
        pending = []
        queue = list(work)
        # Keep a bounded number of units in flight so rows reach the CSV as they finish.
        in_flight = max(2 * jobs, 2)
        while queue or pending:
            while queue and len(pending) < in_flight:
                u, todo = queue.pop(0)
                pending.append(task.remote(pdoc, u, todo))
            ready, pending = ray.wait(pending, num_returns=1)
            for r in ready:
                record(ray.get(r))
    finally:
        if started:
            ray.shutdown()
