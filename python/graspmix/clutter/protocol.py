"""The clutter-removal protocol's settings (written to clutter.json), its seeds, its rules and its CSV.

The rules are those of Breyer et al. 2020 (VGN, ethz-asl/vgn, src/vgn/experiments/clutter_removal.py),
which Jiang et al. 2021 (GIGA) keep: per round (a scene of N objects), observe, plan, execute the best
grasp, and go on while objects remain and fewer than MAX_CONSECUTIVE_FAILURES = 2 grasps in a row have
failed; a planner that finds no grasp ends the round. VGN has no cap on the number of attempts (the rules
bound it by 2N: every success removes an object and no two failures follow each other). The cap of
Jiang et al.'s protocol description and of graspmix's issue, N + 2 attempts, is the default here
(max_attempts = -1); 0 keeps VGN's rules alone, any other number caps the attempts at it.

task "named" is the other measurement on the same scenes: no clearing, but one object named by a point on
its visible surface (what a user clicks), lifted or not (graspmix.clutter.named); `targets` named objects per
scene, each on the untouched scene.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path

from ..experiment.log import CsvSchema
from ..experiment.protocol import CLOSING as EXPERIMENT_CLOSING
from ..experiment.protocol import derive_seed
from ..experiment.runner import RunFolder
from ..io import CLUTTER_FORMAT, data_path, read_document, read_object_list, sha256_file
from ..io.checks import check_input_file, check_int, check_seed, quote
from ..io.paths import PACKAGE_PREFIX, resolve_path
from ..model import default_model_path
from ..model.options import SynthesisOptions
from ..model.settings import METHODS

MODES = ("pile", "packed")
PLANNERS = (*METHODS, "topdown")  # the methods' models, and the top-down baseline
MAX_CONSECUTIVE_FAILURES = 2  # VGN's MAX_CONSECUTIVE_FAILURES
ROUNDS = 40  # VGN's default number of rounds (num_rounds=40)
CLOSING = tuple(EXPERIMENT_CLOSING)  # how executed grasps close: see graspmix.experiment.protocol.CLOSING
# Outcomes of an attempt: the simulation's reasons, and a planner that found no object or no grasp.
OUTCOMES = ("success", "start in collision", "no contact", "not held", "two objects lifted", "synthesis failed")
# Why a round ended (the "stop" column of its last row).
STOPS = ("clear", "two failures", "no grasp", "attempt limit")
# What a run measures: "clear" the scenes (VGN's rounds), or lift a "named" object (graspmix.clutter.named).
TASKS = ("clear", "named")
# What the planners are given of an observation (the experiment's words): every pixel as points with the
# camera's position ("scene", the points path of segment_scene), or the camera's depth "image" with its intrinsics
# and pose, as a robot's camera gives it (one camera; the default then, as the experiment's defaults take it).
CLOUDS = ("scene", "image")
CLUTTER_NAME = "clutter.json"
CLUTTER_CSV_NAME = "clutter_attempts.csv"


def default_object_list() -> Path:
    """The clutter test split (data/objects/clutter_test.txt): objects never used to choose a setting."""
    return data_path("objects", "clutter_test.txt")


@dataclass
class ClutterProtocol:
    """Everything that decides a clutter-removal run's rows. Equal protocols give equal rows (but times)."""

    object_list: str = ""  # the list the scenes' objects are drawn from; "": the clutter test split
    objects: int = 5  # objects placed per scene (VGN's num_objects)
    scenes: int = ROUNDS  # rounds per mode and method; every method sees the same scenes
    modes: list[str] = field(default_factory=lambda: ["pile"])
    methods: list[str] = field(default_factory=lambda: ["gmm"])
    views: int = 1  # cameras per observation
    noise: bool = False  # the depth noise model
    synthesis: SynthesisOptions = field(default_factory=SynthesisOptions)  # every plan's (seeded per attempt)
    closing: str = "full"  # how executed grasps close (the experiment's CLOSING)
    max_attempts: int = -1  # per round; -1: objects + 2; 0: VGN's rules alone (no cap)
    seed: int = 0
    models: dict = field(default_factory=dict)  # method -> model file; empty: the bundled box models
    task: str = "clear"  # TASKS: clear the scenes, or lift a named object per scene
    targets: int = 1  # task "named": objects named per scene (each on the untouched scene)
    cloud: str = ""  # CLOUDS; "": "image" with one camera, else "scene" (a clutter.json without it: "scene")

    def __post_init__(self):
        if not self.object_list:  # named as bundled data, so the run's files name no machine's path
            self.object_list = PACKAGE_PREFIX + "objects/clutter_test.txt"
        if self.cloud == "":
            self.cloud = "image" if self.views == 1 else "scene"
        self.validate()

    @property
    def object_list_path(self) -> Path:
        """The object list as a file (package://graspmix/... names the bundled data)."""
        return resolve_path(self.object_list, Path.cwd())

    @property
    def attempt_limit(self) -> int:
        """Attempts a round may take at most (0: no cap)."""
        return self.objects + 2 if self.max_attempts < 0 else self.max_attempts

    def validate(self) -> None:
        if not isinstance(self.object_list, str):
            raise ValueError(f"object_list must be a file name, got {quote(self.object_list)}")
        check_int(self.objects, "objects", 1, 50)
        check_int(self.scenes, "scenes", 1, 1_000_000)
        check_int(self.views, "views", 1, 64)
        if not isinstance(self.synthesis, SynthesisOptions):
            raise ValueError(f"synthesis must be SynthesisOptions, got {type(self.synthesis).__name__}")
        check_int(self.max_attempts, "max_attempts", -1, 10_000)
        self._check_task()
        if self.cloud not in CLOUDS:
            raise ValueError(f"cloud must be one of {', '.join(CLOUDS)}, got {quote(self.cloud)}")
        if self.cloud == "image" and self.views != 1:
            raise ValueError(f"cloud 'image' is one camera's depth image: views must be 1, got {self.views}")
        check_seed(self.seed)
        if not isinstance(self.noise, bool):
            raise ValueError(f"noise must be true or false, got {quote(self.noise)}")
        if self.closing not in CLOSING:
            raise ValueError(f"closing must be one of {', '.join(CLOSING)}, got {quote(self.closing)}")
        for what, values, known in (("mode", self.modes, MODES), ("method", self.methods, PLANNERS)):
            if not isinstance(values, (list, tuple)) or not values:
                raise ValueError(f"no {what}s given ({what}s: {quote(values)})")
            for v in values:
                if v not in known:
                    raise ValueError(f"unknown {what} {quote(v)} (known: {', '.join(known)})")
            if len(set(values)) != len(values):
                raise ValueError(f"a {what} is listed twice: {','.join(values)}")
        if not isinstance(self.models, dict) or any(m not in METHODS for m in self.models):
            raise ValueError(f"models must be a dict method (gmm|kde) -> model file, got {quote(self.models)}")

    def _check_task(self) -> None:
        if self.task not in TASKS:
            raise ValueError(f"task must be one of {', '.join(TASKS)}, got {quote(self.task)}")
        check_int(self.targets, "targets", 1, 50)
        if self.task == "clear" and self.targets != 1:
            raise ValueError(f"targets ({self.targets}) is for the named task only (task is clear)")
        if self.task == "named" and self.max_attempts != -1:
            raise ValueError(f"max_attempts ({self.max_attempts}) is for the clear task only (named: one attempt each)")
        if self.task == "named" and self.targets > self.objects:
            raise ValueError(f"targets ({self.targets}) must not exceed the objects per scene ({self.objects})")

    def check_inputs(self) -> None:
        """The object list has at least `objects` entries and every model file exists: before any work."""
        entries = read_object_list(check_input_file(self.object_list_path, "object list"))
        if len(entries) < self.objects:
            raise ValueError(f"{self.object_list}: lists {len(entries)} objects, a scene needs {self.objects}")
        for m in self.model_methods():
            if not self.model_path(m).is_file():
                raise ValueError(f"{self.model_path(m)}: no such {m} model file")

    def synthesize(self, model, obs, options: SynthesisOptions, target="all"):
        """A model's grasps on an observation (acquire_scene's), given as the protocol's `cloud` says."""
        if self.cloud == "image":
            return model.synthesize(**obs.view_input(), options=options, target=target)
        return model.synthesize(obs.points, options, target=target, viewpoints=obs.viewpoints)

    def object_labels(self, obs):
        """Per row of the synthesis' input (Scene.sources index it), the simulator's object label (-1 the table):
        per point of the observation, or per pixel of its image (-2 where nothing was hit); None without labels."""
        if obs.labels is None or self.cloud == "scene":
            return obs.labels
        return obs.per_pixel(obs.labels, -2)

    def model_methods(self) -> list[str]:
        return [m for m in self.methods if m in METHODS]

    def model_path(self, method: str) -> Path:
        return Path(self.models[method]) if method in self.models else default_model_path(method)

    def to_json(self) -> dict:
        """clutter.json's "protocol": files identified by content (sha256) as well as by name."""
        d = {f: getattr(self, f) for f in PROTOCOL_FIELDS}
        if self.task == "clear":  # a clearing run's clutter.json as before the task existed: its folders resume
            del d["task"], d["targets"]
        if self.cloud == "scene":  # as before the image input existed (a clutter.json without it): those resume
            del d["cloud"]
        d["synthesis"] = self.synthesis.to_dict()
        d["object_list_sha256"] = sha256_file(self.object_list_path)
        d["models"] = {
            m: {"file": self.model_path(m).name, "sha256": sha256_file(self.model_path(m))}
            for m in self.model_methods()
        }
        return d

    # -- the work: one round per (mode, scene, method), or per (mode, scene, method, pick) named object;
    # all methods share a mode's scenes
    def rounds(self) -> list[tuple]:
        if self.task == "named":
            return [
                (mode, s, m, k)
                for mode in self.modes
                for s in range(self.scenes)
                for m in self.methods
                for k in range(self.targets)
            ]
        return [(mode, s, m) for mode in self.modes for s in range(self.scenes) for m in self.methods]

    def scene_seed(self, mode: str, scene: int) -> int:
        return derive_seed(self.seed, "clutter scene", mode, scene)

    def stage_seed(self, stage: str, mode: str, scene: int, attempt: int) -> int:
        return derive_seed(self.seed, "clutter", stage, mode, scene, attempt)


