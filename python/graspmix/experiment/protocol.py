"""The experiment's protocol: conditions A-D, the methods, how grasps close, the seeds, and everything
else that decides the results (written to protocol.json)."""

from __future__ import annotations

import dataclasses
import hashlib
from dataclasses import dataclass, field
from operator import attrgetter
from pathlib import Path

from ..io import PROTOCOL_FORMAT, read_document, resolve_object, sha256_file, test_objects
from ..io.checks import check_float, check_int, check_seed, quote
from ..model import default_model_path
from ..model.options import SynthesisOptions
from ..model.settings import METHODS
from ..sim.acquisition import AcquisitionSettings
from ..sim.execution import CLOSING  # how an executed grasp closes: one definition for every caller
from ..sim.scene_camera import scene_cameras

_ACQUISITION = AcquisitionSettings()

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
PRESETS = ("smoke", "paper", "defaults")
# What an acquisition keeps: "object", the pixels that see the object with the table cropped (the paper's: a
# segmented sensor); "scene", every pixel, the table too, as points in the world (the synthesis finds the object
# above the known table, and the table's rays show the occupancy model the free space around it); "image", every
# pixel as the camera's driver gives it, the depth image with its intrinsics and the camera's pose (one camera:
# the synthesis works in image space, perception.segment_view). The defaults preset with one camera takes "image":
# the user's input.
CLOUDS = ("object", "scene", "image")
# The smoke preset's objects: three of the test set with different shapes (a mug, a small block-like
# part, an elongated part), so the smoke run exercises more than one kind of grasp.
SMOKE_OBJECTS = 3
# The known support plane of an acquired scene (z = 0, the object on its positive side).
SUPPORT_PLANE = (0.0, 0.0, 1.0, 0.0)


def derive_seed(*parts) -> int:
    """A 31-bit seed from the parts' text (BLAKE2b): the same in every process and on every machine."""
    text = "\x1f".join(str(p) for p in parts).encode()
    return int.from_bytes(hashlib.blake2b(text, digest_size=8).digest(), "little") & 0x7FFFFFFF


