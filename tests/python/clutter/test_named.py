"""The named-target task: the target rule (deterministic, uniform, only objects whose top the camera sees),
the named point (on the target's visible surface, and selecting it in the segmented cloud) on boxes of
known geometry, the classification of an execution (a neighbour lifted instead), the protocol file, a run
folder with a fake unit (resume), the command line's errors, and one tiny real attempt."""

from __future__ import annotations

import dataclasses
import json
import math
from dataclasses import dataclass

import numpy as np
import pytest
from graspmix import clutter
from graspmix.clutter import named
from graspmix.clutter.protocol import clutter_protocol_from_json
from graspmix.clutter.rounds import Plan
from graspmix.experiment.log import AttemptLog, read_rows
from graspmix.model import Grasp
from graspmix.sim.acquisition import Acquisition


def _yaw(yaw):
    return [0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)]


def box_scene(box_urdf, boxes):
    """A SceneSpec of boxes [(size (x, y, z), (x, y), yaw)] standing on the table."""
    from graspmix.sim.scenes import PlacedObject, SceneSpec

    objects = [PlacedObject(str(box_urdf(size)), [x, y, size[2] / 2, *_yaw(yaw)]) for size, (x, y), yaw in boxes]
    return SceneSpec(objects)


# ---- the rule -------------------------------------------------------------------------------------
def test_object_tops_of_boxes(box_urdf):
    spec = box_scene(box_urdf, [((0.04, 0.02, 0.08), (0.03, -0.02), 0.7), ((0.03, 0.03, 0.05), (-0.05, 0.04), 0.0)])
    tops = named.object_tops(spec)
    assert tops == pytest.approx(np.array([[0.03, -0.02, 0.08], [-0.05, 0.04, 0.05]]), abs=1e-6)


def test_the_draw_is_deterministic_and_uniform():
    eligible = [4, 0, 2]
    draws = [named.choose_targets(eligible, 1, seed)[0] for seed in range(600)]
    assert draws == [named.choose_targets(eligible, 1, seed)[0] for seed in range(600)]
    counts = np.bincount(draws, minlength=5)
    assert counts[1] == counts[3] == 0
    # Each of 3 objects about 200 times: 5 binomial standard deviations (about 58) either side.
    assert all(abs(counts[i] - 200) < 58 for i in eligible)
    two = named.choose_targets(eligible, 2, 3)
    assert len(two) == len(set(two)) == 2 and set(two) <= set(eligible)
    assert sorted(named.choose_targets(eligible, 5, 3)) == [0, 2, 4] and named.choose_targets([], 1, 3) == []


@pytest.fixture(scope="module")
def hidden_behind(box_urdf):
    """A tall box, and a short one just behind it as the scene camera sees it (55 cm in front, 45 degrees
    down): the short one's top cannot be seen; a third box apart."""
    from graspmix.sim.scene_camera import acquire_scene

    spec = box_scene(box_urdf, [((0.08, 0.02, 0.10), (0.0, -0.03), 0.0), ((0.04, 0.04, 0.02), (0.0, 0.015), 0.0)])
    spec.objects.append(box_scene(box_urdf, [((0.04, 0.04, 0.04), (0.09, 0.05), 0.3)]).objects[0])
    return spec, acquire_scene(spec)


def test_an_object_whose_top_is_hidden_is_not_eligible(hidden_behind):
    spec, obs = hidden_behind
    tops = named.object_tops(spec)
    assert named.eligible_objects(obs.points, obs.labels, tops) == [0, 2]
    assert np.sum(obs.labels == 1) < named.MIN_TARGET_POINTS  # the short box: hidden
    # The rule's two parts: too few points, or points seen only below the top.
    pts, labels = obs.points, obs.labels
    low = labels == 2
    lowered = pts.copy()
    lowered[low, 2] -= 1.5 * named.TOP_VISIBLE_TOLERANCE
    assert named.eligible_objects(lowered, labels, tops) == [0]
    few = labels.copy()
    few[np.flatnonzero(low)[named.MIN_TARGET_POINTS - 1 :]] = -1
    assert named.eligible_objects(pts, few, tops) == [0]


