"""Running (or resuming) the clutter-removal protocol into a run folder: clutter.json, clutter_attempts.csv,
summary.json, report.md and a plot. The machinery is the experiment's (graspmix.experiment.runner): the
folder checks, the executors (--jobs workers, Ray), the append-only log and the progress bar.

Resuming: a round's rows reach the CSV (flushed, synced) when it ends; running again into the folder
skips the rounds whose last row is there and reruns the others. A folder of another protocol is refused.
"""

from __future__ import annotations

import time
from pathlib import Path

from ..experiment.log import AttemptLog, read_rows
from ..experiment.progress import Progress
from ..experiment.runner import check_run_options, execute_work, prepare_folder
from .named import NAMED_CSV, NAMED_CSV_NAME, done_named, run_named
from .protocol import CLUTTER_CSV, CLUTTER_CSV_NAME, CLUTTER_FOLDER, ClutterProtocol
from .report import build_clutter_report
from .rounds import run_round


def done_rounds(path) -> set[tuple]:
    """The (mode, scene, method) rounds the log holds whole (a row of theirs names why they ended)."""
    if not Path(path).is_file():
        return set()
    return {(r["mode"], r["scene"], r["method"]) for r in read_rows(path, CLUTTER_CSV) if r["stop"]}


def run_clutter(
    protocol: ClutterProtocol,
    out,
    *,
    jobs: int = 1,
    executor: str = "local",
    progress: bool = True,
    report: bool = True,
    ray_address: str | None = None,
    max_rounds: int | None = None,
    command: str | None = None,
    round_fn=None,
) -> dict:
    """Runs (or resumes) the protocol into the folder out; returns {"rounds": rounds done, "ran": attempts
    written now, "skipped": rounds done before, "total": rounds of the protocol, "seconds"}. jobs, executor, ray_address: as graspmix.experiment.run. max_rounds: stop after this many
    rounds (tests of resuming). round_fn(pdoc, unit, todo) -> rows: the round (a module-level function,
    for workers to import; tests give one with fake stages; None: run_round, or run_named for the named
    task, whose units are (mode, scene, method, pick) and whose log is named_attempts.csv)."""
    check_run_options(executor, jobs)
    out = prepare_folder(protocol, out, command, CLUTTER_FOLDER)
    named = protocol.task == "named"
    done_fn = done_named if named else done_rounds
    round_fn = round_fn or (run_named if named else run_round)
    log = AttemptLog(out / (NAMED_CSV_NAME if named else CLUTTER_CSV_NAME), NAMED_CSV if named else CLUTTER_CSV)
    done = done_fn(log.path)
    rounds = protocol.rounds()
    work = [(u, None) for u in rounds if u not in done]
    work = work if max_rounds is None else work[:max_rounds]
    pdoc = protocol.to_json()
    pdoc["model_paths"] = {m: str(protocol.model_path(m).resolve()) for m in protocol.model_methods()}
    bar = Progress(len(rounds), len(done), enabled=progress, unit="rounds")
    t0 = time.perf_counter()
    ran = execute_work(
        pdoc, work, log, bar, jobs=jobs, executor=executor, ray_address=ray_address, fn=round_fn, count=_one
    )
    result = {
        "rounds": len(done_fn(log.path)),
        "ran": ran,
        "skipped": len(done),
        "total": len(rounds),
        "seconds": time.perf_counter() - t0,
    }
    if report and result["rounds"] > 0:
        build_clutter_report(out)
    return result


def _one(rows) -> int:
    return 1
