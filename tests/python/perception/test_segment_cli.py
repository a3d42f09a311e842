"""graspmix_cli segment and the view flags (cli/views.py) on a rendered scene saved as files."""

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
