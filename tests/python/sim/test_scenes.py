"""Scenes in the simulation: the scene file, building, settling (against pybullet), observing (labels
against the renderer's geometry), executing a grasp among several objects, and the CLI's bad input."""

from __future__ import annotations

import json

import numpy as np
import pytest
from graspmix.cli.main import main
from graspmix.sim import execution, scenes
from graspmix.sim.scene_camera import SCENE_CAMERA, acquire_scene

MUG = "random_urdfs/000/000.urdf"


@pytest.fixture
def box(tmp_path):
    """A 4 x 4 x 4 cm box of 100 g."""
    p = tmp_path / "cube.urdf"
    p.write_text(
        '<?xml version="1.0"?><robot name="cube"><link name="cube"><contact><lateral_friction value="0.8"/>'
        '</contact><inertial><mass value="0.1"/><inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/>'
        '</inertial><collision><geometry><box size="0.04 0.04 0.04"/></geometry></collision><visual><geometry>'
        '<box size="0.04 0.04 0.04"/></geometry></visual></link></robot>'
    )
    return str(p)


def two_boxes(box, gap_y=0.1) -> scenes.SceneSpec:
    return scenes.SceneSpec(
        [scenes.PlacedObject(box, [0, 0, 0.02, 0, 0, 0, 1]), scenes.PlacedObject(box, [0, gap_y, 0.02, 0, 0, 0, 1])]
    )


def test_grasp_on_one_of_two_boxes_lifts_it_and_not_the_other(box):
    spec = two_boxes(box)
    grasp = execution.top_grasp((0, 0), 0.035, 0.018)
    ex = scenes.execute_in_scene(spec, grasp)
    assert ex.result.success and ex.outcome == "success"
    assert ex.lifted == [0]
    assert ex.moved[1] < 1e-3 and ex.moved[0] > 0.1
    assert len(ex.remaining.objects) == 1
    np.testing.assert_allclose(ex.remaining.objects[0].pose[:3], [0, 0.1, 0.02], atol=1e-3)


def test_grasp_straddling_two_touching_boxes_lifts_two(tmp_path):
    p = tmp_path / "half.urdf"
    p.write_text(
        '<?xml version="1.0"?><robot name="half"><link name="half"><inertial><mass value="0.1"/><inertia ixx="1" '
        'ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial><collision><geometry><box size="0.02 0.04 0.04"/>'
        "</geometry></collision></link></robot>"
    )
    spec = scenes.SceneSpec([scenes.PlacedObject(str(p), [x, 0, 0.02, 0, 0, 0, 1]) for x in (-0.01, 0.01)])
    ex = scenes.execute_in_scene(spec, execution.top_grasp((0, 0), 0.035, 0.018))
    assert ex.outcome == "two objects lifted" and not ex.result.success
    assert ex.lifted == [0, 1] and ex.remaining.objects == []


def test_settled_box_rests_at_its_height_and_pybullet_agrees(box):
    import pybullet as p

    spec = scenes.SceneSpec([scenes.PlacedObject(box, [0.03, -0.02, 0.12, 0, 0, 0.3826834, 0.9238795])])
    settled = scenes.settle(spec)
    np.testing.assert_allclose(settled.poses[0, :3], [0.03, -0.02, 0.02], atol=1e-3)
    # pybullet, from the same start, with its own engine settings
    cid = p.connect(p.DIRECT)
    try:
        from graspmix.io import pybullet_data_path

        p.setAdditionalSearchPath(str(pybullet_data_path()), physicsClientId=cid)
        p.setGravity(0, 0, -9.81, physicsClientId=cid)
        p.loadURDF("plane.urdf", physicsClientId=cid)
        body = p.loadURDF(box, [0.03, -0.02, 0.12], [0, 0, 0.3826834, 0.9238795], physicsClientId=cid)
        for _ in range(720):
            p.stepSimulation(physicsClientId=cid)
        pos, orn = p.getBasePositionAndOrientation(body, physicsClientId=cid)
    finally:
        p.disconnect(cid)
    np.testing.assert_allclose(settled.poses[0, :3], pos, atol=2e-3)
    assert abs(abs(np.dot(settled.poses[0, 3:], orn)) - 1) < 1e-4


