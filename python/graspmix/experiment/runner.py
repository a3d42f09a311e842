"""The paper's experiment: conditions A-D, GMM vs KDE, on the 60 test objects over repeated trials.

    from graspmix import experiment
    protocol = experiment.Protocol.preset("smoke")          # or "paper", or Protocol(objects=[...], ...)
    experiment.run(protocol, "runs/smoke", jobs=2)           # attempts.csv, summary.json, report.md/html

For every object, trial and condition, the object's cloud is acquired from 4 simulated depth cameras
(with the noise model where the condition says so), each method synthesises n_samples grasps, ranks
them, optimises the best n_optimise by annealing where the condition says so, and the best grasp is
executed in Bullet with the object at its rest pose.

Determinism: every attempt is a pure function of its key. The acquisition seed comes from
(seed, object, trial), so all conditions sharing a noise setting and both methods see the same
cloud; the synthesis seed comes from (seed, object, trial, condition), shared by both methods (common
random numbers). Seeds are taken from a BLAKE2 hash, never from Python's salted hash(). The work unit
is one (object, trial, noise) acquisition and the attempts that share it; results do not depend on
the executor, the number of jobs or the order in which units finish.

Resuming: attempts.csv gets one row per executed grasp as soon as its unit is done (flushed and
synced), so a stopped run loses at most the units in flight. Running again into the same folder
skips every attempt already in the CSV; a folder written by a different protocol is refused.
"""
from __future__ import annotations

import csv
import dataclasses
import hashlib
import io
import json
import math
import os
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Iterable

import numpy as np

PROTOCOL_FORMAT = "graspmix.experiment/1"
CSV_NAME = "attempts.csv"
PROTOCOL_NAME = "protocol.json"


@dataclass(frozen=True)
class Condition:
    name: str
    noise: bool
    optimise: bool
    description: str


CONDITIONS = {
    "A": Condition("A", False, True, "no depth noise, with optimisation"),
    "B": Condition("B", True, True, "depth noise, with optimisation"),
    "C": Condition("C", False, False, "no depth noise, no optimisation"),
    "D": Condition("D", True, False, "depth noise, no optimisation"),
}
METHODS = ("gmm", "kde")
# How an executed grasp closes. "full": the fingers close, force-limited, until they stop on the object or
# reach their closed limit, as a parallel gripper's grasp command does (the simulation's motor target is
# pushed past the grasp joints far enough to be clamped to the closed limit). "learnt": the simulation's
# default, a target 0.5 x (grasp - pregrasp) past the synthesised grasp joints; with a configuration
# model learnt from one 6 cm box, the fingers then stop about 4.4 cm apart and cannot hold anything
# narrower, whatever the method.
CLOSING = {"full": {"close_overshoot": 1000.0}, "learnt": {}}
PRESETS = ("smoke", "paper")
# The smoke preset's objects: three of the test set with different shapes (a mug, a small block-like
# part, an elongated part), so the smoke run exercises more than one kind of grasp.
SMOKE_OBJECTS = 3

# Columns of attempts.csv. Times are in seconds.
KEY_COLUMNS = ["object", "trial", "condition", "method"]
RESULT_COLUMNS = ["noise", "optimise", "acquisition_seed", "synthesis_seed", "n_points", "success", "reason",
                  "lift_height", "contact_count", "log_likelihood", "grasp", "evaluations", "rejected", "error"]
TIME_COLUMNS = ["t_acquisition", "t_features", "t_query", "t_sampling", "t_optimisation", "t_synthesis",
                "t_execution"]
COLUMNS = KEY_COLUMNS + RESULT_COLUMNS + TIME_COLUMNS


def derive_seed(*parts) -> int:
    """A 31-bit seed from the parts' text (BLAKE2b): the same in every process and on every machine."""
    text = "\x1f".join(str(p) for p in parts).encode()
    return int.from_bytes(hashlib.blake2b(text, digest_size=8).digest(), "little") & 0x7FFFFFFF


def _sha256(path: Path) -> str:
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()