PROTOCOL_FIELDS = [f.name for f in dataclasses.fields(ClutterProtocol)]


def input_words(p: dict) -> str:
    """What a stored protocol's planners were given, for its report."""
    return "as its depth image" if p.get("cloud", "scene") == "image" else "as points"


def clutter_protocol_from_json(d: dict) -> ClutterProtocol:
    kw = {k: d[k] for k in PROTOCOL_FIELDS if k in d and k not in ("models", "synthesis")}
    kw.setdefault("cloud", "scene")  # written before the image input existed: the points
    return ClutterProtocol(**kw, synthesis=SynthesisOptions.from_stored(d["synthesis"]))


def load_clutter_protocol(run_dir) -> dict:
    """A run folder's clutter.json (format graspmix.clutter/2), checked."""
    path = Path(run_dir) / CLUTTER_NAME
    if not path.is_file():
        raise ValueError(f"{run_dir}: no {CLUTTER_NAME} (not a clutter-removal run folder)")
    doc = read_document(path, CLUTTER_FORMAT)
    try:
        clutter_protocol_from_json(doc["protocol"]).validate()
    except (TypeError, ValueError) as e:
        raise ValueError(f"{path}: {e}") from None
    return doc


CLUTTER_FOLDER = RunFolder(CLUTTER_NAME, CLUTTER_FORMAT, load_clutter_protocol)

