"""JSON documents of graspmix: every file carries a versioned "format" field, checked here, once per
format, and its content is checked against the format's schema (SCHEMAS, one per format) before any
reader looks at a field. The layouts are written by the types that write them (Demonstration, GraspModel,
Grasp/GraspSet, Protocol, the report's summary, the benchmark, fit-gmm); a schema states what a reader
relies on (types, shapes, finiteness), and allows fields a newer writer adds."""

from __future__ import annotations

import json
from pathlib import Path

from .checks import check_input_file, quote
from .schema import Any, Arr, Bool, Either, Int, Map, Null, Num, Obj, Str, Tagged, Tensor, validate

DEMO_FORMAT = "graspmix.demo/1"
MODEL_FORMAT = "graspmix.model/2"  # grasp types (a "types" list)
GRASPS_FORMAT = "graspmix.grasps/1"
PROTOCOL_FORMAT = "graspmix.experiment/2"  # the synthesis as SynthesisOptions (a "synthesis" object)
SUMMARY_FORMAT = "graspmix.summary/2"
BENCHMARK_FORMAT = "graspmix.benchmark/1"
GMM_FORMAT = "graspmix.gmm/1"
SCENE_FORMAT = "graspmix.scene/1"
CLUTTER_FORMAT = "graspmix.clutter/2"
CLUTTER_SUMMARY_FORMAT = "graspmix.clutter_summary/2"

# format -> (what the file is called in messages, whether a file without a "format" field is taken as it)
FORMATS = {
    DEMO_FORMAT: ("demonstration", True),  # hand-written demonstrations may omit it
    MODEL_FORMAT: ("model", False),
    GRASPS_FORMAT: ("grasps", False),
    PROTOCOL_FORMAT: ("protocol", False),
    SUMMARY_FORMAT: ("summary", False),
    BENCHMARK_FORMAT: ("benchmark", False),
    GMM_FORMAT: ("mixture", False),
    SCENE_FORMAT: ("scene", False),
    CLUTTER_FORMAT: ("clutter protocol", False),
    CLUTTER_SUMMARY_FORMAT: ("clutter summary", False),
}


# ---- the schemas ----------------------------------------------------------------------------------
_COUNT = Int(lo=0)
_POSITIVE = Num(gt=0.0)
_NONNEGATIVE = Num(lo=0.0)
_POSE = Tensor(1, (7,), "7 finite numbers [x, y, z, qx, qy, qz, qw]")
_JOINTS = Map(Num(), "an object of joint name -> finite number")
_VECTOR = Tensor(1)
# grasps.json writes the log value of a grasp a hard expert rejected as "-inf" (and NaN as null).
_LOG = Num(also=("-inf", "inf", None))

_DEMO = Obj(
    {
        "format": Str(),
        "hand": Str(nonempty=True),
        "cloud": Either(
            Str(nonempty=True),
            Tensor(2, (None, 3), "a file name or a non-empty list of [x, y, z] rows of finite numbers"),
        ),
        "T_world_wrist": _POSE,
        "pregrasp_joints": _JOINTS,
        "grasp_joints": _JOINTS,
    },
    required=["hand", "cloud", "T_world_wrist", "pregrasp_joints", "grasp_joints"],
)