def git_commit(cwd: str | Path | None = None) -> str | None:
    """The commit of the source tree the run is started from (with "+dirty" if it has changes), if any."""
    try:
        head = subprocess.run(["git", "rev-parse", "HEAD"], cwd=cwd, capture_output=True, text=True, timeout=10)
        if head.returncode != 0:
            return None
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=cwd,
                               capture_output=True, text=True, timeout=10)
        return head.stdout.strip() + ("+dirty" if dirty.stdout.strip() else "")
    except (OSError, subprocess.SubprocessError):
        return None


# ---- the protocol ------------------------------------------------------------------------------

@dataclass
class Protocol:
    """Everything that decides an experiment's results. Two runs with equal protocols give equal rows."""

    objects: list[str]
    trials: int = 10
    conditions: list[str] = field(default_factory=lambda: list(CONDITIONS))
    methods: list[str] = field(default_factory=lambda: list(METHODS))
    n_samples: int = 200  # grasps sampled and ranked per attempt
    n_optimise: int = 10  # the best this many are annealed (conditions with optimisation)
    annealing_iterations: int = 100  # the paper's 100
    initial_temperature: float = 1.0  # the paper's 1.0, linear decay
    query_samples: int = 500  # N_Q samples per link for the query densities
    min_height: float = 0.004  # m: clean-up drops points closer than this to the known support plane z = 0
    closing: str = "full"  # how the executed grasp closes: see CLOSING
    seed: int = 0  # base of every derived seed
    models: dict = field(default_factory=dict)  # method -> model file; empty: the bundled box models

    def __post_init__(self):
        self.validate()

    @classmethod
    def preset(cls, name: str, **overrides) -> "Protocol":
        """"paper": the 60 test objects, 10 trials, A-D, GMM and KDE. "smoke": the same with 3 objects and
        2 trials (minutes, for tests and a first look)."""
        from .sim import test_objects

        if name not in PRESETS:
            raise ValueError(f"preset must be one of {', '.join(PRESETS)}, got {name!r}")
        objects = test_objects()
        if name == "smoke":
            kw = dict(objects=objects[:SMOKE_OBJECTS], trials=2)
        else:
            kw = dict(objects=objects, trials=10)
        kw.update({k: v for k, v in overrides.items() if v is not None})
        return cls(**kw)

    def validate(self) -> None:
        if not self.objects:
            raise ValueError("the protocol has no objects")
        if len(set(self.objects)) != len(self.objects):
            dup = sorted({o for o in self.objects if self.objects.count(o) > 1})
            raise ValueError(f"objects are listed twice: {', '.join(dup)}")
        if not isinstance(self.trials, int) or self.trials < 1:
            raise ValueError(f"trials must be a positive integer, got {self.trials!r}")
        if not self.conditions:
            raise ValueError("no conditions given")
        for c in self.conditions:
            if c not in CONDITIONS:
                raise ValueError(f"unknown condition {c!r} (known: {', '.join(CONDITIONS)})")
        if len(set(self.conditions)) != len(self.conditions):
            raise ValueError(f"a condition is listed twice: {','.join(self.conditions)}")
        if not self.methods:
            raise ValueError("no methods given")
        for m in self.methods:
            if m not in METHODS:
                raise ValueError(f"unknown method {m!r} (known: {', '.join(METHODS)})")
        if len(set(self.methods)) != len(self.methods):
            raise ValueError(f"a method is listed twice: {','.join(self.methods)}")
        for name in ("n_samples", "n_optimise", "annealing_iterations", "query_samples"):
            if int(getattr(self, name)) < 1:
                raise ValueError(f"{name} must be at least 1, got {getattr(self, name)}")
        if self.closing not in CLOSING:
            raise ValueError(f"closing must be one of {', '.join(CLOSING)}, got {self.closing!r}")
        for m in self.models:
            if m not in METHODS:
                raise ValueError(f"models: unknown method {m!r}")

    def check_inputs(self) -> None:
        """Every object and model file exists and loads: raises ValueError before any work starts."""
        from .acquisition import resolve_object

        missing = []
        for o in self.objects:
            try:
                resolve_object(o)
            except ValueError:
                missing.append(o)
        if missing:
            raise ValueError(f"{len(missing)} object(s) not found (neither a file nor in pybullet_data): "
                             + ", ".join(missing[:5]) + (" ..." if len(missing) > 5 else ""))
        for m in self.methods:
            path = self.model_path(m)
            if not path.is_file():
                raise ValueError(f"{path}: no such {m} model file")

    def model_path(self, method: str) -> Path:
        from .model import default_model_path

        return Path(self.models[method]) if method in self.models else default_model_path(method)

    def to_json(self) -> dict:
        """The protocol as written to protocol.json; models are identified by content (sha256), not path."""
        d = dataclasses.asdict(self)
        d["models"] = {m: {"file": self.model_path(m).name, "sha256": _sha256(self.model_path(m))} for m in self.methods}
        d["condition_definitions"] = {c: dataclasses.asdict(CONDITIONS[c]) for c in self.conditions}
        return d

    # -- the work
    def units(self) -> list[tuple[str, int, bool]]:
        """(object, trial, noise) work units in a fixed order."""
        noises = sorted({CONDITIONS[c].noise for c in self.conditions})
        return [(o, t, n) for o in self.objects for t in range(self.trials) for n in noises]

    def attempts(self, unit) -> list[tuple[str, int, str, str]]:
        o, t, noise = unit
        return [(o, t, c, m) for c in self.conditions if CONDITIONS[c].noise == noise for m in self.methods]

    def all_attempts(self) -> list[tuple[str, int, str, str]]:
        return [a for u in self.units() for a in self.attempts(u)]

    def acquisition_seed(self, obj: str, trial: int) -> int:
        return derive_seed(self.seed, "acquisition", obj, trial)

    def synthesis_seed(self, obj: str, trial: int, condition: str) -> int:
        return derive_seed(self.seed, "synthesis", obj, trial, condition)


