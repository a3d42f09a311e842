"""scripts/hands_trial.py (issue 27's trial of any hand): bad arguments are one line and exit status 2 before any
work; one development object with the WSG 50 runs the user's commands and records what they did."""

import importlib.util
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[3]
SCRIPT = REPO / "scripts" / "hands_trial.py"
DEV = REPO / "data" / "objects" / "clutter_dev.txt"  # not the held-out list: nothing is judged on it here


@pytest.mark.parametrize(
    "argv, names",
    [
        (["--hands", "wsg50,shadow"], "shadow"),
        (["--hands", "panda,panda"], "twice"),
        (["--count", "0"], "--count"),
        (["--count", "61"], "lists 60 objects"),
        (["--objects", "no/such/list.txt"], "no/such/list.txt"),
        (["--seed", "-1"], "--seed"),
        (["--views", "1"], "--views"),
    ],
)
def test_bad_arguments_are_one_line_and_exit_2(tmp_path, argv, names):
    out = tmp_path / "out"
    done = subprocess.run([sys.executable, str(SCRIPT), str(out), *argv], capture_output=True, text=True)
    assert done.returncode == 2
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and names in lines[0], done.stderr
    assert done.stdout == "" and not out.exists()  # nothing done


def load_script():
    spec = importlib.util.spec_from_file_location("hands_trial", SCRIPT)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_one_object_with_the_wsg50(tmp_path, capsys):
    from graspmix import GraspSet, _core
    from graspmix.io import read_objects_file
    from graspmix.sim import rest_pose

    trial = load_script()
    out = tmp_path / "trial"
    assert trial.main([str(out), "--hands", "wsg50", "--objects", str(DEV), "--count", "1", "--seed", "5"]) == 0
    obj = read_objects_file(DEV)[0]
    doc = json.loads((out / "results.json").read_text())
    (row,) = doc["attempts"]["wsg50"]
    s = doc["summary"]["wsg50"]
    # The summary counts the rows; the WSG 50 is its own reference.
    assert s["lifted"] == int(row["lifted"]) and s["n"] == 1 and s["ratio_to_wsg50"] == pytest.approx(1.0)
    assert [f["object"] for f in s["failed"]] == ([] if row["lifted"] else [obj])
    assert row["outcome"] in ("success", "not held", "no contact", "start in collision", "synthesis failed")
    # The object was placed where acquire places it, and the commands a user would type were the ones run.
    np.testing.assert_allclose(doc["objects"][0]["pose"], rest_pose(obj))
    commands = (out / "commands.sh").read_text().splitlines()
    assert any(c.startswith(f"graspmix_cli acquire --object {obj} --views 4 --noise --seed 5 ") for c in commands)
    assert any(c.startswith("graspmix_cli synthesize --model ") for c in commands)
    # The cloud is the four cameras' (one viewpoint per point, four distinct) and the grasps were made on it.
    cloud = out / "clouds" / doc["objects"][0]["cloud"]
    viewpoints = _core.load_cloud(str(cloud)).viewpoints
    assert len(np.unique(np.round(viewpoints, 6), axis=0)) == 4
    grasps = GraspSet.load(out / row["grasps"])
    assert grasps.best().log_likelihood == pytest.approx(row["log_likelihood"])
    assert f"| wsg50 | {s['lifted']} of 1 |" in (out / "results.md").read_text()
    assert "[1/1]" in capsys.readouterr().out  # progress
