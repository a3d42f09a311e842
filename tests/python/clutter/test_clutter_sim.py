"""The clutter protocol on the real stages (simulated scenes, one camera, GMM synthesis, Bullet): a tiny
run, its counts against its own rows, determinism across runs, and the README's bundled example scene
through the three commands with their defaults."""

from __future__ import annotations

import csv
import json

import pytest
from graspmix.cli.main import main
from graspmix.io import data_path

TIMES = {"t_observe", "t_segment", "t_synthesis", "t_execution"}


def _run(out, capsys):
    rc = main(
        [
            "clutter",
            "--mode",
            "packed",
            "--method",
            "gmm,topdown",
            "--objects",
            "2",
            "--scenes",
            "1",
            "--out",
            str(out),
            "--quiet",
        ]  # fmt: skip
    )
    capsys.readouterr()
    assert rc == 0
    with open(out / "clutter_attempts.csv") as f:
        rows = list(csv.DictReader(f))
    return rows, json.loads((out / "summary.json").read_text())


def test_tiny_real_run_counts_and_determinism(tmp_path, capsys):
    rows, summary = _run(tmp_path / "a", capsys)
    again, _ = _run(tmp_path / "b", capsys)
    strip = [{k: v for k, v in r.items() if k not in TIMES} for r in rows]
    assert strip == [{k: v for k, v in r.items() if k not in TIMES} for r in again]
    for method in ("gmm", "topdown"):
        mine = [r for r in rows if r["method"] == method]
        assert mine, method
        # Every round ends once, with a stated reason, within the attempt cap (objects + 2).
        assert [bool(r["stop"]) for r in mine] == [False] * (len(mine) - 1) + [True]
        assert len(mine) <= 2 + 2
        successes = sum(int(r["success"]) for r in mine)
        placed = int(mine[0]["placed"])
        res = summary["results"]["packed"][method]
        assert res["gsr"]["rate"] == pytest.approx(successes / len(mine))
        assert res["dr"]["rate"] == pytest.approx(successes / placed)
        # The table empties one object per success.
        for a, b in zip(mine, mine[1:]):
            assert int(b["before"]) == int(a["after"])
            assert int(a["before"]) - int(a["after"]) >= int(a["success"])


def test_bundled_scene_three_commands_lift_the_named_object(tmp_path, capsys):
    # The README's first command, then the execution it leads to.
    grasps = tmp_path / "grasps.json"
    target = "point:-0.05,-0.1,0.06"  # random_urdfs/121, object 0 of the scene file
    assert main(["synthesize", "--cloud", str(data_path("scenes", "packed4.pcd")), "--target", target,
                 "--out", str(grasps)]) == 0  # fmt: skip
    assert main(["execute", "--scene", str(data_path("scenes", "packed4.json")), "--grasps", str(grasps),
                 "--json"]) == 0  # fmt: skip
    result = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    assert result["success"] and result["lifted"] == [0]