@dataclass
class Protocol:
    """Everything that decides an experiment's results. Two runs with equal protocols give equal rows."""

    objects: list[str]
    trials: int = 10
    conditions: list[str] = field(default_factory=lambda: list(CONDITIONS))
    methods: list[str] = field(default_factory=lambda: list(METHODS))
    # The noise model of the conditions with noise (eq:noise_model): sigma_p, the lateral shift in pixels, and
    # sigma_d, the depth noise in metres; setting one to 0 leaves the other part alone.
    pixel_noise_std: float = _ACQUISITION.pixel_noise_std
    depth_noise_std: float = _ACQUISITION.depth_noise_std
    closing: str = "full"  # how the executed grasp closes: see CLOSING
    views: int = 4  # cameras: the paper's ring of 4 (n > 1: a ring of n), or 1: one camera above the table
    cloud: str = "scene"  # what an acquisition keeps: see CLOUDS (the paper's: "object")
    # How every attempt synthesises (the library's defaults; the paper's: SynthesisOptions.paper()). Per attempt
    # the condition decides sampling.optimise and the seed is derived; the known support plane is given, and its
    # table clearance (segmentation.table_clearance) also crops an object cloud's table fringe.
    synthesis: SynthesisOptions = field(default_factory=SynthesisOptions)
    seed: int = 0  # base of every derived seed
    models: dict = field(default_factory=dict)  # method -> model file; empty: the bundled box models

    def __post_init__(self):
        self.validate()

    @classmethod
    def preset(cls, name: str, **overrides) -> "Protocol":
        """ "paper": the 60 test objects, 10 trials, A-D, GMM and KDE, the paper's synthesis (SynthesisOptions.paper(), object clouds).
        "smoke": the same with 3 objects and 2 trials (minutes, for tests and a first look). "defaults": as
        "paper" with the library's synthesis defaults (SynthesisOptions()) on whole depth images."""
        if name not in PRESETS:
            raise ValueError(f"preset must be one of {', '.join(PRESETS)}, got {name!r}")
        objects = test_objects()
        paper = dict(cloud="object", synthesis=SynthesisOptions.paper())
        if name == "smoke":
            kw = dict(objects=objects[:SMOKE_OBJECTS], trials=2, **paper)
        elif name == "paper":
            kw = dict(objects=objects, trials=10, **paper)
        else:
            kw = dict(objects=objects, trials=10)
        kw.update({k: v for k, v in overrides.items() if v is not None})
        if name == "defaults" and kw.get("views") == 1 and overrides.get("cloud") is None:
            kw["cloud"] = "image"
        return cls(**kw)

    def validate(self) -> None:
        self._validate_lists()
        check_float(self.pixel_noise_std, "pixel_noise_std", 0.0)
        check_float(self.depth_noise_std, "depth_noise_std", 0.0)
        check_seed(self.seed)
        if not isinstance(self.synthesis, SynthesisOptions):
            raise ValueError(f"synthesis must be SynthesisOptions, got {type(self.synthesis).__name__}")
        # What each attempt decides itself (attempt_options): a value here would be recorded and not used.
        default = SynthesisOptions()
        for name, why in (
            ("seed", "each attempt's seed is derived from the protocol's seed"),
            ("sampling.optimise", "the conditions decide the optimisation"),
            ("segmentation.find_plane", "the known table is given"),
        ):
            if attrgetter(name)(self.synthesis) != attrgetter(name)(default):
                raise ValueError(f"synthesis.{name}: {why}, so the protocol does not set it")
        check_int(self.views, "views", 1, 64)
        if not isinstance(self.cloud, str) or self.cloud not in CLOUDS:
            raise ValueError(f"cloud must be one of {', '.join(CLOUDS)}, got {quote(self.cloud)}")
        if self.cloud == "image" and self.views != 1:
            raise ValueError(f"cloud 'image' is one camera's depth image: views must be 1, got {self.views}")
        if not isinstance(self.closing, str) or self.closing not in CLOSING:
            raise ValueError(f"closing must be one of {', '.join(CLOSING)}, got {quote(self.closing)}")
        if not isinstance(self.models, dict):
            raise ValueError(f"models must be a dict method -> model file, got {quote(self.models)}")
        for m in self.models:
            if m not in METHODS:
                raise ValueError(f"models: unknown method {quote(m)}")

    def _validate_lists(self) -> None:
        if not isinstance(self.objects, (list, tuple)) or not self.objects:
            raise ValueError(f"the protocol has no objects (objects: {quote(self.objects)})")
        for o in self.objects:
            if not isinstance(o, str) or not o:
                raise ValueError(f"objects must be file names, got {quote(o)}")
        if len(set(self.objects)) != len(self.objects):
            dup = sorted({o for o in self.objects if self.objects.count(o) > 1})
            raise ValueError(f"objects are listed twice: {', '.join(dup)}")
        check_int(self.trials, "trials", 1, 100_000)
        for what, values, known in (("condition", self.conditions, CONDITIONS), ("method", self.methods, METHODS)):
            if not isinstance(values, (list, tuple)) or not values:
                raise ValueError(f"no {what}s given ({what}s: {quote(values)})")
            for v in values:
                if not isinstance(v, str) or v not in known:
                    raise ValueError(f"unknown {what} {quote(v)} (known: {', '.join(known)})")
            if len(set(values)) != len(values):
                raise ValueError(f"a {what} is listed twice: {','.join(values)}")

    def check_inputs(self) -> None:
        """Every object and model file exists and loads: raises ValueError before any work starts."""
        missing = []
        for o in self.objects:
            try:
                resolve_object(o)
            except ValueError:
                missing.append(o)
        if missing:
            raise ValueError(
                f"{len(missing)} object(s) not found (neither a file nor in pybullet_data): "
                + ", ".join(missing[:5])
                + (" ..." if len(missing) > 5 else "")
            )
        for m in self.methods:
            path = self.model_path(m)
            if not path.is_file():
                raise ValueError(f"{path}: no such {m} model file")

    def model_path(self, method: str) -> Path:
        return Path(self.models[method]) if method in self.models else default_model_path(method)

    def to_json(self) -> dict:
        """The protocol as written to protocol.json; models are identified by content (sha256), not path."""
        d = {f: getattr(self, f) for f in PROTOCOL_FIELDS}
        d["synthesis"] = self.synthesis.to_dict()
        d["models"] = {
            m: {"file": self.model_path(m).name, "sha256": sha256_file(self.model_path(m))} for m in self.methods
        }
        d["condition_definitions"] = {c: dataclasses.asdict(CONDITIONS[c]) for c in self.conditions}
        return d

    def acquisition_settings(self) -> AcquisitionSettings:
        """The cameras, the noise model and what the acquisitions keep."""
        return AcquisitionSettings(
            cameras=scene_cameras(self.views),
            pixel_noise_std=self.pixel_noise_std,
            depth_noise_std=self.depth_noise_std,
            keep="object" if self.cloud == "object" else "scene",
        )

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

    def attempt_options(self, obj: str, trial: int, condition: str) -> SynthesisOptions:
        """The synthesis of one attempt: the protocol's, with the condition's optimisation, the attempt's seed
        and the known support plane (given to the synthesis, so none is searched for)."""
        return self.synthesis.updated(
            {
                "sampling.optimise": CONDITIONS[condition].optimise,
                "seed": self.synthesis_seed(obj, trial, condition),
                "segmentation.find_plane": False,
            }
        )


PROTOCOL_FIELDS = [f.name for f in dataclasses.fields(Protocol)]


def protocol_from_json(d: dict) -> Protocol:
    """The Protocol of a protocol.json's "protocol" entry (model paths are not in it: the defaults)."""
    kw = {k: d[k] for k in PROTOCOL_FIELDS if k in d and k not in ("models", "synthesis")}
    return Protocol(**kw, synthesis=SynthesisOptions.from_stored(d["synthesis"]))


def load_protocol(run_dir: str | Path) -> dict:
    """A run folder's protocol.json (format graspmix.experiment/2)."""
    path = Path(run_dir) / PROTOCOL_NAME
    if not path.is_file():
        raise ValueError(f"{run_dir}: no {PROTOCOL_NAME} (not an experiment folder)")
    doc = read_document(path, PROTOCOL_FORMAT)
    try:
        protocol_from_json(doc["protocol"])  # the values, beyond the schema's types
    except ValueError as e:
        raise ValueError(f"{path}: {e}") from None
    return doc
