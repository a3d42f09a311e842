"""Grasps: one Grasp (the layout of an entry of grasps.json, defined here and nowhere else), the ranked
GraspSet a synthesis returns, and grasps.json itself (format graspmix.grasps/1).

A Grasp is read by its attributes (``grasps.best().T_world_wrist``, ``grasp.experts["collision"]``); its
file form is ``to_dict()`` and ``Grasp.from_dict``.
"""

from __future__ import annotations

import contextlib
import importlib
import json
import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from pathlib import Path

import numpy as np

from .. import _core
from ..io import GRASPS_FORMAT, check_digest, read_document, relative_path, resolve_path
from ..io.checks import check_int, check_output_path
from .grasp_frames import FRAME_KEYS, FrameMaker, GraspFrameSettings

# What executing a grasp needs; the other fields describe how it was ranked.
EXECUTION_KEYS = ("T_world_wrist", "pregrasp_joints", "grasp_joints")
# The stages of a synthesis' timing that the paper's Fig. runtime shows (timing_s also has "features" and
# "total").
STAGES = ("query", "sampling", "optimisation")
STAGE_LABELS = {
    "query": "query density estimation",
    "sampling": "sampling and ranking",
    "optimisation": "optimising the top 10",
}


@dataclass
class Grasp:
    """One grasp in the world frame (the cloud's): the wrist pose [x, y, z, qx, qy, qz, qw], the pre-grasp
    and grasp joints (name -> value), and, for a synthesised grasp, its rank (1 = best), log-likelihood,
    whether annealing moved it, the object of the scene it is on, its grasp type, and every expert's log value ("collision", "config", "pregrasp_clear",
    "contact/<link>", constraint names). Fields a newer writer adds are kept in `extra`.

    What a robot stack needs (graspmix.model.grasp_frames; GraspSet fills them in from its hand):
    T_world_wrist_matrix (4x4, nested lists), T_world_tcp (the tool centre point between the fingertips,
    oriented like the wrist), approach and closing (world unit vectors), opening_width (m, two-finger
    hands), T_world_pregrasp and T_world_retreat (the wrist backed off along the approach)."""

    T_world_wrist: list
    pregrasp_joints: dict
    grasp_joints: dict
    rank: int | None = None
    log_likelihood: float | None = None
    optimised: bool | None = None
    experts: dict | None = None
    object: dict | None = None  # the segmented object it is on: {"index": i, "centroid": [x, y, z]}
    type: str | None = None  # the grasp type (the model's demonstration) it was sampled from
    T_world_wrist_matrix: list | None = None  # 4x4 homogeneous matrix of T_world_wrist
    T_world_tcp: list | None = None  # [x, y, z, qx, qy, qz, qw]
    approach: list | None = None  # (3,) world
    closing: list | None = None  # (3,) world, two-finger hands
    opening_width: float | None = None  # m, two-finger hands
    T_world_pregrasp: list | None = None
    T_world_retreat: list | None = None
    extra: dict = field(default_factory=dict)

    # Key order of a grasps.json entry.
    KEYS = (
        "rank",
        "T_world_wrist",
        "pregrasp_joints",
        "grasp_joints",
        "log_likelihood",
        "optimised",
        "experts",
        "object",  # added after the first release's keys, so their order stays what it was
        "type",  # the grasp type (after "object": both came after the first release)
        *FRAME_KEYS,  # what a robot stack needs (grasp_frames), after them
    )

    def to_dict(self, *, execution_only: bool = False) -> dict:
        """The grasps.json entry; execution_only: just T_world_wrist, pregrasp_joints and grasp_joints."""
        keys = EXECUTION_KEYS if execution_only else self.KEYS
        out = {k: getattr(self, k) for k in keys if getattr(self, k) is not None}
        if not execution_only:
            out.update(self.extra)
        return out

    @classmethod
    def from_dict(cls, d: Mapping, where: str = "grasp") -> "Grasp":
        """A grasps.json entry (or any mapping with at least T_world_wrist, pregrasp_joints, grasp_joints).
        Values are kept as given (lists and dicts copied), so from_dict(d).to_dict() == d."""
        for key in EXECUTION_KEYS:
            if key not in d:
                raise ValueError(f"{where} has no {key!r}")
        known = {k: d[k] for k in cls.KEYS if k in d}
        for k in ("T_world_wrist",):
            known[k] = list(known[k]) if not isinstance(known[k], str) else known[k]
        for k in FRAME_KEYS:
            if isinstance(known.get(k), (list, tuple)):
                known[k] = [list(r) if isinstance(r, (list, tuple)) else r for r in known[k]]
        for k in ("pregrasp_joints", "grasp_joints", "experts", "object"):
            if isinstance(known.get(k), Mapping):
                known[k] = dict(known[k])
        return cls(**known, extra={k: v for k, v in d.items() if k not in cls.KEYS})

    def __repr__(self):
        body = ", ".join(
            f"{f.name}={getattr(self, f.name)!r}"
            for f in fields(self)
            if getattr(self, f.name) not in (None, {}) or f.name in EXECUTION_KEYS
        )
        return f"Grasp({body})"


