"""The case type of the fuzz corpus and what corpus modules share: valid base documents to mutate and
small builders. See test_fuzz.py for the format and how cases are run."""

from __future__ import annotations

import copy
import json
from dataclasses import dataclass, field
from pathlib import Path

from graspmix.experiment import log

DATA = Path(__file__).resolve().parents[3] / "data"  # the source tree's bundled data


@dataclass(frozen=True)
class Case:
    """One input and what graspmix must do with it (see test_fuzz.py)."""

    id: str  # unique over the whole corpus: "<class>/<what>", e.g. "json/grasps/rank-null"
    kind: str  # "cli": argv after graspmix_cli; "api": Python statements (graspmix is imported as graspmix)
    argv: tuple = ()
    code: str = ""
    files: dict = field(default_factory=dict)  # name -> str | bytes, written into the case's folder first
    expect: str = "error"  # "error" (CLI: status 2, one line; API: a ValueError) or "ok"
    names: tuple = ()  # substrings the error line must contain (the file name, the argument)
    timeout: float = 60.0  # s; a case still running then is a hang
    group: str | None = None  # API cases of one group share a subprocess (only for code that reads no file in C++)
    xfail: str = ""  # a known failure someone else owns: why (strict: the test fails once it is fixed)

    def __post_init__(self):
        assert self.kind in ("cli", "api"), self.id
        assert self.expect in ("error", "ok"), self.id
        assert self.kind == "api" or self.group is None, f"{self.id}: only API cases are grouped"


def cli(id: str, *argv, names=(), files=None, expect="error", timeout=60.0) -> Case:
    return Case(id, "cli", argv=tuple(argv), files=files or {}, expect=expect, names=tuple(names), timeout=timeout)


def api(id: str, code: str, names=(), files=None, expect="error", group=None, timeout=60.0, xfail="") -> Case:
    return Case(
        id,
        "api",
        code=code,
        files=files or {},
        expect=expect,
        names=tuple(names),
        group=group,
        timeout=timeout,
        xfail=xfail,
    )


def dumps(doc) -> str:
    return json.dumps(doc)


# ---- valid documents to grow malformed ones from -------------------------------------------------------

HAND = "package://graspmix/hands/wsg50.urdf"
BOX_URDF = str(DATA / "objects" / "box.urdf")
MUG = str(DATA / "mug.pcd")


def demo_doc() -> dict:
    """The bundled box demonstration, with its cloud given by absolute path (the case's folder is elsewhere)."""
    d = json.loads((DATA / "demos" / "box_wsg50.json").read_text())
    d["cloud"] = str(DATA / "demos" / "box.pcd")
    return d


def model_doc(method: str = "gmm") -> dict:
    """The bundled box model (one grasp type), without its demonstration file."""
    d = json.loads((DATA / "models" / f"box_wsg50_{method}.json").read_text())
    d["types"][0]["demonstration"] = None
    return d


def grasps_doc() -> dict:
    """A grasps.json of two WSG 50 top grasps over the bundled box (as synthesize writes them)."""
    g = {
        "rank": 1,
        "T_world_wrist": [0.0, 0.0, 0.1635, 1.0, 0.0, 0.0, 0.0],
        "pregrasp_joints": {"finger_left_joint": 0.05},
        "grasp_joints": {"finger_left_joint": 0.02},
        "log_likelihood": 12.5,
        "optimised": True,
        "experts": {"collision": 0.0, "config": 2.6, "contact/palm": 5.7, "kinematic": 0.0},
    }
    g2 = copy.deepcopy(g)
    g2.update(rank=2, log_likelihood="-inf", optimised=False)
    return {
        "format": "graspmix.grasps/1",
        "hand": HAND,
        "method": "gmm",
        "cloud": "package://graspmix/mug.pcd",
        "timing_s": {"query": 0.05, "sampling": 0.002, "optimisation": 0.02, "features": 0.3, "total": 0.4},
        "grasps": [g, g2],
    }


def protocol_doc() -> dict:
    """A protocol.json of a small run (2 objects of the test set, 2 trials, conditions A and D)."""
    return {
        "format": "graspmix.experiment/2",
        "protocol": {
            "objects": ["random_urdfs/000/000.urdf", "random_urdfs/001/001.urdf"],
            "trials": 2,
            "conditions": ["A", "D"],
            "methods": ["gmm", "kde"],
            "pixel_noise_std": 1.0,
            "depth_noise_std": 0.001,
            "views": 4,
            "cloud": "object",
            "synthesis": {"sampling": {"n_samples": 200, "n_optimise": 10}, "approach": None, "contact_quality": None},
            "closing": "full",
            "seed": 0,
            "models": {},
        },
        "provenance": {"graspmix": "0", "commit": None},
    }


COLUMNS = log.COLUMNS  # the experiment's CSV columns, as the runner writes them


def attempts_csv(edit=None) -> str:
    """attempts.csv of protocol_doc()'s run, every attempt done; edit(row index, row dict) may change rows."""
    p = protocol_doc()["protocol"]
    lines = [",".join(COLUMNS)]
    i = 0
    for o in p["objects"]:
        for t in range(p["trials"]):
            for c in p["conditions"]:
                for m in p["methods"]:
                    s = (i * 7 + 3) % 5 < 3
                    row = {
                        "object": o,
                        "trial": t,
                        "condition": c,
                        "method": m,
                        "noise": int(c == "D"),
                        "optimise": int(c == "A"),
                        "acquisition_seed": 1,
                        "synthesis_seed": 2,
                        "n_points": 100,
                        "success": int(s),
                        "reason": "success" if s else "not held",
                        "lift_height": 0.2,
                        "contact_count": 2,
                        "log_likelihood": -1.0,
                        "grasp": "",
                        "evaluations": 10,
                        "rejected": 0,
                        "error": "",
                        "t_acquisition": 0.1,
                        "t_features": 0.01,
                        "t_query": 0.01,
                        "t_sampling": 0.02,
                        "t_optimisation": 0.03,
                        "t_synthesis": 0.1,
                        "t_execution": 0.02,
                    }
                    if edit is not None:
                        edit(i, row)
                    lines.append(",".join(str(row[k]) for k in COLUMNS))
                    i += 1
    return "\n".join(lines) + "\n"


def run_folder(protocol=None, csv=None) -> dict:
    """The files of an experiment folder "run/" (protocol.json and attempts.csv) for a case's `files`."""
    return {
        "run/protocol.json": protocol if protocol is not None else dumps(protocol_doc()),
        "run/attempts.csv": csv if csv is not None else attempts_csv(),
    }


def set_path(doc, path: tuple, value):
    """doc with the value at path (keys and indices) replaced (or added); a deep copy."""
    out = copy.deepcopy(doc)
    node = out
    for k in path[:-1]:
        node = node[k]
    node[path[-1]] = value
    return out


def del_path(doc, path: tuple):
    out = copy.deepcopy(doc)
    node = out
    for k in path[:-1]:
        node = node[k]
    del node[path[-1]]
    return out