_GMM_DENSITY = Obj(
    {"kind": Str(), "reference": _VECTOR, "weights": _VECTOR, "means": Tensor(2), "covariances": Tensor(3)},
    required=["reference", "weights", "means", "covariances"],
)
_KDE_DENSITY = Obj(
    {
        "kind": Str(),
        "position_bandwidth": _POSITIVE,
        "orientation_bandwidth": _POSITIVE,
        "feature_bandwidth": Tensor(1),
        "poses": Tensor(2, (None, 7)),
        "features": Tensor(2),
        "weights": _VECTOR,
    },
    required=["position_bandwidth", "orientation_bandwidth", "feature_bandwidth", "poses", "features", "weights"],
)
_CONFIG_SETTINGS = Obj(
    {"beta": Num(), "n_kernels": Int(lo=1, hi=1_000_000), "alpha": Num(), "bandwidth": Num(), "min_bandwidth": Num()}
)
_LEARN_SETTINGS = Obj(
    {
        "n_components": Int(lo=1),
        "kde_position_bandwidth": _POSITIVE,
        "kde_orientation_bandwidth": _POSITIVE,
        "kde_feature_bandwidth": _POSITIVE,
        "gmm_reg_covar": _POSITIVE,
        "max_distance": _POSITIVE,
        "contact_lambda": _POSITIVE,
        "min_points": _COUNT,
        "seed": _COUNT,
        "config": _CONFIG_SETTINGS,
    }
)
# One grasp type's models: an entry of a graspmix.model/2 "types".
_TYPE_MODELS = {
    "demonstration": Either(Str(), Null()),
    "config_model": Obj(
        {"pregrasp": _VECTOR, "grasp": _VECTOR, "settings": _CONFIG_SETTINGS}, required=["pregrasp", "grasp"]
    ),
    "contact_models": Arr(
        Obj(
            {
                "link": Str(nonempty=True),
                "n_points": _COUNT,
                "density": Tagged("kind", {"gmm": _GMM_DENSITY, "kde": _KDE_DENSITY}),
            },
            required=["link", "density"],
        ),
        min_len=1,
    ),
}
_MODEL = Obj(
    {
        "format": Str(),
        "method": Str(choices=["gmm", "kde"]),
        "hand": Str(nonempty=True),
        "features": Obj({"voxel_size": _NONNEGATIVE, "radius": _POSITIVE}),
        "learn_settings": _LEARN_SETTINGS,
        "types": Arr(
            Obj(
                {"name": Str(nonempty=True), "log_reference": Num(), **_TYPE_MODELS},
                required=["name", "config_model", "contact_models"],
            ),
            min_len=1,
        ),
    },
    required=["method", "hand", "features", "types"],
)

_GRASP = Obj(
    {
        "rank": Int(lo=1),
        "T_world_wrist": _POSE,
        "pregrasp_joints": _JOINTS,
        "grasp_joints": _JOINTS,
        "log_likelihood": _LOG,
        "optimised": Bool(),
        "experts": Map(_LOG),
        # What a robot stack needs (graspmix.model.grasp_frames), after the first release's keys.
        "T_world_wrist_matrix": Tensor(2, (4, 4)),
        "T_world_tcp": _POSE,
        "approach": Tensor(1, (3,)),
        "closing": Tensor(1, (3,)),
        "opening_width": Num(),
        "T_world_pregrasp": _POSE,
        "T_world_retreat": _POSE,
    },
    required=["T_world_wrist", "pregrasp_joints", "grasp_joints"],
)
_GRASPS = Obj(
    {
        "format": Str(),
        "hand": Str(),
        "method": Str(),
        "cloud": Str(),
        "timing_s": Map(Num(lo=0.0)),
        "grasps": Arr(_GRASP, min_len=1),
        "plane": Either(Tensor(1, (4,)), Null()),
        "evaluations": _COUNT,
        "rejected": _COUNT,
        "targets": Arr(_COUNT),
        "view": Obj(
            {
                "depth": Str(nonempty=True),
                "intrinsics": Tensor(1, (4,), "fx, fy, cx, cy"),
                "depth_scale": Either(Num(lo=0.0), Null()),
                "camera_pose": _POSE,
                "sha256": Str(nonempty=True),  # the image file's (plot refuses a file replaced since)
            },
            required=["depth", "intrinsics", "depth_scale", "camera_pose"],
        ),
        "cloud_sha256": Str(),  # the cloud file's
        "frames": Obj(
            {
                "approach_axis": Tensor(1, (3,)),
                "pregrasp_distance": _NONNEGATIVE,
                "retreat_distance": _NONNEGATIVE,
                "fingertip_tolerance": _NONNEGATIVE,
                "fingertip_links": Arr(Str(nonempty=True)),
            }
        ),
    },
    required=["grasps"],
)