def check_grasp(grasp, what: str = "grasp") -> Grasp:
    """grasp, which must be a Grasp (Grasp.from_dict reads a grasps.json entry); ValueError naming `what` else."""
    if not isinstance(grasp, Grasp):
        raise ValueError(
            f"{what}: expected a Grasp (Grasp.from_dict reads a grasps.json entry), got {type(grasp).__name__}"
        )
    return grasp


def grasps_from_columns(columns: dict, term_names: list, hand, objects: list, types: list) -> list[Grasp]:
    """The Grasps of a scene synthesis, best first (_core.SceneSynthesis.columns(): one array a field, turned into
    Python numbers in bulk), each with every term of its log L by name (term_names[its type]), its object
    (objects[its object index]: {"index", "centroid"}) and its type's name (types[its type index])."""
    c = {
        k: np.asarray(columns[k]).tolist()
        for k in ("T_world_wrist", "joints", "pregrasp", "log_likelihood", "optimised", "object", "type")
    }
    terms = columns["log_terms"]
    names = sorted(enumerate(hand.joint_names), key=lambda j: j[1])  # by name, as Hand.joints_dict orders them
    grasps = []
    for i, wrist in enumerate(c["T_world_wrist"]):
        k = c["type"][i]
        grasps.append(
            Grasp(
                T_world_wrist=wrist,
                pregrasp_joints={n: c["pregrasp"][i][j] for j, n in names},
                grasp_joints={n: c["joints"][i][j] for j, n in names},
                rank=i + 1,
                log_likelihood=c["log_likelihood"][i],
                optimised=c["optimised"][i],
                experts=dict(zip(term_names[k], terms[i])),
                object=objects[c["object"][i]],
                type=types[k],
            )
        )
    return grasps


class NoFeasibleGraspWarning(UserWarning):
    """Every grasp a synthesis returned was rejected by a hard expert (collision, kinematics, the clear approach, a
    caller's reachability test): GraspSet.best() is then the least bad of them, not a grasp to execute."""


# What may help when no grasp passed, in the settings' words (GraspSet.no_feasible_message).
NO_FEASIBLE_ADVICE = (
    "the grasps are the least bad, not grasps to execute. More samples (sampling.n_samples, "
    "sampling.max_sampling_rounds) or another seed may find one; with the occupancy collision model the cloud must "
    "hold the table around the objects (a whole depth image), or the space beside them is unseen and counts as solid"
)


def _passed(g: Grasp) -> bool:
    """Whether a grasp passed every hard expert (its log-likelihood is finite)."""
    return g.log_likelihood is not None and math.isfinite(g.log_likelihood)