def test_the_named_point_is_on_the_target_and_selects_it(hidden_behind):
    from graspmix.perception import segment_scene

    spec, obs = hidden_behind
    tops = named.object_tops(spec)
    scene = segment_scene(obs.points, viewpoints=obs.viewpoints)
    for target in (0, 2):
        p = named.named_point(obs.points, obs.labels, target, tops[target])
        dist = [np.linalg.norm(obs.points[obs.labels == i] - p, axis=1).min(initial=np.inf) for i in range(3)]
        assert dist[target] < 0.003 and all(d > dist[target] + 0.01 for i, d in enumerate(dist) if i != target)
        assert p[2] == pytest.approx(tops[target][2], abs=0.002)  # on the top face
        assert np.linalg.norm(p[:2] - tops[target][:2]) < 0.01
        index = scene.select(named.point_target(p))[0]
        assert named.cluster_of(scene, index, obs.labels) == target


# ---- the outcome ----------------------------------------------------------------------------------
@dataclass
class Result:
    success: bool
    reason: str
    lift_height: float


@dataclass
class Execution:
    result: Result
    lifted: list
    moved: list


def _grasp():
    return Grasp([0.0, 0.0, 0.3, 1.0, 0.0, 0.0, 0.0], {"finger_left_joint": 0.05}, {"finger_left_joint": 0.0})


def _stages(execution):
    plan = lambda obs, text, seed: (Plan(_grasp(), 1, 3, 0.01, 0.1), 1)  # noqa: E731
    return named.NamedStages(plan, lambda spec, grasp: execution)


def test_a_neighbour_lifted_is_a_wrong_object(box_urdf):
    spec = box_scene(box_urdf, [((0.04, 0.04, 0.04), (x, 0.0), 0.0) for x in (-0.06, 0.0, 0.06)])
    point = np.array([0.0, 0.0, 0.04])
    wrong = Execution(Result(True, "success", 0.2), [1], [0.0, 0.2, 0.0])
    row = named.named_attempt(spec, None, 0, point, _stages(wrong), 7)
    assert (row["outcome"], row["success"], row["lifted"], row["target"]) == ("wrong object", 0, "1", 0)
    assert row["point"] == "0.0000,0.0000,0.0400" and row["cluster"] == 1 and row["synthesis_seed"] == 7
    right = named.named_attempt(spec, None, 1, point, _stages(wrong), 7)
    assert (right["outcome"], right["success"]) == ("success", 1)
    two = Execution(Result(False, "two objects lifted", 0.2), [0, 1], [0.2, 0.2, 0.0])
    assert named.named_attempt(spec, None, 1, point, _stages(two), 7)["outcome"] == "two objects lifted"
    assert named.classify("not held", [], 2) == "not held"
    with pytest.raises(ValueError, match="one object"):
        named.classify("success", [0, 1], 0)

    def no_object(obs, text, seed):
        raise ValueError(f"target: the point {text} is 0.2 m from the nearest object")

    failed = named.named_attempt(spec, None, 1, point, named.NamedStages(no_object, None), 7)
    assert failed["outcome"] == "synthesis failed" and "nearest object" in failed["error"] and failed["lifted"] == ""


# ---- the protocol, the run folder, the command line -------------------------------------------------
@pytest.fixture
def object_list(tmp_path):
    path = tmp_path / "objects.txt"
    path.write_text("".join(f"random_urdfs/{i:03d}/{i:03d}.urdf\n" for i in range(6)))
    return str(path)