def read_objects_file(path: str | Path) -> list[str]:
    """An objects file: one object URDF per line (a path, or relative to pybullet_data); '#' comments."""
    from .sim import test_objects

    p = Path(path)
    if not p.is_file():
        raise ValueError(f"{path}: no such objects file")
    objects = test_objects(p)
    if not objects:
        raise ValueError(f"{path}: lists no objects")
    # Relative paths that exist next to the list are taken from there.
    return [str((p.parent / o).resolve()) if not Path(o).is_absolute() and (p.parent / o).is_file() else o
            for o in objects]


# ---- one work unit (runs in a worker) -----------------------------------------------------------

_MODELS: dict = {}


def _model(path: str):
    """Each process loads a model once."""
    from .model import GraspModel

    if path not in _MODELS:
        _MODELS[path] = GraspModel.load(path)
    return _MODELS[path]


def crop_above_plane(min_height: float) -> Callable:
    """The clean-up of an acquired cloud: drop points closer than min_height to the support plane z = 0.
    The noise model's lateral shift gives object pixels the depth of the plane beside them, a fringe of
    points on the plane around the object; the segmentation mask keeps the rest of the plane out."""
    from .acquisition import Acquisition

    def cleanup(acq: Acquisition) -> Acquisition:
        keep = acq.points[:, 2] >= min_height
        return dataclasses.replace(acq, points=acq.points[keep], viewpoints=acq.viewpoints[keep],
                                   camera_index=acq.camera_index[keep])

    return cleanup