@contextlib.contextmanager
def infeasible_unwarned():
    """A block in which NoFeasibleGraspWarning is not shown: for callers that report it themselves (the CLI) or
    record every attempt's outcome by protocol (the experiment and clutter runs execute the best grasp whatever it
    scored)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", NoFeasibleGraspWarning)
        yield


# The grasp pictures are drawn by graspmix.viz, a higher layer: it registers its drawing function here when
# it is imported (GraspSet.plot imports it when it has not been), so this layer needs nothing from it.
_PLOTTER: list = []


def register_grasp_plotter(plot) -> None:
    """Sets the function GraspSet.plot calls: plot(grasp_set, path, cloud=..., **options)."""
    _PLOTTER[:] = [plot]


@dataclass
class GraspSet:
    """Synthesised grasps, best first, as written to grasps.json (GraspSet.load reads one back).

    Every Grasp gets the frames a robot stack needs from the hand (grasp_frames; ``frame_settings`` says
    how): per grasp as its fields, for the whole set as (N, ...) arrays (``tcp_poses``, ``wrist_matrices``,
    ``approaches``, ``closings``, ``opening_widths``, ``pregrasp_poses``, ``retreat_poses``)."""

    grasps: list  # of Grasp
    hand_path: Path
    method: str
    cloud: str
    timing: dict
    surface: object = None  # the target objects' SurfaceCloud (a SurfaceUnion of several)
    plane: np.ndarray | None = None  # the support plane, oriented towards the cameras
    evaluations: int = 0
    rejected: int = 0
    scene: object = None  # the segmented scene (graspmix.Scene)
    targets: list = field(default_factory=list)  # indices of the objects grasps were sampled on
    frame_settings: GraspFrameSettings = field(default_factory=GraspFrameSettings)
    fingertips: list = field(default_factory=list)  # the fingertip links the frames were made with
    hand: object = None  # the graspmix.Hand of hand_path (read when first needed)
    # the depth image file the grasps were synthesised on, as synthesize(depth=...) read it: {"depth": path,
    # "intrinsics": [fx, fy, cx, cy], "depth_scale": metres per unit or None, "camera_pose": [x, y, z, qx, qy, qz, qw],
    # "sha256": the file's}
    view: dict | None = None
    cloud_sha256: str = ""  # of the cloud file (`cloud`) the grasps were synthesised on; "" for no file

    def __post_init__(self):
        for i, g in enumerate(self.grasps):
            check_grasp(g, f"grasps[{i}]")
        if any(g.T_world_wrist_matrix is None for g in self.grasps):
            self.add_frames()

    def __len__(self):
        return len(self.grasps)

    def __getitem__(self, i):
        return self.grasps[i]

    def best(self) -> Grasp:
        """The first grasp (check ``n_feasible``: when it is 0, it is the least bad of grasps every one of which a
        hard expert rejected)."""
        return self.grasps[0]

    @property
    def n_feasible(self) -> int:
        """How many grasps passed every hard expert (a finite log-likelihood); they come first."""
        return sum(1 for g in self.grasps if _passed(g))

    def rejections(self) -> dict:
        """{hard expert: how many grasps it rejected first} (its order in each grasp's experts table) for the
        grasps that did not pass; {} when every grasp passed."""
        first: dict = {}
        for g in self.grasps:
            if not _passed(g):
                name = next((k for k, v in (g.experts or {}).items() if v == -math.inf), "?")
                first[name] = first.get(name, 0) + 1
        return dict(sorted(first.items(), key=lambda kv: -kv[1]))

    def no_feasible_message(self, advice: str = NO_FEASIBLE_ADVICE) -> str:
        """Why no grasp passed (the experts that rejected them, rejections()), then `advice`: what may help, in the
        caller's words (the default: the settings; the CLI names its flags). The text of NoFeasibleGraspWarning."""
        why = ", ".join(f"{k} {n}" for k, n in self.rejections().items())
        return f"no sampled grasp passed the hard experts (rejected first by: {why}); {advice}"

    def get_hand(self):
        """The graspmix.Hand of hand_path, read once."""
        if self.hand is None:
            self.hand = _core.Hand.from_urdf(str(self.hand_path))
        return self.hand

    def add_frames(self, settings: GraspFrameSettings | None = None) -> None:
        """(Re)computes every Grasp's frames (T_world_wrist_matrix, T_world_tcp, approach, closing,
        opening_width, T_world_pregrasp, T_world_retreat) from the hand at its grasp joints; call it again
        after moving a grasp. settings: how (default: frame_settings)."""
        self.frame_settings = (settings or self.frame_settings).checked()
        rows = self.grasps
        if not rows:
            return
        hand = self.get_hand()
        maker = FrameMaker(hand, self.frame_settings)
        self.frame_settings, tips = maker.settings, maker.tips  # the hand's axis and fingertips made explicit
        wrists = np.array([g.T_world_wrist for g in rows], dtype=float)
        joints = np.array([hand.joints_array(g.grasp_joints) for g in rows], dtype=float)
        for g, f in zip(rows, maker.frames(wrists, joints)):
            for k, v in f.items():
                setattr(g, k, v)
        self.fingertips = tips

    def _column(self, key: str) -> np.ndarray:
        return np.array([np.nan if getattr(g, key) is None else getattr(g, key) for g in self.grasps], dtype=float)

    @property
    def wrist_matrices(self) -> np.ndarray:
        """(N, 4, 4) T_world_wrist as homogeneous matrices."""
        return np.array([g.T_world_wrist_matrix for g in self.grasps], dtype=float).reshape(-1, 4, 4)

    @property
    def tcp_poses(self) -> np.ndarray:
        """(N, 7) T_world_tcp (NaN rows for a hand without fingertip links)."""
        return np.array([g.T_world_tcp or [np.nan] * 7 for g in self.grasps], dtype=float).reshape(-1, 7)

    @property
    def approaches(self) -> np.ndarray:
        """(N, 3) approach directions (world, unit)."""
        return np.array([g.approach for g in self.grasps], dtype=float).reshape(-1, 3)

    @property
    def closings(self) -> np.ndarray:
        """(N, 3) closing directions (world, unit; NaN unless the hand has two fingertip links)."""
        return np.array([g.closing or [np.nan] * 3 for g in self.grasps], dtype=float).reshape(-1, 3)

    @property
    def opening_widths(self) -> np.ndarray:
        """(N,) opening widths in m (NaN unless the hand has two fingertip links)."""
        return self._column("opening_width")

    @property
    def pregrasp_poses(self) -> np.ndarray:
        """(N, 7) T_world_pregrasp: the wrist frame_settings.pregrasp_distance back along the approach."""
        return np.array([g.T_world_pregrasp for g in self.grasps], dtype=float).reshape(-1, 7)

    @property
    def retreat_poses(self) -> np.ndarray:
        """(N, 7) T_world_retreat: the wrist frame_settings.retreat_distance back along the approach."""
        return np.array([g.T_world_retreat for g in self.grasps], dtype=float).reshape(-1, 7)

    def to_json(self, base: Path | None = None) -> dict:
        """The grasps.json content; paths are written relative to `base` (the file's folder) when given."""
        hand, cloud = str(self.hand_path), self.cloud
        if base is not None:
            hand = relative_path(self.hand_path, base)
            cloud = _relative(cloud, base)
        return {
            "format": GRASPS_FORMAT,
            "hand": hand,
            "method": self.method,
            "cloud": cloud,
            "timing_s": self.timing,
            "grasps": [g.to_dict() for g in self.grasps],
            # Added after the first release's keys: what GraspSet.load and plot need again.
            "plane": None if self.plane is None else [float(v) for v in self.plane],
            "evaluations": int(self.evaluations),
            "rejected": int(self.rejected),
            "targets": [int(t) for t in self.targets],
            "frames": {**self.frame_settings.to_json(), "fingertip_links": list(self.fingertips)},
            **({} if self.view is None else {"view": {**self.view, "depth": _relative(self.view["depth"], base)}}),
            **({"cloud_sha256": self.cloud_sha256} if self.cloud_sha256 else {}),
        }

    def save(self, path: str | Path) -> None:
        # Non-finite log values (a grasp a hard expert rejected) are written as the strings "-inf"/"inf".
        path = check_output_path(path, "grasps file")
        doc = self.to_json(path.resolve().parent)
        for g in doc["grasps"]:  # where a hard expert's -inf lives: made safe first, the rest only if needed
            for key in ("log_likelihood", "experts"):
                if key in g:
                    g[key] = _json_safe(g[key])
        try:
            text = _dumps_entries_one_line(doc, "grasps", allow_nan=False)
        except ValueError:  # a non-finite number elsewhere (e.g. a user's extra field)
            text = _dumps_entries_one_line(_json_safe(doc), "grasps")
        path.write_text(text)

    @classmethod
    def load(cls, path: str | Path) -> "GraspSet":
        """A grasps.json (format graspmix.grasps/1) back as a GraspSet: its grasps (by rank), hand, method,
        cloud (resolved against the file's folder), timing, support plane, counts and frames. A file
        without frames (an older writer) gets them from its hand."""
        doc = load_grasps(path)
        base = Path(path).resolve().parent
        cloud = doc.get("cloud", "")
        if cloud and not cloud.startswith("<"):  # "<array>" and the like name no file
            cloud = str(resolve_path(cloud, base))
        if not doc.get("hand"):
            raise ValueError(f"{path}: names no hand")
        frames = doc.get("frames") or {}
        known = {f.name for f in fields(GraspFrameSettings)}  # the axis and fingertips the frames were made with
        settings = GraspFrameSettings(
            **{k: tuple(v) if isinstance(v, list) else v for k, v in frames.items() if k in known}
        )
        plane = doc.get("plane")
        view = doc.get("view")
        if view is not None:
            view = {**view, "depth": str(resolve_path(view["depth"], base))}
        return cls(
            doc["grasps"],
            resolve_path(doc["hand"], base),
            doc.get("method", ""),
            cloud,
            dict(doc.get("timing_s", {})),
            plane=None if plane is None else np.asarray(plane, dtype=float),
            evaluations=int(doc.get("evaluations", 0)),
            rejected=int(doc.get("rejected", 0)),
            targets=list(doc.get("targets", [])),
            frame_settings=settings.checked(),
            fingertips=list(frames.get("fingertip_links", [])),
            view=view,
            cloud_sha256=str(doc.get("cloud_sha256", "")),
        )

    def view_points(self) -> np.ndarray | None:
        """(N, 3) the objects' points (world frame) of the depth image the grasps were synthesised on (`view`), read
        again from its file (ValueError when the file changed since) and segmented on the set's support plane (the
        library's default segmentation); None without a view."""
        if self.view is None:
            return None
        from ..perception.views import depth_view, segment_view

        v = self.view
        check_digest(v["depth"], v.get("sha256"), "depth image")
        view = depth_view(v["depth"], v["intrinsics"], v["camera_pose"], v["depth_scale"])
        return np.asarray(segment_view(view, self.plane).points, dtype=float)

    def plot(self, path: str | Path | None = None, cloud=None, **options):
        """Draws the cloud (cloud: a path or (N, 3) points; default: the synthesis' scene, else the file's
        cloud if it exists, else none), the support plane as a patch when known, and the hands of the best
        `top` grasps as their links' collision shapes at their poses and grasp joints.
        path: .html -> an interactive, self-contained 3D view (plotly); .png/.pdf/.svg -> a picture
        (matplotlib); None -> the matplotlib Figure. Options: graspmix.viz.plot_grasps'."""
        if not _PLOTTER:  # the pictures' layer registers its plotter when it is first imported
            importlib.import_module("graspmix.viz")
        return _PLOTTER[0](self, path, cloud=cloud, **options)


def _relative(name: str, base: Path) -> str:
    """A file name written relative to `base` when it names an existing file (as given otherwise: "" or "<array>")."""
    return relative_path(Path(name), base) if name and Path(name).exists() else name


def _dumps_entries_one_line(doc: dict, key: str, allow_nan: bool = True) -> str:
    """The text of json.dumps(doc, indent=1) with each entry of the list doc[key] on a line of its own: still
    readable, and written by json's C encoder (given an indent, json encodes in Python: ~10 times slower,
    0.1 s for 200 grasps)."""
    marker = "\0entries\0"  # no JSON value of the document (paths, names, numbers) holds a NUL
    text = json.dumps({**doc, key: marker}, indent=1, allow_nan=allow_nan)
    entries = ",\n  ".join(json.dumps(e, allow_nan=allow_nan) for e in doc[key])
    return text.replace(json.dumps(marker), f"[\n  {entries}\n ]" if entries else "[]", 1) + "\n"


def _json_safe(x):
    if isinstance(x, float) and not math.isfinite(x):
        return None if math.isnan(x) else ("-inf" if x < 0 else "inf")
    if isinstance(x, dict):
        return {k: _json_safe(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_json_safe(v) for v in x]
    return x


def _from_json_safe(x) -> float:
    """A log value as _json_safe wrote it ("-inf", "inf", null for NaN, or a number) as a float."""
    return math.nan if x is None else float(x)


def load_grasps(path) -> dict:
    """Reads and checks a grasps.json (format graspmix.grasps/1). The document comes back as read, but for
    its grasps: Grasp objects sorted by rank (a missing rank is the position), their log values numbers
    again (save() writes non-finite ones as "-inf", "inf" and null)."""
    doc = read_document(path, GRASPS_FORMAT)
    grasps = doc.get("grasps")
    if not isinstance(grasps, list) or not grasps:
        raise ValueError(f"{path}: no grasps")
    entries = []
    for i, g in enumerate(grasps):
        if not isinstance(g, Mapping):
            raise ValueError(f"{path}: grasp {i} is not an object")
        entry = Grasp.from_dict(g, where=f"{path}: grasp {i}")
        if entry.rank is None:
            entry.rank = i + 1
        if entry.log_likelihood is not None:
            entry.log_likelihood = _from_json_safe(entry.log_likelihood)
        if entry.experts is not None:
            entry.experts = {k: _from_json_safe(v) for k, v in entry.experts.items()}
        entries.append(entry)
    doc["grasps"] = sorted(entries, key=lambda g: g.rank)
    return doc


def grasp_by_rank(doc: Mapping, rank: int = 1):
    """The grasp of the given rank of a loaded grasps.json (or a GraspSet)."""
    grasps = doc["grasps"] if isinstance(doc, Mapping) else doc.grasps
    rank = check_int(rank, "rank", 1)
    for g in grasps:
        if g.rank == rank:
            return g
    raise ValueError(f"no grasp of rank {rank} (ranks {grasps[0].rank}..{grasps[-1].rank})")