def test_the_protocol_file_round_trips(object_list):
    p = clutter.ClutterProtocol(object_list=object_list, objects=3, scenes=2, task="named", targets=2, modes=["packed"])
    d = json.loads(json.dumps(p.to_json()))
    assert d["task"] == "named" and d["targets"] == 2
    assert clutter_protocol_from_json(d) == p
    assert p.rounds()[:2] == [("packed", 0, "gmm", 0), ("packed", 0, "gmm", 1)] and len(p.rounds()) == 4
    clear = clutter.ClutterProtocol(object_list=object_list, objects=3)
    assert "task" not in clear.to_json() and clutter_protocol_from_json(clear.to_json()) == clear
    # One camera: the planners get its depth image by default, several: the points; a clutter.json written before
    # the option (no "cloud") was the points, and a points protocol's is written as then, so those folders resume.
    assert p.cloud == "image" and p.to_json()["cloud"] == "image"
    assert clutter.ClutterProtocol(object_list=object_list, objects=3, views=4).cloud == "scene"
    points = clutter.ClutterProtocol(object_list=object_list, objects=3, task="named", cloud="scene")
    assert "cloud" not in points.to_json() and clutter_protocol_from_json(points.to_json()) == points
    old = p.to_json()
    del old["cloud"]
    assert clutter_protocol_from_json(old).cloud == "scene"
    for kw, msg in (
        ({"cloud": "voxels"}, "cloud must be one of"),
        ({"cloud": "image", "views": 4}, "views must be 1"),
        ({"task": "fetch"}, "task must be one of"),
        ({"targets": 2}, "for the named task only"),
        ({"task": "named", "max_attempts": 3}, "for the clear task only"),
        ({"task": "named", "targets": 4}, "must not exceed"),
    ):
        with pytest.raises(ValueError, match=msg):
            clutter.ClutterProtocol(object_list=object_list, objects=3, **kw)


def test_object_labels_follow_the_input_the_planner_gets(object_list):
    """Scene.sources index the planner's input: the observation's points, or its image's pixels (row v * width + u);
    the simulator's labels come per observed point, in pixel order."""
    depth = np.array([[0.5, np.inf, 0.6], [np.inf, 0.7, 0.8]])
    obs = Acquisition(np.zeros((4, 3)), np.zeros((4, 3)), np.zeros(4), [depth], np.zeros(7), [], False, 0,
                      labels=np.array([-1, 0, 1, 1]))  # fmt: skip
    points = clutter.ClutterProtocol(object_list=object_list, objects=3, cloud="scene")
    image = clutter.ClutterProtocol(object_list=object_list, objects=3, cloud="image")
    np.testing.assert_array_equal(points.object_labels(obs), [-1, 0, 1, 1])
    np.testing.assert_array_equal(image.object_labels(obs), [-1, -2, 0, -2, 1, 1])
    assert image.object_labels(dataclasses.replace(obs, labels=None)) is None


def fake_named(pdoc, unit, todo=None):
    """A named unit with scripted outcomes from the protocol's seeds; scene 1's second pick has no target."""
    p = clutter_protocol_from_json(pdoc)
    mode, scene, method, pick = unit[0], int(unit[1]), unit[2], int(unit[3])
    rng = np.random.default_rng(p.scene_seed(mode, scene) + pick)
    outcome = rng.choice(["success", "success", "wrong object", "not held"])
    if scene == 1 and pick == 1:
        outcome = named.NO_TARGET
    row = {c: "" for c in named.NAMED_CSV.columns}
    row.update(mode=mode, scene=scene, method=method, pick=pick, placed=3, eligible=1 if scene == 1 else 3)
    row.update(outcome=outcome, success=int(outcome == "success"), target=pick, cluster=pick, t_observe=0.1)
    return [row]


