"""Malformed and edge-case JSON documents of every format, and edited attempts.csv files: each field of a
valid document replaced by values of the wrong kind (a seeded choice among all such pairs), fields
removed, files that are not JSON, nested 100,000 deep, huge. Read through the commands that consume them
(learn --demo, synthesize --model, execute --grasps, report) and, for the formats no command reads back,
through graspmix.io.read_document."""

from __future__ import annotations

import random

from cases import (
    MUG,
    api,
    attempts_csv,
    cli,
    del_path,
    demo_doc,
    dumps,
    grasps_doc,
    model_doc,
    protocol_doc,
    run_folder,
    set_path,
)

RNG = random.Random(20240611)  # the corpus is the same on every run

NAN, INF = float("nan"), float("inf")
# Wrong values per kind of field (json.dumps writes NaN and Infinity, which Python's reader accepts).
WRONG = {
    "str": [None, 5, [], {}, True],
    "num": [None, "x", [], {}, True, NAN, INF, "1.0"],
    "int": [None, 1.5, "1", -3, True, NAN],
    "list": [None, 5, "x", {}, [[]]],
    "map": [None, [], "x", 5],
    "obj": [None, [], "x", 5, True],
    "bool": [None, "yes", 1, []],
}

# (field path, kind) of each format's fields that readers use.
DEMO_FIELDS = [
    (("hand",), "str"),
    (("cloud",), "str"),
    (("T_world_wrist",), "list"),
    (("T_world_wrist", 3), "num"),
    (("pregrasp_joints",), "map"),
    (("grasp_joints",), "map"),
    (("grasp_joints", "finger_left_joint"), "num"),
]
MODEL_FIELDS = [
    (("method",), "str"),
    (("hand",), "str"),
    (("features",), "obj"),
    (("features", "radius"), "num"),
    (("features", "voxel_size"), "num"),
    (("types",), "list"),
    (("types", 0), "obj"),
    (("types", 0, "name"), "str"),
    (("types", 0, "log_reference"), "num"),
    (("types", 0, "config_model"), "obj"),
    (("types", 0, "config_model", "pregrasp"), "list"),
    (("types", 0, "config_model", "settings"), "obj"),
    (("types", 0, "config_model", "settings", "n_kernels"), "int"),
    (("types", 0, "contact_models"), "list"),
    (("types", 0, "contact_models", 0), "obj"),
    (("types", 0, "contact_models", 0, "link"), "str"),
    (("types", 0, "contact_models", 0, "density"), "obj"),
    (("types", 0, "contact_models", 1, "density", "weights"), "list"),
    (("types", 0, "contact_models", 2, "density", "means", 0, 1), "num"),
    (("learn_settings",), "obj"),
    (("learn_settings", "kde_position_bandwidth"), "num"),
]
GRASPS_FIELDS = [
    (("grasps",), "list"),
    (("grasps", 0), "obj"),
    (("grasps", 0, "rank"), "int"),
    (("grasps", 0, "T_world_wrist"), "list"),
    (("grasps", 0, "T_world_wrist", 6), "num"),
    (("grasps", 0, "pregrasp_joints"), "map"),
    (("grasps", 0, "grasp_joints", "finger_left_joint"), "num"),
    (("grasps", 1, "experts"), "map"),
    (("grasps", 0, "optimised"), "bool"),
    (("hand",), "str"),
    (("timing_s",), "map"),
]
PROTOCOL_FIELDS = [
    (("protocol",), "obj"),
    (("protocol", "objects"), "list"),
    (("protocol", "objects", 0), "str"),
    (("protocol", "trials"), "int"),
    (("protocol", "conditions"), "list"),
    (("protocol", "methods", 1), "str"),
    (("protocol", "seed"), "int"),
    (("protocol", "closing"), "str"),
    (("protocol", "synthesis"), "map"),
    (("protocol", "synthesis", "sampling"), "map"),
    (("protocol", "synthesis", "sampling", "n_samples"), "int"),
    (("provenance",), "map"),
]


def _label(value) -> str:
    if value is None:
        return "null"
    if isinstance(value, float) and value != value:
        return "nan"
    if isinstance(value, float) and value in (INF, -INF):
        return "inf"
    return {bool: "bool", str: "string", int: "int", float: "float", list: "list", dict: "object"}[type(value)]


def _wrong_values(fields, per_field: int):
    """(path, value) pairs: for each field, per_field of the wrong values of its kind (seeded choice)."""
    out = []
    for path, kind in fields:
        for v in RNG.sample(WRONG[kind], min(per_field, len(WRONG[kind]))):
            out.append((path, v))
    return out


def _path_id(path) -> str:
    return ".".join(str(p) for p in path)