@pytest.mark.parametrize("mode", scenes.MODES)
def test_make_scene_is_deterministic_at_rest_and_in_the_workspace(mode):
    objects = [MUG, "random_urdfs/001/001.urdf", "random_urdfs/002/002.urdf"]
    a = scenes.make_scene(objects, mode, seed=3)
    b = scenes.make_scene(objects, mode, seed=3)
    assert a.to_dict() == b.to_dict() and a.mode == mode and len(a.objects) >= 1
    x0, y0, x1, y1 = scenes.WORKSPACE
    assert np.all((a.poses[:, 0] >= x0) & (a.poses[:, 0] <= x1) & (a.poses[:, 1] >= y0) & (a.poses[:, 1] <= y1))
    # at rest: settling it again moves nothing
    again = scenes.settle(a)
    assert np.abs(again.poses[:, :3] - a.poses[:, :3]).max() < 2e-3


def test_acquire_scene_labels_follow_the_objects(box):
    spec = two_boxes(box, gap_y=0.08)
    acq = acquire_scene(spec)
    assert acq.points.shape[0] == SCENE_CAMERA.width * SCENE_CAMERA.height  # the table fills the view
    np.testing.assert_allclose(acq.viewpoints, np.tile(SCENE_CAMERA.eye, (len(acq.points), 1)))
    for i, (x, y) in enumerate([(0, 0), (0, 0.08)]):
        pts = acq.points[acq.labels == i]
        assert len(pts) > 100
        # every point labelled i is on box i's surface (a 4 cm cube at (x, y, 0.02))
        d = np.abs(pts - [x, y, 0.02]).max(axis=1)
        np.testing.assert_allclose(d, 0.02, atol=1e-3)
    np.testing.assert_allclose(acq.points[acq.labels == -1][:, 2], 0.0, atol=1e-3)
    ring = acquire_scene(spec, views=4, keep="object")
    assert len(ring.cameras) == 4 and np.all(ring.labels >= 0)


def test_scene_file_round_trip_and_errors(box, tmp_path):
    spec = two_boxes(box)
    spec.save(tmp_path / "s.json")
    loaded = scenes.SceneSpec.load(tmp_path / "s.json")
    np.testing.assert_array_equal(loaded.poses, spec.poses)
    assert len(loaded.without(0).objects) == 1
    doc = json.loads((tmp_path / "s.json").read_text())
    for mutate, message in (
        (lambda d: d["objects"][1].update(urdf="missing.urdf"), "scene object 1"),
        (lambda d: d["objects"][0].update(pose=[0, 0, 0, 0, 0, 0, 2]), "length 2"),
        (lambda d: d["objects"][0].update(pose=[0, 0, 0]), "pose"),
    ):
        bad = json.loads(json.dumps(doc))
        mutate(bad)
        (tmp_path / "bad.json").write_text(json.dumps(bad))
        with pytest.raises(ValueError, match=message):
            scenes.SceneSpec.load(tmp_path / "bad.json")


def test_cli_scene_acquire_execute(tmp_path, box, capsys):
    spec = two_boxes(box)
    spec.save(tmp_path / "s.json")
    (tmp_path / "g.json").write_text(
        json.dumps({"format": "graspmix.grasps/1", "grasps": [execution.top_grasp((0, 0.1), 0.035, 0.018).to_dict()]})
    )
    assert main(["acquire", "--scene", str(tmp_path / "s.json"), "--out", str(tmp_path / "c.pcd")]) == 0
    assert b"VIEWPOINT 0 -0.55 0.55" in (tmp_path / "c.pcd").read_bytes()[:400]
    args = ["execute", "--scene", str(tmp_path / "s.json"), "--grasps", str(tmp_path / "g.json")]
    assert main([*args, "--json", "--out-scene", str(tmp_path / "r.json")]) == 0
    out = json.loads(capsys.readouterr().out.strip().splitlines()[-1])
    assert out["lifted"] == [1] and out["success"]
    assert len(scenes.SceneSpec.load(tmp_path / "r.json").objects) == 1
    assert main(["scene", "--objects", "0", "--mode", "pile", "--out", str(tmp_path / "x.json")]) == 2
    (tmp_path / "bad.json").write_text(
        json.dumps({"format": "graspmix.scene/1", "objects": [{"urdf": "nope.urdf", "pose": [0, 0, 0, 0, 0, 0, 1]}]})
    )
    assert main(["execute", "--scene", str(tmp_path / "bad.json"), "--grasps", str(tmp_path / "g.json")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 2 and "nope.urdf" in err[-1]
