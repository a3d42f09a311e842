"""Grasps: one Grasp (the layout of an entry of grasps.json, defined here and nowhere else), the ranked
GraspSet a synthesis returns, and grasps.json itself (format graspmix.grasps/1).

A Grasp is a dataclass that also reads like the dictionary it is written as, so code written for the
dictionaries keeps working: ``grasps.best()["T_world_wrist"]``, ``dict(grasp)``, ``grasp["experts"]``.
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping, MutableMapping
from dataclasses import dataclass, field, fields
from pathlib import Path

import numpy as np

from ..io import GRASPS_FORMAT, read_document, relative_path
from ..io.checks import check_int, check_output_path

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


@dataclass(eq=False)
class Grasp(MutableMapping):
    """One grasp in the world frame (the cloud's): the wrist pose [x, y, z, qx, qy, qz, qw], the pre-grasp
    and grasp joints (name -> value), and, for a synthesised grasp, its rank (1 = best), log-likelihood,
    whether annealing moved it, the object of the scene it is on, its grasp type, and every expert's log value ("collision", "config", "pregrasp_clear",
    "contact/<link>", constraint names). Fields a newer writer adds are kept in `extra`."""

    T_world_wrist: list
    pregrasp_joints: dict
    grasp_joints: dict
    rank: int | None = None
    log_likelihood: float | None = None
    optimised: bool | None = None
    experts: dict | None = None
    object: dict | None = None  # the segmented object it is on: {"index": i, "centroid": [x, y, z]}
    type: str | None = None  # the grasp type (the model's demonstration) it was sampled from
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
        "type",
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
        for k in ("pregrasp_joints", "grasp_joints", "experts", "object"):
            if isinstance(known.get(k), Mapping):
                known[k] = dict(known[k])
        return cls(**known, extra={k: v for k, v in d.items() if k not in cls.KEYS})

    # -- the dictionary view (grasps.json's keys)
    def __getitem__(self, key):
        if key in self.KEYS:
            value = getattr(self, key)
            if value is None:
                raise KeyError(key)
            return value
        return self.extra[key]

    def __setitem__(self, key, value):
        if key in self.KEYS:
            setattr(self, key, value)
        else:
            self.extra[key] = value

    def __delitem__(self, key):
        if key in EXECUTION_KEYS:
            raise KeyError(f"{key!r} is required in a grasp")
        if key in self.KEYS:
            if getattr(self, key) is None:
                raise KeyError(key)
            setattr(self, key, None)
        else:
            del self.extra[key]

    def __iter__(self):
        return iter(self.to_dict())

    def __len__(self):
        return len(self.to_dict())

    def __repr__(self):
        body = ", ".join(
            f"{f.name}={getattr(self, f.name)!r}"
            for f in fields(self)
            if getattr(self, f.name) not in (None, {}) or f.name in EXECUTION_KEYS
        )
        return f"Grasp({body})"


def grasps_from_result(result, hand) -> list[Grasp]:
    """The Grasps of a C++ synthesis result, best first, with every expert's log value by name."""
    grasps = []
    for rank, g in enumerate(result.grasps, start=1):
        experts = {"collision": g["log_collision"], "config": g["log_config"], "pregrasp_clear": g["log_pregrasp"]}
        experts.update({f"contact/{n}": float(v) for n, v in zip(result.contact_links, g["log_contact"])})
        experts.update({n: float(v) for n, v in zip(result.expert_names, g["log_experts"])})
        grasps.append(
            Grasp(
                T_world_wrist=[float(x) for x in g["T_world_wrist"]],
                pregrasp_joints=hand.joints_dict(g["pregrasp"]),
                grasp_joints=hand.joints_dict(g["joints"]),
                rank=rank,
                log_likelihood=float(g["log_likelihood"]),
                optimised=bool(g["optimised"]),
                experts={k: float(v) for k, v in experts.items()},
            )
        )
    return grasps


@dataclass
class GraspSet:
    """Synthesised grasps, best first, as written to grasps.json."""

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

    def __len__(self):
        return len(self.grasps)

    def __getitem__(self, i):
        return self.grasps[i]

    def best(self) -> Grasp:
        return self.grasps[0]

    def to_json(self, base: Path | None = None) -> dict:
        """The grasps.json content; paths are written relative to `base` (the file's folder) when given."""
        hand, cloud = str(self.hand_path), self.cloud
        if base is not None:
            hand = relative_path(self.hand_path, base)
            if Path(cloud).exists():
                cloud = relative_path(Path(cloud), base)
        return {
            "format": GRASPS_FORMAT,
            "hand": hand,
            "method": self.method,
            "cloud": cloud,
            "timing_s": self.timing,
            "grasps": [_as_dict(g) for g in self.grasps],
        }

    def save(self, path: str | Path) -> None:
        # Non-finite log values (a grasp a hard expert rejected) are written as the strings "-inf"/"inf".
        path = check_output_path(path, "grasps file")
        path.write_text(json.dumps(_json_safe(self.to_json(path.resolve().parent)), indent=1) + "\n")


def _as_dict(g) -> dict:
    return g.to_dict() if isinstance(g, Grasp) else dict(g)


def _json_safe(x):
    if isinstance(x, float) and not math.isfinite(x):
        return None if math.isnan(x) else ("-inf" if x < 0 else "inf")
    if isinstance(x, dict):
        return {k: _json_safe(v) for k, v in x.items()}
    if isinstance(x, list):
        return [_json_safe(v) for v in x]
    return x


def load_grasps(path) -> dict:
    """Reads and checks a grasps.json (format graspmix.grasps/1). The document comes back as read, its
    grasps (dictionaries, as in the file; a missing rank is the position) sorted by rank."""
    doc = read_document(path, GRASPS_FORMAT)
    grasps = doc.get("grasps")
    if not isinstance(grasps, list) or not grasps:
        raise ValueError(f"{path}: no grasps")
    entries = []
    for i, g in enumerate(grasps):
        if not isinstance(g, Mapping):
            raise ValueError(f"{path}: grasp {i} is not an object")
        entry = Grasp.from_dict(g, where=f"{path}: grasp {i}").to_dict()
        entry.setdefault("rank", i + 1)
        entries.append(entry)
    doc["grasps"] = sorted(entries, key=lambda g: g["rank"])
    return doc


def grasp_by_rank(doc: Mapping, rank: int = 1):
    """The grasp of the given rank of a loaded grasps.json (or a GraspSet)."""
    grasps = doc["grasps"] if isinstance(doc, Mapping) else doc.grasps
    rank = check_int(rank, "rank", 1)
    for g in grasps:
        if g["rank"] == rank:
            return g
    raise ValueError(f"no grasp of rank {rank} (ranks {grasps[0]['rank']}..{grasps[-1]['rank']})")