def _field_name(path) -> str:
    """How the message names the field: the last key (indices appear as [i])."""
    last = [p for p in path if isinstance(p, str)]
    return last[-1] if last else "grasps"


def demo_cases():
    cases = []
    run = ("learn", "--demo", "{tmp}/demo.json", "--out", "{tmp}/model.json")
    for path, v in _wrong_values(DEMO_FIELDS, 2):
        if path == ("cloud",) and isinstance(v, list):
            continue  # an empty inline cloud: below
        doc = set_path(demo_doc(), path, v)
        cases.append(
            cli(
                f"json/demo/{_path_id(path)}-{_label(v)}",
                *run,
                files={"demo.json": dumps(doc)},
                names=("demo.json", _field_name(path)),
            )
        )
    for key in ("hand", "cloud", "T_world_wrist", "grasp_joints"):
        cases.append(
            cli(
                f"json/demo/missing-{key}",
                *run,
                files={"demo.json": dumps(del_path(demo_doc(), (key,)))},
                names=("demo.json", key),
            )
        )
    ragged = [[0.0, 0.0, 0.0], [0.1, 0.2], [0.3, 0.1, 0.0]]  # numpy: "setting an array element with a sequence"
    for label, cloud in (("ragged", ragged), ("empty", []), ("strings", [["a", "b", "c"]]), ("nan", [[0, 0, NAN]])):
        cases.append(
            cli(
                f"json/demo/inline-cloud-{label}",
                *run,
                files={"demo.json": dumps(set_path(demo_doc(), ("cloud",), cloud))},
                names=("demo.json", "cloud"),
            )
        )
    cases.append(
        cli(
            "json/demo/cloud-file-missing",
            *run,
            files={"demo.json": dumps(set_path(demo_doc(), ("cloud",), "nowhere.pcd"))},
            names=("demo.json", "nowhere.pcd"),
        )
    )
    cases.append(
        cli(
            "json/demo/cloud-name-too-long",
            *run,
            files={"demo.json": dumps(set_path(demo_doc(), ("cloud",), "c" * 300 + ".pcd"))},
            names=("255 bytes",),
        )
    )
    cases.append(
        cli(
            "json/demo/cloud-name-lone-surrogate",
            *run,
            files={
                "demo.json": '{"hand": "x", "cloud": "\\udcff.pcd", "T_world_wrist": [0,0,0,0,0,0,1], '
                '"pregrasp_joints": {}, "grasp_joints": {}}'
            },
            names=("demo.json", "cloud"),
        )
    )
    cases.append(
        cli(
            "json/demo/format-of-another-file",
            *run,
            files={"demo.json": dumps(set_path(demo_doc(), ("format",), "graspmix.grasps/1"))},
            names=("demo.json", "format"),
        )
    )
    # Valid edge cases: a hand-written demonstration without "format", with fields a newer writer adds.
    doc = del_path(demo_doc(), ("format",))
    doc["comment"] = "written by hand"
    cases.append(
        cli("json/demo/ok-no-format-extra-field", *run, files={"demo.json": dumps(doc)}, expect="ok", timeout=120)
    )
    return cases


def model_cases():
    run = (
        "synthesize",
        "--model",
        "{tmp}/model.json",
        "--cloud",
        MUG,
        "--samples",
        "5",
        "--optimise-top",
        "0",
        "--out",
        "{tmp}/grasps.json",
    )
    cases = []
    for path, v in _wrong_values(MODEL_FIELDS, 1):
        gmm_only = "means" in path  # a KDE density has poses, not means
        doc = set_path(model_doc("gmm" if gmm_only or RNG.random() < 0.6 else "kde"), path, v)
        cases.append(
            cli(
                f"json/model/{_path_id(path)}-{_label(v)}",
                *run,
                files={"model.json": dumps(doc)},
                names=("model.json", _field_name(path)),
            )
        )
    for path in (("method",), ("features",), ("types",), ("types", 0, "contact_models"), ("types", 0, "config_model")):
        cases.append(
            cli(
                f"json/model/missing-{path[-1]}",
                *run,
                files={"model.json": dumps(del_path(model_doc(), path))},
                names=("model.json", path[-1]),
            )
        )
    ragged = set_path(model_doc(), ("types", 0, "contact_models", 0, "density", "covariances", 1, 2), [1.0, 2.0])
    cases.append(
        cli(
            "json/model/covariance-ragged",
            *run,
            files={"model.json": dumps(ragged)},
            names=("model.json", "covariances"),
        )
    )
    cases.append(
        cli(
            "json/model/density-kind-unknown",
            *run,
            files={
                "model.json": dumps(set_path(model_doc(), ("types", 0, "contact_models", 0, "density", "kind"), "svm"))
            },
            names=("model.json", "kind"),
        )
    )
    cases.append(
        cli(
            "json/model/density-of-other-method",
            *run,
            files={
                "model.json": dumps(
                    set_path(
                        model_doc("gmm"),
                        ("types", 0, "contact_models", 0, "density"),
                        model_doc("kde")["types"][0]["contact_models"][0]["density"],
                    )
                )
            },
            names=("model.json",),
        )
    )
    cases.append(
        cli(
            "json/model/link-of-another-hand",
            *run,
            files={"model.json": dumps(set_path(model_doc(), ("types", 0, "contact_models", 0, "link"), "thumb"))},
            names=("model.json", "thumb"),
        )
    )
    return cases


