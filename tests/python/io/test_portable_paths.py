"""Files that name other files load on another machine: every writer (Demonstration.save, GraspModel.save,
GraspSet.save, SceneSpec.save) names the bundled data as package://graspmix/..., pybullet_data's files as
pybullet_data://... (scenes: relative to pybullet_data, their format's form) and anything else relative to
the file. Each test saves into one folder, moves the folder and loads from the new place."""

import json
import shutil

import numpy as np
import pybullet_data
from graspmix import Demonstration, GraspModel, GraspSet, default_model_path
from graspmix.io import (
    PYBULLET_DATA_PREFIX,
    data_path,
    object_reference,
    relative_path,
    resolve_object,
    resolve_path,
)
from graspmix.sim.scenes import PlacedObject, SceneSpec

PB = pybullet_data.getDataPath()
WSG50 = data_path("hands", "wsg50.urdf")
IDENTITY = [0, 0, 0, 0, 0, 0, 1.0]


def move(tmp_path, name="a"):
    """Moves tmp_path/name to tmp_path/moved/name and returns the new folder."""
    dest = tmp_path / "moved" / name
    dest.parent.mkdir()
    shutil.move(str(tmp_path / name), dest)
    return dest


def test_pybullet_data_scheme_resolves_against_the_installed_package(tmp_path):
    pr2 = f"{PB}/pr2_gripper.urdf"
    text = relative_path(pr2, tmp_path)
    assert text == PYBULLET_DATA_PREFIX + "pr2_gripper.urdf"
    assert resolve_path(text, tmp_path) == resolve_path(text, tmp_path / "elsewhere")
    assert resolve_path(text, tmp_path).samefile(pr2)
    assert resolve_object(text).samefile(pr2) and resolve_object("package://graspmix/objects/box.urdf").is_file()


def test_demonstration_moves_with_its_cloud(tmp_path):
    a = tmp_path / "a"
    a.mkdir()
    shutil.copy(data_path("demos", "box.pcd"), a / "box.pcd")
    hand = f"{PB}/pr2_gripper.urdf"
    demo = Demonstration(hand, np.zeros((1, 3)), np.array(IDENTITY), {"j": 0.1}, {"j": 0.0}, a / "box.pcd")
    demo.save(a / "demo.json")
    doc = json.loads((a / "demo.json").read_text())
    assert doc["hand"] == "pybullet_data://pr2_gripper.urdf" and doc["cloud"] == "box.pcd"
    b = move(tmp_path)
    loaded = Demonstration.load(b / "demo.json")
    assert loaded.hand_path.samefile(hand) and loaded.cloud_path.samefile(b / "box.pcd")
    np.testing.assert_array_equal(loaded.T_world_wrist, IDENTITY)


def test_model_with_its_own_hand_moves(tmp_path):
    a = tmp_path / "a"
    a.mkdir()
    shutil.copy(WSG50, a / "hand.urdf")
    model = GraspModel.load(default_model_path("gmm"))
    model.hand_path = a / "hand.urdf"
    model.save(a / "model.json")
    doc = json.loads((a / "model.json").read_text())
    assert doc["hand"] == "hand.urdf" and doc["types"][0]["demonstration"] == "package://graspmix/demos/box_wsg50.json"
    b = move(tmp_path)
    loaded = GraspModel.load(b / "model.json")
    assert loaded.hand_path.samefile(b / "hand.urdf")
    assert loaded.demo is not None and data_path("demos", "box_wsg50.json").samefile(loaded.demo)


def test_grasps_file_names_its_hand_portably(tmp_path):
    a = tmp_path / "a"
    a.mkdir()
    shutil.copy(data_path("demos", "box.pcd"), a / "c.pcd")
    GraspSet([], f"{PB}/pr2_gripper.urdf", "gmm", str(a / "c.pcd"), {}).save(a / "grasps.json")
    GraspSet([], WSG50, "gmm", str(a / "c.pcd"), {}).save(a / "wsg.json")
    b = move(tmp_path)
    pr2, wsg = (json.loads((b / f).read_text()) for f in ("grasps.json", "wsg.json"))
    assert pr2["hand"] == "pybullet_data://pr2_gripper.urdf" and wsg["hand"] == "package://graspmix/hands/wsg50.urdf"
    assert resolve_path(pr2["hand"], b).samefile(f"{PB}/pr2_gripper.urdf")
    assert resolve_path(pr2["cloud"], b).samefile(b / "c.pcd")


def test_scene_moves_with_its_objects(tmp_path):
    a = tmp_path / "a"
    (a / "obj").mkdir(parents=True)
    shutil.copy(data_path("objects", "box.urdf"), a / "obj" / "mine.urdf")
    spec = SceneSpec(
        [
            PlacedObject(f"{PB}/random_urdfs/012/012.urdf", np.array([0, 0, 0.05, 0, 0, 0, 1.0])),
            PlacedObject(str(a / "obj" / "mine.urdf"), np.array([0.1, 0, 0.05, 0, 0, 0, 1.0])),
            PlacedObject(str(data_path("objects", "box.urdf")), np.array([-0.1, 0, 0.05, 0, 0, 0, 1.0])),
        ]
    )
    spec.save(a / "scene.json")
    names = [o["urdf"] for o in json.loads((a / "scene.json").read_text())["objects"]]
    assert names == ["random_urdfs/012/012.urdf", "obj/mine.urdf", "package://graspmix/objects/box.urdf"]
    b = move(tmp_path)
    loaded = SceneSpec.load(b / "scene.json")
    assert resolve_object(loaded.objects[1].urdf).samefile(b / "obj" / "mine.urdf")
    assert resolve_object(loaded.objects[0].urdf).samefile(f"{PB}/random_urdfs/012/012.urdf")
    np.testing.assert_array_equal(loaded.poses, spec.poses)
    assert object_reference(loaded.objects[2].urdf, b) == names[2]