_STRINGS = Arr(Str(nonempty=True), min_len=1)
# SynthesisOptions.to_dict(): part -> its fields (or null: the expert off), and the seed; the values are checked
# by SynthesisOptions.from_dict when the protocol is read.
_SYNTHESIS = Map(Any(), nonempty=True)
_PROTOCOL = Obj(
    {
        "format": Str(),
        "protocol": Obj(
            {
                "objects": _STRINGS,
                "trials": Int(lo=1),
                "conditions": _STRINGS,
                "methods": _STRINGS,
                "pixel_noise_std": Num(lo=0.0),
                "depth_noise_std": Num(lo=0.0),
                "closing": Str(),
                "views": Int(lo=1),
                "cloud": Str(),
                "synthesis": _SYNTHESIS,
                "seed": _COUNT,
                "models": Map(Obj({"file": Str(), "sha256": Str()})),
                "condition_definitions": Map(
                    Obj({"noise": Bool(), "optimise": Bool()}, required=["noise", "optimise"])
                ),
            },
            required=["objects", "trials", "conditions", "methods", "synthesis"],
        ),
        "provenance": Map(Any()),
    },
    required=["protocol"],
)

_RATE = Num(lo=0.0, hi=1.0, also=(None,))
_SUMMARY = Obj(
    {
        "format": Str(),
        "protocol": _PROTOCOL.fields["protocol"],
        "provenance": Map(Any()),
        "attempts": Obj({"done": _COUNT, "expected": _COUNT, "complete": Bool()}, required=["done", "expected"]),
        "success_rate": Map(
            Map(
                Obj(
                    {
                        "mean": _RATE,
                        "ci_low": Num(also=(None,)),
                        "ci_high": Num(also=(None,)),
                        "per_trial": Map(_RATE),
                        "successes": _COUNT,
                        "attempts": _COUNT,
                    }
                )
            )
        ),
        "ttest_gmm_vs_kde": Map(Map(Any())),
        "outcomes": Map(Map(Map(_COUNT))),
        "runtime": Map(Any()),
        "per_object_success_rate": Map(Any()),
    },
    required=["protocol", "attempts", "success_rate"],
)

_SECONDS = Num(lo=0.0, finite=False, also=(None,))
_BENCHMARK = Obj(
    {
        "format": Str(),
        "objects": _STRINGS,
        "n_samples": Int(lo=1),
        "n_optimise": Int(lo=0),
        "median_s": Map(Map(_SECONDS)),
        "ratio_kde_over_gmm": Map(_SECONDS),
        "per_object_s": Map(Map(Arr(_SECONDS))),
    },
    required=["objects", "median_s"],
)

_GMM = Obj(
    {
        "format": Str(),
        "weights": _VECTOR,
        "means": Tensor(2),
        "covariances": Tensor(3),
        "converged": Bool(),
        "n_iter": _COUNT,
        "lower_bound": Num(),
    },
    required=["weights", "means", "covariances"],
)

# A scene of objects on the table z = 0 (graspmix.sim.scenes.SceneSpec): each object's URDF, link pose and
# scale; the seed and mode that made it (null for a scene made by hand).
_SCENE = Obj(
    {
        "format": Str(),
        "objects": Arr(
            Obj({"urdf": Str(nonempty=True), "pose": _POSE, "scale": _POSITIVE}, required=["urdf", "pose"]),
            min_len=0,  # a table cleared of every object is a scene too
        ),
        "seed": Either(Int(lo=0), Null()),
        "mode": Either(Str(), Null()),
    },
    required=["format", "objects"],
)

