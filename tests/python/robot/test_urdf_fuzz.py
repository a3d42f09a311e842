"""The malformed hand and object URDFs of tests/python/fuzz/corpus_urdf.py through the command line.

Every case runs `python -m graspmix.cli ...` in a subprocess (two at a time) with a timeout; a bad file
must end with exit status 2 and exactly one line on stderr that names what was wrong (the case's
`mentions`), never a crash, a hang or a traceback; a good file must run (exit status 0).
"""

from __future__ import annotations

import importlib.util
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

CORPUS_FILE = Path(__file__).resolve().parents[1] / "fuzz" / "corpus_urdf.py"
TIMEOUT_S = 60  # per case; a case normally takes well under a second


def _load_corpus():
    spec = importlib.util.spec_from_file_location("corpus_urdf", CORPUS_FILE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.CASES


CASES = _load_corpus()


def _run(case: dict) -> dict:
    with tempfile.TemporaryDirectory(prefix="graspmix_fuzz_") as d:
        for name, data in case["files"].items():
            path = Path(d, name)
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_bytes(data)
        argv = [a.replace("{dir}", d) for a in case["argv"]]
        try:
            r = subprocess.run(
                [sys.executable, "-m", "graspmix.cli", *argv],
                cwd=d,
                capture_output=True,
                text=True,
                errors="backslashreplace",
                timeout=TIMEOUT_S,
            )
        except subprocess.TimeoutExpired:
            return {"timeout": True}
        return {
            "timeout": False,
            "returncode": r.returncode,
            "stderr": r.stderr.replace(d, "{dir}"),
            "stdout": r.stdout.replace(d, "{dir}"),
        }


@pytest.fixture(scope="module")
def results() -> dict:
    """Every case's outcome, run two at a time (the subprocesses are independent)."""
    with ThreadPoolExecutor(max_workers=2) as pool:
        return dict(zip((c["name"] for c in CASES), pool.map(_run, CASES)))


def test_corpus_is_well_formed():
    names = [c["name"] for c in CASES]
    assert len(names) == len(set(names))
    assert 50 <= len(CASES) <= 150
    for c in CASES:
        assert c["expect"] in ("error", "ok"), c["name"]
        assert c["expect"] == "ok" or c["mentions"], c["name"]
        assert all(isinstance(v, bytes) for v in c["files"].values()), c["name"]
        assert any("{dir}" in a for a in c["argv"]), c["name"]


@pytest.mark.parametrize("case", CASES, ids=[c["name"] for c in CASES])
def test_case(case, results):
    r = results[case["name"]]
    assert not r["timeout"], f"no answer within {TIMEOUT_S} s"
    assert "Traceback" not in r["stderr"], r["stderr"]
    if case["expect"] == "ok":
        assert r["returncode"] == 0, r["stderr"]
        return
    lines = r["stderr"].splitlines()
    assert r["returncode"] == 2, (r["returncode"], r["stderr"])
    assert len(lines) == 1, r["stderr"]
    assert lines[0].startswith("graspmix_cli "), lines[0]
    assert case["mentions"] in lines[0], lines[0]
