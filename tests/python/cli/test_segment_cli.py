"""graspmix_cli segment and the view flags (cli/views.py) on a rendered scene saved as files; the per-point
viewpoints of a multi-camera acquisition (acquire --views 4) read back by segment and synthesize."""

import json

import numpy as np
import pytest
from graspmix import _core
from graspmix.cli.main import main
from graspmix.sim.acquisition import AcquisitionSettings, Camera, acquire

EYE = (0.5, 0.1, 0.45)


@pytest.fixture(scope="module")
def clouds(tmp_path_factory):
    d = tmp_path_factory.mktemp("segment")
    acq = acquire("objects/mug.urdf", seed=1, settings=AcquisitionSettings(cameras=[Camera(eye=EYE)], keep="scene"))
    _core.save_cloud(str(d / "scene.pcd"), acq.points, viewpoint=[*EYE, 0, 0, 0, 1])
    np.save(d / "world.npy", acq.points)
    # the same cloud in the camera's frame: camera at EYE, rotated 90 degrees about z (q = [0, 0, s, s])
    s = np.sqrt(0.5)
    R = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    np.save(d / "camera.npy", (acq.points - EYE) @ R)
    return d, [*EYE, 0.0, 0.0, s, s]


def _json(capsys, argv):
    assert main(argv) == 0
    return json.loads(capsys.readouterr().out)


def test_segment_reads_the_pcd_viewpoint_and_draws(clouds, capsys):
    d, _ = clouds
    assert main(["segment", "--cloud", str(d / "scene.pcd"), "--png", str(d / "s.png")]) == 0
    out = capsys.readouterr().out
    assert out.startswith("plane: found [") and "support" in out and "objects: " in out
    assert (d / "s.png").stat().st_size > 10000
    r = _json(capsys, ["segment", "--cloud", str(d / "scene.pcd"), "--json"])
    assert r["plane"][2] > 0.999 and r["objects"]
    # the same cloud as .npy (no viewpoint in the file) with the camera given by the flag
    f = _json(capsys, ["segment", "--cloud", str(d / "world.npy"), "--viewpoint", ",".join(map(str, EYE)), "--json"])
    assert f["objects"] == r["objects"]


def test_camera_pose_gives_world_results(clouds, capsys):
    d, pose = clouds
    world = _json(
        capsys, ["segment", "--cloud", str(d / "world.npy"), "--viewpoint", ",".join(map(str, EYE)), "--json"]
    )
    cam = _json(
        capsys, ["segment", "--cloud", str(d / "camera.npy"), "--camera-pose", ",".join(map(str, pose)), "--json"]
    )
    assert len(cam["objects"]) == len(world["objects"])
    np.testing.assert_allclose(cam["plane"], world["plane"], atol=2e-3)
    np.testing.assert_allclose(cam["objects"][0]["centroid"], world["objects"][0]["centroid"], atol=3e-3)


@pytest.mark.parametrize(
    "flags, message",
    [
        (["--camera-pose", "0,0,0,0,0,0.5,1"], "not a unit quaternion"),
        (["--viewpoint", "1,2"], "--viewpoint: expected 3"),
        (["--viewpoint", "0,0,1", "--camera-pose", "0,0,0,0,0,0,1"], "give one"),
        (["--plane", "0,0,0,1"], "--plane"),
        (["--plane", "0,0,1,-0.5"], "no object above the support plane"),
    ],
)
def test_bad_view_inputs_are_one_line_and_exit_2(clouds, capsys, flags, message):
    d, _ = clouds
    assert main(["segment", "--cloud", str(d / "world.npy"), *flags]) == 2
    err = capsys.readouterr().err
    assert message in err and err.count("\n") == 1


def test_acquire_views_4_writes_per_point_viewpoints_that_segment_and_synthesize_use(tmp_path, capsys):
    from graspmix.sim import scene_camera, scenes

    scene, cloud = tmp_path / "scene.json", tmp_path / "s4.pcd"
    assert main(["scene", "--objects", "3", "--mode", "packed", "--seed", "2", "--out", str(scene)]) == 0
    assert main(["acquire", "--scene", str(scene), "--views", "4", "--out", str(cloud)]) == 0
    assert "per-point viewpoints" in capsys.readouterr().out
    # The file holds the camera that saw each point, as the renderer made them.
    truth = scene_camera.acquire_scene(scenes.SceneSpec.load(str(scene)), views=4)
    c = _core.load_cloud(str(cloud))
    assert not c.has_viewpoint
    np.testing.assert_array_equal(c.viewpoints, truth.viewpoints.astype(np.float32))
    # segment orients the table towards those cameras and finds the three objects; the same points without
    # the viewpoints (a camera at the origin, in the table's plane) give no support plane, and since the plane
    # refused is most of the cloud, the error asks for the camera.
    r = _json(capsys, ["segment", "--cloud", str(cloud), "--json"])
    assert r["plane_found"] and r["plane"][2] > 0.999 and abs(r["plane"][3]) < 2e-3
    assert len(r["objects"]) == len(set(truth.labels[truth.labels >= 0]))
    _core.save_cloud(str(tmp_path / "bare.pcd"), c.points)
    assert main(["segment", "--cloud", str(tmp_path / "bare.pcd"), "--json"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "refused as the support only because the camera is in it" in err
    grasps = tmp_path / "g.json"
    assert main(["synthesize", "--cloud", str(cloud), "--target", "largest", "--out", str(grasps)]) == 0
    doc = json.loads(grasps.read_text())
    largest = max(r["objects"], key=lambda o: o["n_points"])
    assert doc["grasps"] and all(g["object"]["index"] == largest["index"] for g in doc["grasps"])
    assert all(g["T_world_wrist"][2] > 0 for g in doc["grasps"])  # above the table the viewpoints oriented