_CLUTTER = Obj(
    {
        "format": Str(),
        "protocol": Obj(
            {
                "object_list": Str(nonempty=True),
                "object_list_sha256": Str(),
                "objects": Int(lo=1),
                "scenes": Int(lo=1),
                "modes": _STRINGS,
                "methods": _STRINGS,
                "views": Int(lo=1),
                "noise": Bool(),
                "synthesis": _SYNTHESIS,
                "closing": Str(),
                "max_attempts": Int(lo=-1),
                "seed": _COUNT,
                "models": Map(Obj({"file": Str(), "sha256": Str()})),
                "task": Str(),
                "targets": Int(lo=1),
            },
            required=["object_list", "objects", "scenes", "modes", "methods", "synthesis"],
        ),
        "provenance": Map(Any()),
    },
    required=["protocol"],
)
_RATE_CI = Obj(
    {"rate": _RATE, "low": _RATE, "high": _RATE, "successes": _COUNT, "trials": _COUNT, "clusters": _COUNT},
    required=["rate", "low", "high"],
)
_NAMED_RATE = Obj({"trials": _COUNT, "successes": _COUNT}, required=["trials"])  # rate null without attempts
_NAMED_CELL = Obj(
    {"success": _NAMED_RATE, "wrong_object": _NAMED_RATE, "outcomes": Map(_COUNT)},
    required=["success", "wrong_object", "outcomes"],
)
_CLUTTER_SUMMARY = Obj(
    {
        "format": Str(),
        "protocol": _CLUTTER.fields["protocol"],
        "provenance": Map(Any()),
        "rounds": Obj({"done": _COUNT, "expected": _COUNT, "complete": Bool()}, required=["done", "expected"]),
        "task": Str(),
        # the clearing task's GSR and DR, or the named task's success and neighbours lifted instead
        "results": Map(Map(Either(Obj({"gsr": _RATE_CI, "dr": _RATE_CI}, required=["gsr", "dr"]), _NAMED_CELL))),
    },
    required=["protocol", "rounds", "results"],
)

SCHEMAS = {
    DEMO_FORMAT: _DEMO,
    MODEL_FORMAT: _MODEL,
    GRASPS_FORMAT: _GRASPS,
    PROTOCOL_FORMAT: _PROTOCOL,
    SUMMARY_FORMAT: _SUMMARY,
    BENCHMARK_FORMAT: _BENCHMARK,
    GMM_FORMAT: _GMM,
    SCENE_FORMAT: _SCENE,
    CLUTTER_FORMAT: _CLUTTER,
    CLUTTER_SUMMARY_FORMAT: _CLUTTER_SUMMARY,
}


# ---- reading ---------------------------------------------------------------------------------------
def read_json(path: Path, what: str) -> dict:
    """A JSON object from a file; ValueError naming the file if it is missing, unreadable, not UTF-8 JSON
    (or nested too deeply to parse) or not an object."""
    path = check_input_file(path, what)
    try:
        data = json.loads(path.read_bytes().decode("utf-8"))
    except OSError as e:
        raise ValueError(f"{path}: cannot read the {what} file ({e.strerror})") from None
    except UnicodeDecodeError as e:
        raise ValueError(f"{path}: not valid JSON (not UTF-8 text: byte {e.start})") from None
    except RecursionError:
        raise ValueError(f"{path}: not valid JSON for graspmix (nested too deeply)") from None
    except json.JSONDecodeError as e:
        raise ValueError(f"{path}: not valid JSON ({e.msg} at line {e.lineno} column {e.colno})") from None
    except ValueError as e:  # e.g. an integer of more digits than Python converts
        raise ValueError(f"{path}: not valid JSON ({quote(str(e))})") from None
    if not isinstance(data, dict):
        raise ValueError(f"{path}: expected a JSON object at the top level")
    return data


def check_format(data: dict, fmt: str, path) -> None:
    """The document's "format" field is fmt (or absent, where FORMATS allows it); ValueError otherwise."""
    _, optional = FORMATS[fmt]
    found = data.get("format", fmt if optional else None)
    if found != fmt:
        raise ValueError(f"{path}: format is {quote(found)}, expected format {fmt!r}")


def read_document(path, fmt: str) -> dict:
    """A graspmix JSON document of the given format, read and checked against the format's schema."""
    what, _ = FORMATS[fmt]
    data = read_json(path, what)
    check_format(data, fmt, path)
    validate(data, SCHEMAS[fmt], path)
    return data


def require_field(data: dict, key: str, path, kind=None):
    """data[key], which must exist (and be of type kind, if given); ValueError naming the file otherwise."""
    if key not in data:
        raise ValueError(f"{path}: missing field '{key}'")
    value = data[key]
    if kind is not None and not isinstance(value, kind):
        raise ValueError(f"{path}: field '{key}' has the wrong type ({type(value).__name__}: {quote(value)})")
    return value