def test_a_named_run_resumes_and_reports(tmp_path, object_list):
    p = clutter.ClutterProtocol(object_list=object_list, objects=3, scenes=3, task="named", targets=2, modes=["packed"])
    ref = clutter.run_clutter(p, tmp_path / "ref", progress=False, round_fn=fake_named)
    assert ref["rounds"] == ref["total"] == 6
    part = clutter.run_clutter(p, tmp_path / "part", progress=False, report=False, max_rounds=4, round_fn=fake_named)
    again = clutter.run_clutter(p, tmp_path / "part", progress=False, round_fn=fake_named)
    assert (part["rounds"], again["skipped"], again["ran"]) == (4, 4, 2)
    rows = read_rows(tmp_path / "ref" / named.NAMED_CSV_NAME, named.NAMED_CSV)
    s = json.loads((tmp_path / "ref" / "summary.json").read_text())
    assert json.loads((tmp_path / "part" / "summary.json").read_text())["results"] == s["results"]
    c = s["results"]["packed"]["gmm"]
    tried = [r for r in rows if r["outcome"] != named.NO_TARGET]
    assert c["attempts"] == len(tried) == 5 and c["excluded"]["picks"] == 1 and c["excluded"]["scenes"] == 1
    assert c["success"]["successes"] == sum(r["success"] for r in rows)
    assert c["outcomes"].get("wrong object", 0) == sum(r["outcome"] == "wrong object" for r in rows)
    assert "| packed | gmm | 3 | 5 |" in (tmp_path / "ref" / "report.md").read_text()
    # Another protocol in the folder is refused; the log's own rows are checked.
    with pytest.raises(ValueError, match="different protocol"):
        clutter.run_clutter(clutter.ClutterProtocol(object_list=object_list, objects=3, scenes=3, task="named",
                                                    modes=["packed"]), tmp_path / "ref", progress=False)  # fmt: skip
    AttemptLog(tmp_path / "ref" / named.NAMED_CSV_NAME, named.NAMED_CSV).append(
        [{**{k: "" if v is None else v for k, v in rows[0].items()}, "pick": 5}]
    )
    with pytest.raises(ValueError, match="pick 5 is not in 0..1"):
        clutter.build_clutter_report(tmp_path / "ref")


def test_cli_bad_named_options(tmp_path, capsys, object_list):
    from graspmix.cli.main import main

    for argv in (
        ["--task", "fetch"],
        ["--targets", "0"],
        ["--targets", "2"],  # the clear task
        ["--task", "named", "--max-attempts", "3"],
        ["--task", "named", "--targets", "4", "--objects", "3", "--object-list", object_list],
    ):
        capsys.readouterr()
        assert main(["clutter", "--out", str(tmp_path / "out"), *argv]) == 2, argv
        err = capsys.readouterr().err.strip()
        assert err.startswith("graspmix_cli clutter: error:") and "\n" not in err, err
    assert not (tmp_path / "out").exists()


# ---- one real attempt ------------------------------------------------------------------------------
@pytest.mark.parametrize("cloud", ["scene", "image"])
def test_one_real_named_attempt(tmp_path, capsys, cloud):
    """One named attempt, the planner given the camera's points (--cloud scene) or its depth image (the default)."""
    from graspmix.cli.main import main
    from graspmix.io import data_path

    out = tmp_path / "run"
    argv = ["clutter", "--task", "named", "--mode", "packed", "--objects", "2", "--scenes", "1", "--quiet",
            "--object-list", str(data_path("objects", "clutter_dev.txt")), "--out", str(out),
            "--cloud", cloud]  # fmt: skip
    assert main(argv) == 0
    printed = capsys.readouterr().out
    (row,) = read_rows(out / named.NAMED_CSV_NAME, named.NAMED_CSV)
    assert row["outcome"] in named.NAMED_OUTCOMES and 1 <= row["eligible"] <= row["placed"] <= 2
    assert 0 <= row["target"] < row["placed"] and row["observe_seed"] is not None
    assert 0 <= row["cluster"] < row["placed"]  # the chosen segment's points (or pixels) mostly one placed object's
    summary = json.loads((out / "summary.json").read_text())
    c = summary["results"]["packed"]["gmm"]
    assert c["attempts"] == 1 and c["success"]["successes"] == row["success"]
    assert "success (95% CI)" in printed and "a neighbour instead" in printed
