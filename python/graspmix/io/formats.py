"""JSON documents of graspmix: every file carries a versioned "format" field, checked here, once per
format. The layouts themselves are defined by the types that write them (Demonstration, GraspModel,
Grasp/GraspSet, Protocol, the report's summary)."""
from __future__ import annotations

import json
from pathlib import Path

DEMO_FORMAT = "graspmix.demo/1"
MODEL_FORMAT = "graspmix.model/1"
GRASPS_FORMAT = "graspmix.grasps/1"
PROTOCOL_FORMAT = "graspmix.experiment/1"
SUMMARY_FORMAT = "graspmix.summary/1"
BENCHMARK_FORMAT = "graspmix.benchmark/1"
GMM_FORMAT = "graspmix.gmm/1"

# format -> (what the file is called in messages, whether a file without a "format" field is taken as it)
FORMATS = {
    DEMO_FORMAT: ("demonstration", True),  # hand-written demonstrations may omit it
    MODEL_FORMAT: ("model", False),
    GRASPS_FORMAT: ("grasps", False),
    PROTOCOL_FORMAT: ("protocol", False),
    SUMMARY_FORMAT: ("summary", False),
    BENCHMARK_FORMAT: ("benchmark", False),
    GMM_FORMAT: ("mixture", False),
}


def read_json(path: Path, what: str) -> dict:
    """A JSON object from a file; ValueError naming the file if it is missing, not JSON or not an object."""
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"{path}: no such {what} file")
    try:
        data = json.loads(path.read_text())
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        raise ValueError(f"{path}: not valid JSON ({e})") from None
    if not isinstance(data, dict):
        raise ValueError(f"{path}: expected a JSON object at the top level")
    return data


def check_format(data: dict, fmt: str, path) -> None:
    """The document's "format" field is fmt (or absent, where FORMATS allows it); ValueError otherwise."""
    _, optional = FORMATS[fmt]
    found = data.get("format", fmt if optional else None)
    if found != fmt:
        raise ValueError(f"{path}: format is {found!r}, expected format {fmt!r}")


def read_document(path, fmt: str) -> dict:
    """A graspmix JSON document of the given format, read and checked."""
    what, _ = FORMATS[fmt]
    data = read_json(Path(path), what)
    check_format(data, fmt, path)
    return data


def require_field(data: dict, key: str, path, kind=None):
    """data[key], which must exist (and be of type kind, if given); ValueError naming the file otherwise."""
    if key not in data:
        raise ValueError(f"{path}: missing field '{key}'")
    value = data[key]
    if kind is not None and not isinstance(value, kind):
        raise ValueError(f"{path}: field '{key}' has the wrong type ({type(value).__name__})")
    return value
