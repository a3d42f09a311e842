"""Running (or resuming) the experiment into a run folder.

    from graspmix import experiment
    protocol = experiment.Protocol.preset("smoke")          # or "paper", or Protocol(objects=[...], ...)
    experiment.run(protocol, "runs/smoke", jobs=2)           # attempts.csv, summary.json, report.md/html

Resuming: attempts.csv gets one row per executed grasp as soon as its unit is done (flushed and
synced), so a stopped run loses at most the units in flight. Running again into the same folder
skips every attempt already in the CSV; a folder written by a different protocol is refused.
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

from ..io import PROTOCOL_FORMAT, git_commit, package_version
from ..io.checks import check_output_folder
from .attempt import run_unit
from .executors import EXECUTORS, check_ray, run_pool, run_ray, run_serial
from .log import CSV_NAME, AttemptLog
from .progress import Progress
from .protocol import PROTOCOL_NAME, Protocol, load_protocol
from .report import build_report


@dataclass(frozen=True)
class RunFolder:
    """What kind of run a folder holds: its protocol file's name and format, and the reader of that file
    (which checks it). The experiment's is EXPERIMENT_FOLDER; the clutter protocol has its own."""

    protocol_name: str
    fmt: str
    load: Callable


EXPERIMENT_FOLDER = RunFolder(PROTOCOL_NAME, PROTOCOL_FORMAT, load_protocol)


def protocol_document(protocol, command: str | None = None, fmt: str = PROTOCOL_FORMAT) -> dict:
    """protocol.json's content: the protocol and its provenance (version, commit, time, command)."""
    prov = {
        "graspmix": package_version(),
        "commit": git_commit(),
        "created_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
    }
    if command:
        prov["command"] = command
    return {"format": fmt, "protocol": protocol.to_json(), "provenance": prov}


def prepare_folder(
    protocol, out: str | Path, command: str | None = None, folder: RunFolder = EXPERIMENT_FOLDER
) -> Path:
    """Checks the inputs and the folder; writes protocol.json for a new run. A folder holding another
    protocol's run (or other files) is refused, before any work starts. protocol: a Protocol (or any
    object with validate(), check_inputs() and to_json() whose folder kind is `folder`)."""
    protocol.validate()
    out = check_output_folder(out, "out")
    protocol.check_inputs()
    doc = protocol_document(protocol, command, folder.fmt)
    if out.exists() and not out.is_dir():
        raise ValueError(f"{out}: exists and is not a folder")
    pfile = out / folder.protocol_name
    if pfile.exists():
        old = folder.load(out)["protocol"]
        if old != doc["protocol"]:
            diff = sorted(k for k in set(old) | set(doc["protocol"]) if old.get(k) != doc["protocol"].get(k))
            raise ValueError(
                f"{out}: holds a run of a different protocol (differs in: {', '.join(diff)}); "
                "use another --out folder, or the same options to resume"
            )
    else:
        if out.is_dir() and any(out.iterdir()):
            raise ValueError(f"{out}: is not empty and holds no {folder.protocol_name}; use a new or empty folder")
        out.mkdir(parents=True, exist_ok=True)
        pfile.write_text(json.dumps(doc, indent=1) + "\n")
    return out


def check_run_options(executor: str, jobs) -> None:
    if executor not in EXECUTORS:
        raise ValueError(f"executor must be 'local' or 'ray', got {executor!r}")
    if not isinstance(jobs, int) or jobs < 1:
        raise ValueError(f"jobs must be a positive integer, got {jobs!r}")
    if executor == "ray":
        check_ray()


def _pending_work(protocol: Protocol, done: set, max_units: int | None) -> list:
    """(unit, attempts still to run) in the protocol's order."""
    work = []
    for u in protocol.units():
        todo = [a for a in protocol.attempts(u) if a not in done]
        if todo:
            work.append((u, todo))
    return work if max_units is None else work[:max_units]


def execute_work(
    pdoc: dict,
    work: list,
    log: AttemptLog,
    bar: Progress,
    *,
    jobs: int = 1,
    executor: str = "local",
    ray_address: str | None = None,
    fn: Callable = run_unit,
    count: Callable = len,
) -> int:
    """Runs the work units [(unit, todo), ...] with fn(pdoc, unit, todo) on the executor, appending each
    unit's rows to the log as it finishes and advancing the bar by count(rows); returns the number of rows
    written."""
    ran = 0

    def record(rows):
        nonlocal ran
        log.append(rows)
        ran += len(rows)
        bar.update(count(rows))

    try:
        if not work:
            pass
        elif executor == "ray":
            run_ray(pdoc, work, jobs, record, ray_address, fn)
        elif jobs == 1:
            run_serial(pdoc, work, record, fn)
        else:
            run_pool(pdoc, work, jobs, record, fn)
    finally:
        bar.close()
    return ran


def run(
    protocol: Protocol,
    out: str | Path,
    *,
    jobs: int = 1,
    executor: str = "local",
    progress: bool = True,
    report: bool = True,
    ray_address: str | None = None,
    max_units: int | None = None,
    command: str | None = None,
) -> dict:
    """Runs (or resumes) the experiment into the folder out; returns {"rows", "ran", "skipped", "seconds"}.

    jobs: parallel worker processes (local) or Ray tasks in flight (ray). executor: "local" or "ray"
    (ray_address: a cluster to join; None starts a local Ray instance). max_units: stop after this many
    work units (for tests of resuming). command: recorded in protocol.json when the run starts. report:
    write summary.json, report.md and report.html at the end."""
    check_run_options(executor, jobs)
    out = prepare_folder(protocol, out, command)
    log = AttemptLog(out / CSV_NAME)
    done = log.done()
    pdoc = protocol.to_json()
    pdoc["model_paths"] = {m: str(protocol.model_path(m).resolve()) for m in protocol.methods}
    work = _pending_work(protocol, done, max_units)
    total = len(protocol.all_attempts())
    t0 = time.perf_counter()
    ran = execute_work(
        pdoc,
        work,
        log,
        Progress(total, len(done), enabled=progress),
        jobs=jobs,
        executor=executor,
        ray_address=ray_address,
    )
    result = {
        "rows": len(log.done()),
        "ran": ran,
        "skipped": len(done),
        "seconds": time.perf_counter() - t0,
        "total": total,
    }
    if report and result["rows"] > 0:
        build_report(out)
    return result