def run_unit(protocol: dict, unit: tuple, todo: Iterable[tuple] | None = None) -> list[dict]:
    """The attempts of one (object, trial, noise) unit: acquire once, then per condition and method
    synthesise, execute the best grasp, and return one row per attempt. A pure function of its input.

    protocol: Protocol.to_json() plus "model_paths" (method -> path). todo: the attempt keys to run
    (default: all of the unit's)."""
    from . import sim
    from .acquisition import acquire

    p = Protocol(**{k: protocol[k] for k in _PROTOCOL_FIELDS if k in protocol and k != "models"})
    obj, trial, noise = unit[0], int(unit[1]), bool(unit[2])
    keys = [tuple(k) for k in (todo if todo is not None else p.attempts((obj, trial, noise)))]
    acq_seed = p.acquisition_seed(obj, trial)
    # The first synthesis after an acquisition runs a little slower (cold caches, sleeping OpenMP threads):
    # every other unit runs the methods in the other order, so neither method always pays it.
    if acq_seed % 2:
        keys.sort(key=lambda k: (p.conditions.index(k[2]), -p.methods.index(k[3])))
    t0 = time.perf_counter()
    acq = acquire(obj, noise=noise, seed=acq_seed, postprocess=crop_above_plane(p.min_height))
    t_acq = time.perf_counter() - t0
    pose = sim.rest_pose(obj)
    rows = []
    for (_, _, cond, method) in keys:
        c = CONDITIONS[cond]
        model = _model(protocol["model_paths"][method])
        seed = p.synthesis_seed(obj, trial, cond)
        row = {"object": obj, "trial": trial, "condition": cond, "method": method, "noise": int(noise),
               "optimise": int(c.optimise), "acquisition_seed": acq_seed, "synthesis_seed": seed,
               "n_points": len(acq.points), "t_acquisition": t_acq, "error": ""}
        t1 = time.perf_counter()
        try:
            grasps = model.synthesize(acq.points, n_samples=p.n_samples, n_optimise=p.n_optimise, optimise=c.optimise,
                                      seed=seed, remove_plane=False, plane=[0.0, 0.0, 1.0, 0.0],
                                      viewpoints=acq.viewpoints, query_samples=p.query_samples,
                                      annealing={"iterations": p.annealing_iterations,
                                                 "initial_temperature": p.initial_temperature})
            if len(grasps) == 0:
                raise ValueError("synthesis returned no grasps")
        except (ValueError, RuntimeError) as e:
            # A failed synthesis is a failed attempt (nothing to execute), recorded with its reason.
            row.update(success=0, reason="synthesis failed", lift_height=0.0, contact_count=0, log_likelihood="",
                       grasp="", evaluations=0, rejected=0, error=" ".join(str(e).split()),
                       t_features="", t_query="", t_sampling="", t_optimisation="",
                       t_synthesis=time.perf_counter() - t1, t_execution=0.0)
            rows.append(row)
            continue
        best = grasps.best()
        t2 = time.perf_counter()
        r = sim.execute(obj, best, hand=model.hand, object_pose=pose, **CLOSING[p.closing])
        t_exec = time.perf_counter() - t2
        tm = grasps.timing
        grasp = {"T_world_wrist": best["T_world_wrist"], "pregrasp_joints": best["pregrasp_joints"],
                 "grasp_joints": best["grasp_joints"]}
        row.update(success=int(bool(r.success)), reason=r.reason, lift_height=float(r.lift_height),
                   contact_count=int(r.contact_count), log_likelihood=float(best["log_likelihood"]),
                   grasp=json.dumps(grasp, separators=(",", ":")), evaluations=int(grasps.evaluations),
                   rejected=int(grasps.rejected), t_features=tm["features"], t_query=tm["query"],
                   t_sampling=tm["sampling"], t_optimisation=tm["optimisation"], t_synthesis=tm["total"],
                   t_execution=t_exec)
        rows.append(row)
    return rows


_PROTOCOL_FIELDS = [f.name for f in dataclasses.fields(Protocol)]


# ---- the CSV -----------------------------------------------------------------------------------

def _format(v) -> str:
    if isinstance(v, float):
        return repr(v)
    return str(v)


class AttemptLog:
    """attempts.csv: append-only, one row per attempt, flushed and synced after every unit."""

    def __init__(self, path: Path):
        self.path = Path(path)
        self._repair()
        if not self.path.exists() or self.path.stat().st_size == 0:
            with open(self.path, "w", newline="") as f:
                csv.writer(f).writerow(COLUMNS)

    def _repair(self) -> None:
        """A run killed while writing can leave a partial last line: cut it (its unit is run again)."""
        if not self.path.exists():
            return
        data = self.path.read_bytes()
        if data and not data.endswith(b"\n"):
            cut = data.rfind(b"\n") + 1
            with open(self.path, "r+b") as f:
                f.truncate(cut)
        if self.path.stat().st_size > 0:
            with open(self.path, newline="") as f:
                header = next(csv.reader(f), None)
            if header != COLUMNS:
                raise ValueError(f"{self.path}: its columns are not those of this graspmix version's attempts.csv")

    def done(self) -> set[tuple]:
        return {(r["object"], int(r["trial"]), r["condition"], r["method"]) for r in read_rows(self.path)}

    def append(self, rows: list[dict]) -> None:
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        for r in rows:
            w.writerow([_format(r.get(c, "")) for c in COLUMNS])
        with open(self.path, "a", newline="") as f:
            f.write(buf.getvalue())
            f.flush()
            os.fsync(f.fileno())


