"""One demonstrated grasp and its file (format graspmix.demo/1)."""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import _core
from ..io import DEMO_FORMAT, read_document, relative_path, require_field, resolve_path
from ..io.checks import check_input_file, check_output_path, check_path_text

# How graspmix.sim.demonstration records one (here so the command line's defaults need no simulator).
DEMO_GRIP_FORCE = 20.0  # N (N m): the demonstrating hand's motor force limit (execution's SimSettings: 40)
DEMO_MAX_STEPS = 2000  # simulation steps (240 Hz) the closing fingers get to come to rest


@dataclass
class Demonstration:
    """One demonstrated grasp: a hand, the object's cloud, the wrist pose and the pre-grasp/grasp joints."""

    hand_path: Path
    cloud: np.ndarray
    T_world_wrist: np.ndarray
    pregrasp_joints: dict
    grasp_joints: dict
    cloud_path: Path | None = None
    source: Path | None = None

    @classmethod
    def load(cls, path: str | Path) -> "Demonstration":
        path = check_path_text(path, "demonstration")
        data = read_document(path, DEMO_FORMAT)
        base = path.resolve().parent
        hand = resolve_path(require_field(data, "hand", path, str), base)
        cloud, cloud_path = _cloud(require_field(data, "cloud", path), base, path)
        wrist = np.asarray(require_field(data, "T_world_wrist", path, list), dtype=float)
        if wrist.shape != (7,) or not np.all(np.isfinite(wrist)):
            raise ValueError(f"{path}: 'T_world_wrist' must be 7 finite numbers [x, y, z, qx, qy, qz, qw]")
        pre = require_field(data, "pregrasp_joints", path, dict)
        grasp = require_field(data, "grasp_joints", path, dict)
        return cls(hand, cloud, wrist, pre, grasp, cloud_path, path.resolve())

    def save(self, path: str | Path, inline_cloud: bool = False) -> None:
        path = check_output_path(path, "demonstration file")
        base = path.resolve().parent
        data = {"format": DEMO_FORMAT, "hand": relative_path(self.hand_path, base)}
        if inline_cloud or self.cloud_path is None:
            data["cloud"] = np.round(self.cloud, 6).tolist()
        else:
            data["cloud"] = relative_path(self.cloud_path, base)
        data["T_world_wrist"] = [float(x) for x in self.T_world_wrist]
        data["pregrasp_joints"] = {k: float(v) for k, v in self.pregrasp_joints.items()}
        data["grasp_joints"] = {k: float(v) for k, v in self.grasp_joints.items()}
        path.write_text(json.dumps(data, indent=1) + "\n")


def _cloud(value, base: Path, path: Path):
    """(points, path or None) of a demonstration's "cloud": a file path or inline [x, y, z] rows."""
    if isinstance(value, str):
        try:
            cloud_path = check_input_file(resolve_path(value, base), "cloud")
        except ValueError as e:
            raise ValueError(f"{path}: 'cloud': {e}") from None
        return _core.load_cloud(str(cloud_path)).points, cloud_path
    cloud = np.asarray(value, dtype=float)
    if cloud.ndim != 2 or cloud.shape[1] != 3 or len(cloud) == 0:
        raise ValueError(f"{path}: inline 'cloud' must be a non-empty list of [x, y, z]")
    return cloud, None
