"""The fuzz suite: a fixed corpus of malformed and edge-case inputs, each run in a subprocess, so a crash
(a segfault, an abort) or a hang is a failure of its case and not of the test run.

The corpus
    Every module ``corpus_*.py`` in this folder is picked up; it exposes ``CASES``, a list of
    ``cases.Case`` (one module per input class, so several people can add cases without conflicts):

        corpus_json.py    malformed and edge-case JSON files of every format (demo, model, grasps, protocol,
                          summary, benchmark, gmm), attempts.csv, through the CLI and the API
        corpus_cli.py     bad option values of every graspmix_cli subcommand: numbers out of range or not
                          finite, unwritable outputs, paths too long or not UTF-8, missing inputs
        corpus_api.py     the public Python entry points with bad values of each class
        corpus_reports.py attempts.csv with a column or a recorded value missing, through report and the API
        corpus_scenes.py  clouds of a table with nothing on it (noisy, seen from above or from its own plane)

    The file corpora, many cheap cases of one command each, are dicts run by their own forking runners
    (one interpreter imports graspmix once and forks a child per case, so a crash still ends only its
    case, at a tenth of the cost of a fresh interpreter); this harness skips them:

        corpus_clouds.py  cloud files: PCD/PLY/npy headers, sizes, encodings (tests/python/perception/
                          test_cloud_fuzz.py)
        corpus_urdf.py    hand and object URDFs (tests/python/robot/test_urdf_fuzz.py)

    A case (cases.Case) is:
        id       unique over the corpus, "<class>/<what>"
        kind     "cli": ``argv`` is run as ``python -m graspmix.cli *argv`` (the package this interpreter
                 imports); "api": ``code`` is Python run with ``import graspmix`` done
        files    {relative name: str or bytes} written into the case's own folder, the subprocess' working
                 directory, before it runs ("{tmp}" in argv and code is that folder, "{data}" the bundled data)
        expect   "error" or "ok"
        names    substrings the error line must contain: the file or argument at fault
        timeout  seconds; a case still running then has hung
        group    API cases with the same group share one subprocess (startup is most of their cost); only for
                 code that reads no file in C++, so a crash cannot hide behind another case
        xfail    a known failure that belongs to someone else (the C++ side): why; strict, so a fix is noticed

What is asserted
    CLI, expect "error": exit status 2, exactly one line on stderr, naming every entry of ``names``, no
    "Traceback", at most MAX_LINE characters (values are quoted clipped). API, expect "error": a ValueError
    (or subclass) whose message is one line naming ``names``. expect "ok": exit status 0 (API: no exception),
    no "Traceback". Any other exit (a signal, a timeout, another exception) fails the case.

Cases run in a pool of POOL subprocesses at a time; the whole suite takes a few minutes on two cores.
"""

from __future__ import annotations

import importlib.util
import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from cases import DATA, Case  # noqa: E402

POOL = 2
MAX_LINE = 1000  # characters of an error line: a path or two and clipped values


