"""The paper's experiment: conditions A-D, GMM vs KDE, on the 60 test objects over repeated trials.

    from graspmix import experiment
    protocol = experiment.Protocol.preset("smoke")          # or "paper", or Protocol(objects=[...], ...)
    experiment.run(protocol, "runs/smoke", jobs=2)           # attempts.csv, summary.json, report.md/html
    summary = experiment.report.build_report("runs/smoke")   # the report again, from the folder alone

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

Modules: protocol (conditions, seeds, protocol.json), attempt (one work unit), executors (local, Ray),
log (attempts.csv), progress, runner (run, resume), stats (t-tests), report (summary.json, report.md/html),
runtime_benchmark (Fig. runtime).
"""

from ..io import PROTOCOL_FORMAT, git_commit, read_objects_file
from ..model.grasps import STAGE_LABELS, STAGES
from ..model.settings import METHODS
from . import report, stats
from .attempt import crop_above_plane, run_unit
from .log import COLUMNS, CSV_NAME, KEY_COLUMNS, RESULT_COLUMNS, TIME_COLUMNS, AttemptLog, read_rows
from .progress import Progress
from .protocol import (
    CLOSING,
    CONDITIONS,
    PRESETS,
    PROTOCOL_NAME,
    SMOKE_OBJECTS,
    Condition,
    Protocol,
    derive_seed,
    load_protocol,
)
from .runner import prepare_folder, run
from .runtime_benchmark import benchmark, format_benchmark

__all__ = [
    "PROTOCOL_FORMAT",
    "CSV_NAME",
    "PROTOCOL_NAME",
    "Condition",
    "CONDITIONS",
    "METHODS",
    "CLOSING",
    "PRESETS",
    "SMOKE_OBJECTS",
    "KEY_COLUMNS",
    "RESULT_COLUMNS",
    "TIME_COLUMNS",
    "COLUMNS",
    "STAGES",
    "STAGE_LABELS",
    "derive_seed",
    "git_commit",
    "Protocol",
    "read_objects_file",
    "crop_above_plane",
    "run_unit",
    "AttemptLog",
    "read_rows",
    "Progress",
    "load_protocol",
    "prepare_folder",
    "run",
    "benchmark",
    "format_benchmark",
    "report",
    "stats",
]