def read_rows(path: str | Path) -> list[dict]:
    """The rows of an attempts.csv, typed (ints, floats, None for empty numbers), in file order; a
    trailing partial line (a killed run) is ignored."""
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"{path}: no such attempts file")
    text = path.read_text()
    if text and not text.endswith("\n"):
        text = text[: text.rfind("\n") + 1]
    reader = csv.DictReader(io.StringIO(text))
    if reader.fieldnames is None:
        return []
    missing = [c for c in COLUMNS if c not in reader.fieldnames]
    if missing:
        raise ValueError(f"{path}: not an attempts.csv (missing columns {', '.join(missing)})")
    ints = {"trial", "noise", "optimise", "acquisition_seed", "synthesis_seed", "n_points", "success",
            "contact_count", "evaluations", "rejected"}
    floats = {"lift_height", "log_likelihood", *TIME_COLUMNS}
    rows = []
    for r in reader:
        out = {}
        for k in COLUMNS:
            v = r[k]
            if k in ints:
                out[k] = int(v) if v != "" else None
            elif k in floats:
                out[k] = float(v) if v != "" else None
            else:
                out[k] = v
        rows.append(out)
    return rows


# ---- progress ----------------------------------------------------------------------------------

def _hms(seconds: float) -> str:
    if not math.isfinite(seconds):
        return "--:--"
    s = int(round(seconds))
    return f"{s // 3600}:{s % 3600 // 60:02d}:{s % 60:02d}" if s >= 3600 else f"{s // 60:02d}:{s % 60:02d}"


class Progress:
    """A one-line progress bar on stderr with the time left (from this session's pace). Off a terminal
    it prints a line every 5% instead of redrawing."""

    def __init__(self, total: int, done: int = 0, stream=None, width: int = 30, enabled: bool = True):
        self.total, self.done, self.start_done = total, done, done
        self.stream = stream or sys.stderr
        self.width = width
        self.enabled = enabled
        self.t0 = time.perf_counter()
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self._last_pct = -1

    def line(self) -> str:
        frac = self.done / self.total if self.total else 1.0
        n = int(frac * self.width)
        elapsed = time.perf_counter() - self.t0
        new = self.done - self.start_done
        left = elapsed / new * (self.total - self.done) if new > 0 else math.inf
        return (f"[{'#' * n}{'.' * (self.width - n)}] {self.done}/{self.total} attempts {frac * 100:5.1f}%  "
                f"elapsed {_hms(elapsed)}  left {_hms(left)}")

    def update(self, n: int) -> None:
        self.done += n
        if not self.enabled:
            return
        if self.tty:
            print("\r" + self.line(), end="", file=self.stream, flush=True)
        else:
            pct = int(100 * self.done / max(self.total, 1)) // 5 * 5
            if pct != self._last_pct:
                self._last_pct = pct
                print(self.line(), file=self.stream, flush=True)

    def close(self) -> None:
        if self.enabled and self.tty:
            print(file=self.stream, flush=True)


# ---- running -----------------------------------------------------------------------------------