def load_corpus() -> list[Case]:
    cases = []
    for path in sorted(HERE.glob("corpus_*.py")):
        spec = importlib.util.spec_from_file_location(f"fuzz_{path.stem}", path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        cases.extend(c for c in module.CASES if isinstance(c, Case))  # dict cases: their own runner
    ids = [c.id for c in cases]
    dup = {i for i in ids if ids.count(i) > 1}
    assert not dup, f"duplicate case ids: {sorted(dup)}"
    return cases


CORPUS = load_corpus()

# Runs API cases in one interpreter: prints one JSON line per case (its outcome) on stdout.
_API_RUNNER = r"""
import json, os, sys
cases = json.loads(sys.argv[1])
import graspmix
for c in cases:
    os.chdir(c["dir"])
    try:
        exec(compile(c["code"], c["id"], "exec"), {"graspmix": graspmix, "__name__": "__fuzz__"})
        out = {"id": c["id"], "outcome": "ok"}
    except ValueError as e:
        out = {"id": c["id"], "outcome": "valueerror", "type": type(e).__name__, "message": str(e)[:5000]}
    except BaseException as e:
        out = {"id": c["id"], "outcome": "other", "type": type(e).__name__, "message": str(e)[:5000]}
    print("FUZZ " + json.dumps(out), flush=True)
"""


def _fill(text: str, folder: Path) -> str:
    return text.replace("{tmp}", str(folder)).replace("{data}", str(DATA))


def _prepare(case: Case, root: Path) -> Path:
    folder = root / case.id.replace("/", "__")
    folder.mkdir(parents=True)
    for name, content in case.files.items():
        p = folder / name
        p.parent.mkdir(parents=True, exist_ok=True)
        (p.write_bytes if isinstance(content, bytes) else p.write_text)(
            _fill(content, folder) if isinstance(content, str) else content
        )
    return folder


def _env() -> dict:
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([p for p in sys.path if p and Path(p).is_dir()])
    env.setdefault("OMP_NUM_THREADS", "1")  # two cases at a time on two cores
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    return env


def _run_cli(case: Case, folder: Path) -> dict:
    argv = [sys.executable, "-m", "graspmix.cli", *[_fill(a, folder) for a in case.argv]]
    try:
        r = subprocess.run(argv, cwd=folder, env=_env(), capture_output=True, timeout=case.timeout)
    except subprocess.TimeoutExpired:
        return {case.id: {"outcome": "timeout"}}
    return {
        case.id: {
            "outcome": "exit",
            "status": r.returncode,
            "stderr": r.stderr.decode("utf-8", "backslashreplace"),
            "stdout": r.stdout.decode("utf-8", "backslashreplace")[-2000:],
        }
    }


def _run_api(cases: list[Case], folders: list[Path]) -> dict:
    payload = json.dumps([{"id": c.id, "code": _fill(c.code, f), "dir": str(f)} for c, f in zip(cases, folders)])
    timeout = sum(c.timeout for c in cases)
    try:
        r = subprocess.run(
            [sys.executable, "-c", _API_RUNNER, payload],
            cwd=folders[0],
            env=_env(),
            capture_output=True,
            timeout=timeout,
        )
    except subprocess.TimeoutExpired:
        return {c.id: {"outcome": "timeout"} for c in cases}
    out = {}
    for line in r.stdout.decode("utf-8", "backslashreplace").splitlines():
        if line.startswith("FUZZ "):
            d = json.loads(line[5:])
            out[d.pop("id")] = d
    crash = {"outcome": "crash", "status": r.returncode, "stderr": r.stderr.decode("utf-8", "backslashreplace")[-3000:]}
    for c in cases:
        out.setdefault(c.id, crash)  # the subprocess died before reporting this case
    return out


@pytest.fixture(scope="session")
def results(tmp_path_factory) -> dict:
    """Every case's outcome, run POOL at a time (grouped API cases in one subprocess per group)."""
    root = tmp_path_factory.mktemp("fuzz")
    jobs, groups = [], {}
    for case in CORPUS:
        folder = _prepare(case, root)
        if case.kind == "cli":
            jobs.append((_run_cli, case, folder))
        elif case.group is None:
            jobs.append((_run_api, [case], [folder]))
        else:
            groups.setdefault(case.group, ([], []))
            groups[case.group][0].append(case)
            groups[case.group][1].append(folder)
    jobs.extend((_run_api, cs, fs) for cs, fs in groups.values())
    jobs.sort(key=lambda j: -(sum(c.timeout for c in j[1]) if isinstance(j[1], list) else 0))  # long groups first
    out = {}
    with ThreadPoolExecutor(POOL) as pool:
        for r in pool.map(lambda j: j[0](j[1], j[2]), jobs):
            out.update(r)
    return out


def test_corpus_is_large_and_covers_every_class():
    prefixes = {c.id.split("/")[0] for c in CORPUS}
    assert {"json", "cli", "api"} <= prefixes
    assert len(CORPUS) >= 100


@pytest.mark.parametrize(
    "case",
    [pytest.param(c, marks=pytest.mark.xfail(reason=c.xfail, strict=True)) if c.xfail else c for c in CORPUS],
    ids=[c.id for c in CORPUS],
)
def test_case(case: Case, results):
    r = results[case.id]
    assert r["outcome"] != "timeout", f"hung (no answer within {case.timeout} s)"
    assert r["outcome"] != "crash", f"the subprocess died (status {r['status']}): {r['stderr']}"
    if case.kind == "cli":
        _check_cli(case, r)
    else:
        _check_api(case, r)


def _check_cli(case: Case, r: dict):
    err = r["stderr"]
    assert "Traceback" not in err, err[-3000:]
    if case.expect == "ok":
        assert r["status"] == 0, f"status {r['status']}: {err[-2000:]}"
        return
    assert r["status"] == 2, f"status {r['status']} (a signal if negative): {err[-2000:]}"
    lines = err.strip("\n").split("\n")
    assert len(lines) == 1, f"{len(lines)} lines on stderr: {err[:2000]}"
    line = lines[0]
    assert line.startswith("graspmix_cli"), line[:500]
    assert len(line) <= MAX_LINE, f"an error line of {len(line)} characters: {line[:300]}..."
    for name in case.names:
        assert name in line, f"the error does not name {name!r}: {line[:500]}"


def _check_api(case: Case, r: dict):
    if case.expect == "ok":
        assert r["outcome"] == "ok", f"{r.get('type')}: {r.get('message', '')[:2000]}"
        return
    assert r["outcome"] == "valueerror", (
        f"expected a ValueError, got {r.get('type', r['outcome'])}: {r.get('message', '')[:2000]}"
    )
    message = r["message"]
    assert "\n" not in message.strip(), f"a message of several lines: {message[:2000]}"
    assert len(message) <= MAX_LINE, f"a message of {len(message)} characters: {message[:300]}..."
    for name in case.names:
        assert name in message, f"the error does not name {name!r}: {message[:500]}"