# clutter_attempts.csv: one row per attempt. A round's rows are written together when it ends; its last
# row names why it ended (stop), so a round is done when a row of it has a stop.
KEY_COLUMNS = ("mode", "scene", "method", "attempt")
RESULT_COLUMNS = (
    "scene_seed",
    "placed",
    "before",
    "after",
    "seen",
    "target",
    "outcome",
    "success",
    "lifted",
    "max_moved",
    "lift_height",
    "stop",
    "observe_seed",
    "synthesis_seed",
    "n_points",
    "grasp",
    "error",
)
TIME_COLUMNS = ("t_observe", "t_segment", "t_synthesis", "t_execution")
TEXT_COLUMNS = frozenset({"mode", "method", "outcome", "stop", "grasp", "error"})
FLOAT_COLUMNS = frozenset({"max_moved", "lift_height", *TIME_COLUMNS})
ALL_COLUMNS = KEY_COLUMNS + RESULT_COLUMNS + TIME_COLUMNS
CLUTTER_CSV = CsvSchema(
    ALL_COLUMNS,
    KEY_COLUMNS,
    frozenset(ALL_COLUMNS) - TEXT_COLUMNS - FLOAT_COLUMNS,  # the counts, indices and seeds
    FLOAT_COLUMNS,
    "clutter attempts",
)


def check_row(r: dict, i: int, proto: dict, outcomes, path: Path) -> None:
    """Row i (1-based) of a run's CSV has the protocol's mode, method and scene, and one of `outcomes` that agrees
    with its success: a CSV edited by hand is an error (ValueError naming the file, the row and the column)."""
    if r["mode"] not in proto["modes"] or r["method"] not in proto["methods"]:
        raise ValueError(f"{path}: row {i}: mode/method {quote(r['mode'])}/{quote(r['method'])} not in the protocol")
    if r["scene"] is None or not 0 <= r["scene"] < proto["scenes"]:
        raise ValueError(f"{path}: row {i}: scene {quote(r['scene'])} is not in 0..{proto['scenes'] - 1}")
    if r["outcome"] not in outcomes or r["success"] != int(r["outcome"] == "success"):
        raise ValueError(f"{path}: row {i}: outcome {quote(r['outcome'])} with success {quote(r['success'])}")