def grasps_cases():
    run = ("execute", "--object", "{data}/objects/box.urdf", "--grasps", "{tmp}/grasps.json")
    cases = []
    for path, v in _wrong_values(GRASPS_FIELDS, 2):
        doc = set_path(grasps_doc(), path, v)
        cases.append(
            cli(
                f"json/grasps/{_path_id(path)}-{_label(v)}",
                *run,
                files={"grasps.json": dumps(doc)},
                names=("grasps.json", _field_name(path)),
            )
        )
    cases.append(
        cli(
            "json/grasps/empty-list",
            *run,
            files={"grasps.json": dumps(set_path(grasps_doc(), ("grasps",), []))},
            names=("grasps.json", "grasps"),
        )
    )
    cases.append(
        cli(
            "json/grasps/wrist-6-numbers",
            *run,
            files={"grasps.json": dumps(set_path(grasps_doc(), ("grasps", 0, "T_world_wrist"), [0.0] * 6))},
            names=("grasps.json", "T_world_wrist"),
        )
    )
    cases.append(
        cli(
            "json/grasps/joint-of-another-hand",
            *run,
            files={"grasps.json": dumps(set_path(grasps_doc(), ("grasps", 0, "grasp_joints"), {"thumb": 0.1}))},
            names=("thumb",),
        )
    )
    cases.append(
        cli(
            "json/grasps/rank-not-there",
            *run,
            "--rank",
            "7",
            files={"grasps.json": dumps(grasps_doc())},
            names=("rank 7",),
        )
    )
    # Valid edge cases: rank missing (the position), extra fields, log values "-inf" as written for rejected grasps.
    doc = del_path(grasps_doc(), ("grasps", 0, "rank"))
    doc["grasps"][0]["note"] = "kept"
    doc["written_by"] = "a newer graspmix"
    cases.append(cli("json/grasps/ok-no-rank-extra-fields", *run, files={"grasps.json": dumps(doc)}, expect="ok"))
    cases.append(
        cli(
            "json/grasps/ok-rank-2-minus-inf",
            *run,
            "--rank",
            "2",
            files={"grasps.json": dumps(grasps_doc())},
            expect="ok",
        )
    )
    return cases


def file_cases():
    """Files that are not documents at all, through the grasps reader (the same read_json for every format)."""
    run = ("execute", "--object", "{data}/objects/box.urdf", "--grasps", "{tmp}/grasps.json")
    bad = {
        "empty": "",
        "not-json": "grasps: [1, 2]",
        "truncated": dumps(grasps_doc())[:-40],
        "top-level-list": "[1, 2, 3]",
        "nested-100000": "[" * 100_000 + "]" * 100_000,
        "nested-objects-100000": '{"a":' * 100_000 + "1" + "}" * 100_000,
        "not-utf8": b'{"format": "graspmix.grasps/1", "hand": "\xff\xfe"}',
        "utf8-bom": "\ufeff" + dumps(grasps_doc()),
        "huge-integer": '{"format": "graspmix.grasps/1", "grasps": [' + "9" * 5000 + "]}",
        "format-100MB": '{"format": "' + "x" * 100_000_000 + '"}',
        "format-number": '{"format": 1, "grasps": []}',
    }
    cases = [cli(f"json/file/{k}", *run, files={"grasps.json": v}, names=("grasps.json",)) for k, v in bad.items()]
    cases.append(cli("json/file/a-folder", *run, files={"grasps.json/x": "1"}, names=("grasps.json",)))
    return cases


