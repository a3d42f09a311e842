"""Runs the cloud fuzz corpus (tests/python/fuzz/corpus_clouds.py) through the command line, each case in a
process of its own with a timeout: a bad file is exit status 2 and one line on stderr naming the problem (no
traceback, no crash, no hang); a good one is exit status 0.

Starting Python and importing graspmix costs about a second, so every case runs in a process forked from a
helper that imported graspmix once, with its file descriptors 1 and 2 captured (a crash kills only that
child); a sample of the cases also runs exactly as a user would, `python -m graspmix.cli features --cloud FILE`."""

import importlib.util
import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import graspmix

CORPUS = Path(__file__).resolve().parents[1] / "fuzz" / "corpus_clouds.py"
TIMEOUT_S = 60  # a case takes well under a second; a hang is what this catches
EVERY_NTH_AS_SUBPROCESS = 12


def _corpus():
    spec = importlib.util.spec_from_file_location("corpus_clouds", CORPUS)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


corpus = _corpus()


def _write(case, folder: Path) -> list[str]:
    folder.mkdir()
    for name, data in case["files"].items():
        (folder / name).write_bytes(data)
    return [a.replace("{dir}", str(folder)) for a in case["argv"]]


# A helper process that imports graspmix once, then forks one child per case (it never runs OpenMP itself,
# so its children may). It reads one JSON request a line, {"argv", "out", "err"}, and answers with the
# child's exit status (negative: killed by that signal; null: no answer within the timeout).
HELPER = r"""
import json, os, signal, sys, time
from graspmix.cli.main import main

for line in sys.stdin:
    req = json.loads(line)
    pid = os.fork()
    if pid == 0:
        for fd, path in ((1, req["out"]), (2, req["err"])):
            os.dup2(os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC), fd)
        try:
            rc = main(req["argv"])
        except SystemExit as e:  # argparse
            rc = e.code if isinstance(e.code, int) else 2
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(rc)
    deadline, status = time.monotonic() + req["timeout"], None
    while status is None and time.monotonic() < deadline:
        done, st = os.waitpid(pid, os.WNOHANG)
        status = os.waitstatus_to_exitcode(st) if done else time.sleep(0.002)
    if status is None:
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
    print(json.dumps(status), flush=True)
"""


def _run_forked(helper, case, folder: Path):
    argv = _write(case, folder)
    out, err = folder / "stdout.txt", folder / "stderr.txt"
    helper.stdin.write(json.dumps({"argv": argv, "out": str(out), "err": str(err), "timeout": TIMEOUT_S}) + "\n")
    helper.stdin.flush()
    rc = json.loads(helper.stdout.readline())
    if rc is None:
        return case, None, "", f"no answer within {TIMEOUT_S} s"
    return case, rc, out.read_text(errors="replace"), err.read_text(errors="replace")


def _env() -> dict:
    """This graspmix, whichever way the tests found it."""
    path = [str(Path(graspmix.__file__).parents[1]), os.environ.get("PYTHONPATH", "")]
    return dict(os.environ, PYTHONPATH=os.pathsep.join(p for p in path if p))


def _run_subprocess(case, folder: Path):
    argv = _write(case, folder)
    env = dict(
        os.environ,
        PYTHONPATH=os.pathsep.join([str(Path(graspmix.__file__).parents[1]), os.environ.get("PYTHONPATH", "")]),
    )
    try:
        p = subprocess.run(
            [sys.executable, "-m", "graspmix.cli", *argv], capture_output=True, text=True, timeout=TIMEOUT_S, env=env
        )
    except subprocess.TimeoutExpired:
        return case, None, "", f"no answer within {TIMEOUT_S} s"
    return case, p.returncode, p.stdout, p.stderr


def _failure(case, rc, stdout, stderr) -> str | None:
    """What is wrong with one run, or None."""
    if rc is None:
        return stderr
    if case["expect"] == "ok":
        return None if rc == 0 else f"exit {rc}, expected 0; stderr: {stderr.strip()[-500:]}"
    lines = stderr.strip().splitlines()
    if rc != 2:
        return f"exit {rc}, expected 2 (a negative status is a signal: a crash); stderr: {stderr.strip()[-500:]}"
    if len(lines) != 1 or "Traceback" in stderr:
        return f"expected one stderr line, got {len(lines)}: {stderr.strip()[-500:]}"
    if case["mentions"] not in lines[0]:
        return f"the error does not mention {case['mentions']!r}: {lines[0]}"
    return None


def _check(runs) -> None:
    failures = [f"{case['name']}: {msg}" for case, *rest in runs if (msg := _failure(case, *rest))]
    assert not failures, f"{len(failures)} of {len(runs)} cases failed:\n" + "\n".join(failures)


def test_corpus_is_well_formed():
    names = [c["name"] for c in corpus.CASES]
    assert len(names) == len(set(names))
    assert 100 <= len(names) <= 200, len(names)
    assert {c["expect"] for c in corpus.CASES} == {"ok", "error"}
    for c in corpus.CASES:
        assert any("{dir}" in a for a in c["argv"]) and c["files"], c["name"]


def test_lzf_writer_and_reader_agree():
    data = bytes(range(50)) + b"\0" * 300 + b"ab" * 40 + b"\x07" * 5
    assert corpus.lzf_decompress(corpus.lzf_compress(data), len(data)) == data
    assert corpus.lzf_decompress(b"\xff\x00\x00", 10) is None  # a reference before the start


def test_every_case_fails_cleanly_or_loads(tmp_path):
    with subprocess.Popen(
        [sys.executable, "-c", HELPER], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True, env=_env()
    ) as helper:
        runs = [_run_forked(helper, case, tmp_path / f"{i:03d}") for i, case in enumerate(corpus.CASES)]
        helper.stdin.close()
    _check(runs)


def test_a_sample_as_the_user_runs_it(tmp_path):
    sample = corpus.CASES[::EVERY_NTH_AS_SUBPROCESS]
    with ThreadPoolExecutor(max_workers=(os.cpu_count() or 2) + 1) as pool:
        _check(list(pool.map(lambda ic: _run_subprocess(ic[1], tmp_path / f"{ic[0]:03d}"), enumerate(sample))))