def _protocol_document(protocol: Protocol, command: str | None = None) -> dict:
    from . import __version__

    prov = {"graspmix": __version__, "commit": git_commit(),
            "created_utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())}
    if command:
        prov["command"] = command
    return {"format": PROTOCOL_FORMAT, "protocol": protocol.to_json(), "provenance": prov}


def load_protocol(run_dir: str | Path) -> dict:
    path = Path(run_dir) / PROTOCOL_NAME
    if not path.is_file():
        raise ValueError(f"{run_dir}: no {PROTOCOL_NAME} (not an experiment folder)")
    from .model import _read_json

    doc = _read_json(path, "protocol")
    if doc.get("format") != PROTOCOL_FORMAT:
        raise ValueError(f"{path}: not a {PROTOCOL_FORMAT} file")
    return doc


def prepare_folder(protocol: Protocol, out: str | Path, command: str | None = None) -> Path:
    """Checks the inputs and the folder; writes protocol.json for a new run. A folder holding another
    protocol's run (or other files) is refused, before any work starts."""
    protocol.validate()
    protocol.check_inputs()
    out = Path(out)
    doc = _protocol_document(protocol, command)
    if out.exists() and not out.is_dir():
        raise ValueError(f"{out}: exists and is not a folder")
    pfile = out / PROTOCOL_NAME
    if pfile.exists():
        old = load_protocol(out)["protocol"]
        if old != doc["protocol"]:
            diff = sorted(k for k in set(old) | set(doc["protocol"]) if old.get(k) != doc["protocol"].get(k))
            raise ValueError(f"{out}: holds a run of a different protocol (differs in: {', '.join(diff)}); "
                             "use another --out folder, or the same options to resume")
    else:
        if out.is_dir() and any(out.iterdir()):
            raise ValueError(f"{out}: is not empty and holds no {PROTOCOL_NAME}; use a new or empty folder")
        out.mkdir(parents=True, exist_ok=True)
        pfile.write_text(json.dumps(doc, indent=1) + "\n")
    return out


def run(protocol: Protocol, out: str | Path, *, jobs: int = 1, executor: str = "local", progress: bool = True,
        report: bool = True, ray_address: str | None = None, max_units: int | None = None,
        command: str | None = None) -> dict:
    """Runs (or resumes) the experiment into the folder out; returns {"rows", "ran", "skipped", "seconds"}.

    jobs: parallel worker processes (local) or Ray tasks in flight (ray). executor: "local" or "ray"
    (ray_address: a cluster to join; None starts a local Ray instance). max_units: stop after this many
    work units (for tests of resuming). command: recorded in protocol.json when the run starts. report:
    write summary.json, report.md and report.html at the end."""
    if executor not in ("local", "ray"):
        raise ValueError(f"executor must be 'local' or 'ray', got {executor!r}")
    if not isinstance(jobs, int) or jobs < 1:
        raise ValueError(f"jobs must be a positive integer, got {jobs!r}")
    if executor == "ray":
        try:
            import ray  # noqa: F401
        except ImportError:
            raise ValueError("--executor ray needs the ray package (pip install ray)") from None
    out = prepare_folder(protocol, out, command)
    log = AttemptLog(out / CSV_NAME)
    done = log.done()
    pdoc = protocol.to_json()
    pdoc["model_paths"] = {m: str(protocol.model_path(m).resolve()) for m in protocol.methods}
    work = []
    for u in protocol.units():
        todo = [a for a in protocol.attempts(u) if a not in done]
        if todo:
            work.append((u, todo))
    if max_units is not None:
        work = work[:max_units]
    total = len(protocol.all_attempts())
    bar = Progress(total, len(done), enabled=progress)
    t0 = time.perf_counter()
    ran = 0

    def record(rows):
        nonlocal ran
        log.append(rows)
        ran += len(rows)
        bar.update(len(rows))

    try:
        if not work:
            pass
        elif executor == "ray":
            _run_ray(pdoc, work, jobs, record, ray_address)
        elif jobs == 1:
            for u, todo in work:
                record(run_unit(pdoc, u, todo))
        else:
            _run_pool(pdoc, work, jobs, record)
    finally:
        bar.close()
    result = {"rows": len(log.done()), "ran": ran, "skipped": len(done), "seconds": time.perf_counter() - t0,
              "total": total}
    if report and result["rows"] > 0:
        from .report import build_report

        build_report(out)
    return result


def _unit_job(args):
    return run_unit(*args)


def _run_pool(pdoc: dict, work: list, jobs: int, record: Callable) -> None:
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
        for rows in pool.imap_unordered(_unit_job, [(pdoc, u, todo) for u, todo in work], chunksize=1):
            record(rows)
    except BaseException:
        # Stopped (Ctrl-C) or failed: the workers' unfinished units are lost anyway, so end them now.
        pool.terminate()
        pool.join()
        raise
    pool.close()
    pool.join()


def _run_ray(pdoc: dict, work: list, jobs: int, record: Callable, address: str | None) -> None:
    import ray

    started = False
    if not ray.is_initialized():
        if address:
            ray.init(address=address, log_to_driver=False)
        else:
            ray.init(num_cpus=jobs, include_dashboard=False, log_to_driver=False,
                     runtime_env={"env_vars": {"OMP_NUM_THREADS": "1"}})
        started = True
    try:
        task = ray.remote(num_cpus=1)(run_unit)
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


# ---- the runtime benchmark ---------------------------------------------------------------------

STAGES = ("query", "sampling", "optimisation")
STAGE_LABELS = {"query": "query density estimation", "sampling": "sampling and ranking",
                "optimisation": "optimising the top 10"}


def benchmark(objects: list[str], out: str | Path | None = None, *, n_samples: int = 200, n_optimise: int = 10,
              seed: int = 0, progress: bool = True) -> dict:
    """Fig. runtime: per object, a noise-free acquisition and one synthesis per method (n_samples grasps,
    the best n_optimise annealed); stage times, their medians over objects per method and the ratio
    KDE / GMM. Writes benchmark.json and benchmark.png into out if given."""
    from . import __version__
    from .acquisition import acquire

    p = Protocol(objects=list(objects), trials=1, n_samples=n_samples, n_optimise=n_optimise, seed=seed)
    p.check_inputs()
    per_object = {m: {s: [] for s in (*STAGES, "features", "total")} for m in METHODS}
    bar = Progress(len(objects) * len(METHODS), enabled=progress)
    load_before = os.getloadavg()
    for i, obj in enumerate(objects):
        acq = acquire(obj, noise=False, seed=p.acquisition_seed(obj, 0), postprocess=crop_above_plane(p.min_height))
        for m in (METHODS if i % 2 == 0 else METHODS[::-1]):  # alternate which method runs first
            g = _model(str(p.model_path(m).resolve())).synthesize(
                acq.points, n_samples=n_samples, n_optimise=n_optimise, optimise=True,
                seed=p.synthesis_seed(obj, 0, "A"), remove_plane=False, plane=[0.0, 0.0, 1.0, 0.0],
                viewpoints=acq.viewpoints, query_samples=p.query_samples)
            for s in (*STAGES, "features"):
                per_object[m][s].append(float(g.timing[s]))
            per_object[m]["total"].append(float(sum(g.timing[s] for s in STAGES)))
            bar.update(1)
    bar.close()
    medians = {m: {s: float(np.median(v)) for s, v in per_object[m].items()} for m in METHODS}
    ratio = {s: medians["kde"][s] / medians["gmm"][s] if medians["gmm"][s] > 0 else math.nan
             for s in (*STAGES, "total")}
    result = {"format": "graspmix.benchmark/1", "graspmix": __version__, "commit": git_commit(),
              "objects": list(objects), "n_samples": n_samples, "n_optimise": n_optimise,
              "annealing_iterations": p.annealing_iterations,
              "note": "total = query + sampling + optimisation (the paper's Fig. runtime); features (shared by "
                      "both methods) is listed apart",
              "median_s": medians, "ratio_kde_over_gmm": ratio, "per_object_s": per_object,
              "machine": {"cpu_count": os.cpu_count(), "load_average_before": list(load_before),
                          "load_average_after": list(os.getloadavg()),
                          "OMP_NUM_THREADS": os.environ.get("OMP_NUM_THREADS"),
                          "OMP_WAIT_POLICY": os.environ.get("OMP_WAIT_POLICY")}}
    if out is not None:
        from .report import plot_runtime

        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        (out / "benchmark.json").write_text(json.dumps(result, indent=1) + "\n")
        plot_runtime(medians, out / "benchmark.png",
                     title=f"Synthesis time, median over {len(objects)} objects ({n_samples} grasps)")
    return result


def format_benchmark(result: dict) -> str:
    med, ratio = result["median_s"], result["ratio_kde_over_gmm"]
    lines = [f"runtime per object (median over {len(result['objects'])} objects, {result['n_samples']} grasps, "
             f"top {result['n_optimise']} optimised), ms:",
             f"{'stage':<28} {'GMM':>9} {'KDE':>9} {'KDE/GMM':>8}"]
    for s in (*STAGES, "total"):
        label = STAGE_LABELS.get(s, "total (the three stages)")
        lines.append(f"{label:<28} {med['gmm'][s] * 1e3:>9.1f} {med['kde'][s] * 1e3:>9.1f} {ratio[s]:>8.2f}")
    lines.append(f"{'(features, shared)':<28} {med['gmm']['features'] * 1e3:>9.1f} {med['kde']['features'] * 1e3:>9.1f}")
    return "\n".join(lines)