def report_cases():
    """An experiment folder whose protocol.json or attempts.csv was edited by hand."""
    cases = []
    for path, v in _wrong_values(PROTOCOL_FIELDS, 1):
        doc = set_path(protocol_doc(), path, v)
        cases.append(
            cli(
                f"json/protocol/{_path_id(path)}-{_label(v)}",
                "report",
                "{tmp}/run",
                files=run_folder(protocol=dumps(doc)),
                names=("protocol.json", _field_name(path)),
            )
        )
    edits = {
        "condition-unknown": (("protocol", "conditions"), ["A", "Z"]),
        "method-twice": (("protocol", "methods"), ["gmm", "gmm"]),
        "closing-unknown": (("protocol", "closing"), "halfway"),
    }
    for label, (path, v) in edits.items():
        cases.append(
            cli(
                f"json/protocol/{label}",
                "report",
                "{tmp}/run",
                files=run_folder(protocol=dumps(set_path(protocol_doc(), path, v))),
                names=("protocol.json",),
            )
        )

    def row_edit(col, value):
        def edit(i, row):
            if i == 5:
                row[col] = value

        return edit

    for label, col, value in (
        ("trial-text", "trial", "two"),
        ("success-text", "success", "yes"),
        ("trial-out-of-range", "trial", 7),
        ("condition-unknown", "condition", "Q"),
        ("object-unknown", "object", "elsewhere.urdf"),
        ("success-2", "success", 2),
        ("lift-text", "lift_height", "high"),
    ):
        cases.append(
            cli(
                f"json/csv/{label}",
                "report",
                "{tmp}/run",
                files=run_folder(csv=attempts_csv(row_edit(col, value))),
                names=("attempts.csv",),
            )
        )
    csv_text = attempts_csv()
    cases.append(
        cli(
            "json/csv/short-row",
            "report",
            "{tmp}/run",
            files=run_folder(csv=csv_text + "random_urdfs/000/000.urdf,0,A\n"),
            names=("attempts.csv",),
        )
    )
    cases.append(
        cli(
            "json/csv/not-utf8",
            "report",
            "{tmp}/run",
            files=run_folder(csv=csv_text.encode() + b"\xff\xfe\n"),
            names=("attempts.csv",),
        )
    )
    cases.append(
        cli(
            "json/csv/other-columns", "report", "{tmp}/run", files=run_folder(csv="a,b\n1,2\n"), names=("attempts.csv",)
        )
    )
    cases.append(
        cli(
            "json/csv/ok-torn-last-line",
            "report",
            "{tmp}/run",
            files=run_folder(csv=csv_text + "random_ur"),
            expect="ok",
            timeout=120,
        )
    )
    return cases


def read_document_cases():
    """The formats no command reads back: summary, benchmark, gmm (fit-gmm --out), through read_document."""
    docs = {
        "summary": {
            "format": "graspmix.summary/2",
            "protocol": protocol_doc()["protocol"],
            "attempts": {"done": 3, "expected": 4, "complete": False},
            "success_rate": {"A": {"gmm": {"mean": 0.5, "per_trial": {"0": 0.5}, "successes": 1, "attempts": 2}}},
        },
        "benchmark": {
            "format": "graspmix.benchmark/1",
            "objects": ["a.urdf"],
            "n_samples": 200,
            "n_optimise": 10,
            "median_s": {"gmm": {"query": 0.1}},
            "ratio_kde_over_gmm": {"query": 2.0},
            "per_object_s": {"gmm": {"query": [0.1]}},
        },
        "gmm": {
            "format": "graspmix.gmm/1",
            "weights": [0.5, 0.5],
            "means": [[0.0, 0.0], [1.0, 1.0]],
            "covariances": [[[1.0, 0.0], [0.0, 1.0]], [[1.0, 0.0], [0.0, 1.0]]],
            "converged": True,
            "n_iter": 3,
            "lower_bound": -1.2,
        },
    }
    fmt = {"summary": "SUMMARY_FORMAT", "benchmark": "BENCHMARK_FORMAT", "gmm": "GMM_FORMAT"}
    bad = {
        "summary": [
            (("attempts", "done"), "3"),
            (("success_rate", "A", "gmm", "mean"), 1.5),
            (("protocol",), []),
            (("success_rate",), None),
        ],
        "benchmark": [(("objects",), "a.urdf"), (("median_s", "gmm", "query"), "fast"), (("n_samples",), 0)],
        "gmm": [(("means", 1), [1.0]), (("weights", 0), None), (("covariances",), [[1.0]]), (("converged",), "yes")],
    }
    cases = []
    for name, doc in docs.items():
        code = f"graspmix.io.read_document('{name}.json', graspmix.io.{fmt[name]})"
        cases.append(api(f"json/{name}/ok", code, files={f"{name}.json": dumps(doc)}, expect="ok", group="json"))
        for path, v in bad[name]:
            cases.append(
                api(
                    f"json/{name}/{_path_id(path)}-{_label(v)}",
                    code,
                    files={f"{name}.json": dumps(set_path(doc, path, v))},
                    names=(f"{name}.json", _field_name(path) if name != "gmm" or path[0] != "weights" else "weights"),
                    group="json",
                )
            )
    return cases


CASES = demo_cases() + model_cases() + grasps_cases() + file_cases() + report_cases() + read_document_cases()
