"""One camera's view as its driver gives it (perception/views.py): a depth image with intrinsics or an organized cloud
in the sensor frame, with the camera's pose, segmented in image space, against the same view's points segmented as a
cloud (graspmix.segment_scene) on the bundled packed scene rendered by pybullet; the depth image written as a 16-bit
PNG in millimetres; GraspModel.synthesize and the CLI on each input; bad input naming what is wrong."""

import json
import struct
import warnings
import zlib

import graspmix
import numpy as np
import pytest
from graspmix import _core
from graspmix.cli.main import main
from graspmix.io import data_path
from graspmix.perception import (
    depth_view,
    organized_view,
    read_depth,
    scene_input,
    segment_scene,
    segment_view,
    write_depth,
)
from graspmix.perception.views import NOT_A_CAMERA_VIEW
from graspmix.sim import scene_camera, scenes
from PIL import Image
from scipy.spatial import cKDTree
from scipy.spatial.transform import Rotation


@pytest.fixture(scope="module")
def view(tmp_path_factory):
    """(acquisition, camera, depth in metres with inf = no return, path of the 16-bit PNG in mm) of packed4."""
    spec = scenes.SceneSpec.load(str(data_path("scenes", "packed4.json")))
    acq = scene_camera.acquire_scene(spec, views=1, noise=True, seed=3, keep="scene")
    depth = acq.depth_images[0]
    png = tmp_path_factory.mktemp("views") / "depth.png"
    Image.fromarray(np.where(np.isfinite(depth), np.round(depth * 1000), 0).astype(np.uint16)).save(png)
    return acq, acq.cameras[0], depth, png


def _angle_deg(a, b) -> float:
    return float(np.degrees(np.arccos(np.clip(abs(np.dot(a[:3], b[:3])), -1, 1))))


def _pieces(labels_of_objects) -> dict:
    """{true object: how many segmented objects hold mostly its points}"""
    out = {}
    for labels in labels_of_objects:
        values, counts = np.unique(labels, return_counts=True)
        out[values[np.argmax(counts)]] = out.get(values[np.argmax(counts)], 0) + 1
    return out


def test_depth_image_gives_the_scene_of_its_points(view):
    acq, cam, depth, _ = view
    image = segment_view(depth_view(depth, cam.pinhole(), cam.pose()))
    cloud = segment_scene(acq.points, acq.viewpoints)
    assert image.plane_found and cloud.plane_found
    assert _angle_deg(image.plane, cloud.plane) < 0.05 and abs(image.plane[3] - cloud.plane[3]) < 5e-4
    # Against the renderer's labels (per pixel; the image's sources are pixels): every object the view shows is
    # found, each segmented object holds one object's points (99% of those on objects; under 10% table fringe, the
    # lateral noise's), and an object
    # falls into no more pieces than segment_scene leaves of it on the same view's points.
    pixel_label = np.full(depth.size, -2)
    pixel_label[np.flatnonzero(np.isfinite(depth))] = acq.labels
    of_image = [pixel_label[image.sources[o.rows]] for o in image.objects]
    of_cloud = [acq.labels[cloud.sources[o.rows]] for o in cloud.objects]
    for labels in of_image:
        on = labels[labels >= 0]
        assert np.mean(on == np.bincount(on).argmax()) > 0.99 and np.mean(labels < 0) < 0.1
    pieces_image, pieces_cloud = _pieces(of_image), _pieces(of_cloud)
    assert set(pieces_image) == set(range(len(acq.object_pose)))
    assert all(pieces_image[k] <= pieces_cloud.get(k, 0) for k in pieces_image), (pieces_image, pieces_cloud)
    # the image's visibility model is the camera's own pinhole view
    (v,) = image.visibility.views
    assert v["kind"] == "pinhole" and (v["width"], v["height"]) == (640, 480)
    # sources are pixels: each object point lies within a voxel diagonal of its pixel's point
    pixels = cam.pinhole().back_project(depth).reshape(-1, 3)[image.sources]
    world = depth_view(depth, cam.pinhole(), cam.pose())
    R = Rotation.from_quat(world.pose[3:]).as_matrix()
    assert np.all(np.linalg.norm(pixels @ R.T + world.pose[:3] - image.points, axis=1) < 0.003 * np.sqrt(3) + 1e-9)


def test_organized_cloud_and_millimetre_png_give_the_same_scene(view):
    _, cam, depth, png = view
    a = segment_view(depth_view(depth, cam.pinhole(), cam.pose()))
    b = segment_view(organized_view(cam.pinhole().back_project(depth), cam.pose()))
    assert np.allclose(a.plane, b.plane, atol=1e-9) and len(a.objects) == len(b.objects)
    assert np.allclose(a.points, b.points, atol=1e-6)
    with pytest.raises(ValueError, match="camera is 64 x 48, the cloud 640 x 480"):
        small = _core.PinholeCamera(60, 60, 32, 24, 64, 48)
        _core.segment_organized(cam.pinhole().back_project(depth), cam.pose(), camera=small)
    mm = read_depth(png)
    assert mm.dtype == np.uint16 and mm.shape == depth.shape
    c = segment_view(depth_view(png, cam.pinhole().K, cam.pose()))  # integers: millimetres by default
    assert _angle_deg(a.plane, c.plane) < 0.05
    # rounded to millimetres, the objects are the same but for a small fragment the rounding may leave apart
    big = [o.centroid for o in c.objects if o.n_points >= 300]
    assert len(big) == sum(o.n_points >= 300 for o in a.objects)
    assert all(min(np.linalg.norm(o.centroid - b) for b in big) < 0.003 for o in a.objects if o.n_points >= 300)
    assert c.result.n_input == a.result.n_input  # the PNG keeps every return (0 where the image had inf)
    assert np.array_equal(depth_view(png, cam.pinhole().K, cam.pose()).depth, read_depth(png) * 0.001)


def test_world_points_follow_the_camera_pose(view):
    _, cam, depth, _ = view
    v = depth_view(depth, (cam.pinhole().fx, cam.pinhole().fy, cam.pinhole().cx, cam.pinhole().cy), cam.pose())
    sensor = cam.pinhole().back_project(depth).reshape(-1, 3)
    sensor = sensor[np.all(np.isfinite(sensor), axis=1)]
    expected = Rotation.from_quat(cam.pose()[3:]).apply(sensor) + cam.pose()[:3]
    assert np.allclose(v.world_points(), expected, atol=1e-12)
    assert np.allclose(v.position, cam.eye)


def test_synthesize_takes_each_input_and_answers_in_the_world(view):
    acq, cam, depth, png = view
    model = graspmix.GraspModel.load(graspmix.default_model_path())
    opts = graspmix.SynthesisOptions().updated({"sampling.n_samples": 60})
    target = "point:-0.05,-0.1,0.06"
    a = model.synthesize(depth=depth, intrinsics=cam.pinhole().K, camera_pose=cam.pose(), options=opts, target=target)
    b = model.synthesize(cam.pinhole().back_project(depth), opts, camera_pose=cam.pose(), target=target)
    assert [g.T_world_wrist for g in a[:5]] == [g.T_world_wrist for g in b[:5]]
    # In the world frame (the renderer's points, labelled): the grasps are on the object nearest the point, and the
    # best grasp's tool centre point is within 5 cm of that object's seen points (it may hold the unseen side; a
    # grasp in the camera's frame would be most of a metre off).
    target_points = acq.points[
        acq.labels == acq.labels[np.argmin(np.linalg.norm(acq.points - [-0.05, -0.1, 0.06], axis=1))]
    ]
    tcp = np.asarray(a.best().T_world_tcp[:3])
    assert np.min(np.linalg.norm(target_points - tcp, axis=1)) < 0.05
    # Every grasp on one segment, made of the named object's points (a piece of it: the named segment is tried by the
    # split rule below its size gate, and this object's creases cut it; SegmentationSettings.split_named_max_size).
    on = {g.object["index"] for g in a}
    assert len(on) == 1
    segment = a.scene.objects[on.pop()].points
    nearest = cKDTree(target_points).query(segment)[0]
    assert np.mean(nearest < 0.005) > 0.95
    c = model.synthesize(
        depth=str(png), intrinsics=cam.pinhole().K, camera_pose=cam.pose(), options=opts, target=target
    )
    assert len(c) == len(a) and c.scene.plane_found


@pytest.mark.parametrize(
    "kwargs, words",
    [
        ({"cloud": np.zeros((4, 5, 2))}, "shape (H, W, 3)"),
        ({"depth": np.ones((4, 5))}, "needs its camera's intrinsics"),
        ({"depth": np.ones((48, 64)), "intrinsics": (0, 60, 32, 24)}, "fx"),
        ({"depth": np.ones((48, 64)), "intrinsics": [[60, 1, 32], [0, 60, 24], [0, 0, 1]]}, "pinhole K"),
        ({"depth": -np.ones((48, 64)), "intrinsics": (60, 60, 32, 24)}, "negative"),
        ({"depth": np.full((48, 64), np.nan), "intrinsics": (60, 60, 32, 24)}, "no pixel has a return"),
        # a bare table seen straight on: the table is found and nothing stands on it (once "the cloud is empty")
        ({"depth": np.full((48, 64), 0.8), "intrinsics": (50, 50, 32, 24)}, "no object above the support plane"),
        ({"depth": np.ones((48, 64)), "intrinsics": (60, 60, 32, 24), "camera_pose": [0, 0, 1, 0, 0, 0, 2]}, "unit"),
        ({"depth": np.ones((48, 64)), "intrinsics": (60, 60, 32, 24), "depth_scale": 0}, "depth_scale"),
        # millimetres read as metres: a scene 850 m wide, the voxel grid's error with what to check
        ({"depth": np.full((48, 64), 800.0), "intrinsics": (60, 60, 32, 24)}, "check its depth scale"),
        # text and ragged lists where numbers belong: the argument named, not numpy's words
        ({"depth": np.ones((48, 64)), "intrinsics": "60,60,32,24"}, "intrinsics: expected numbers"),
        ({"depth": np.ones((48, 64)), "intrinsics": [[60, 0, 32], [0, 60]]}, "intrinsics: expected numbers"),
        ({"depth": np.ones((48, 64)), "intrinsics": (60, 60, 32, 24), "camera_pose": "0,0,0,0,0,0,1"}, "camera_pose"),
        ({"depth": np.ones((48, 64)), "intrinsics": (60, 60, 32, 24), "depth_scale": "abc"}, "depth_scale"),
        ({"depth": np.ones((48, 64)), "intrinsics": (60, 60, 32, 24), "depth_scale": [0.001]}, "depth_scale"),
        ({"depth": np.ones((48, 64)), "cloud": np.ones((5, 3)), "intrinsics": (60, 60, 32, 24)}, "not both"),
        ({"cloud": np.ones((5, 3)), "intrinsics": (60, 60, 32, 24)}, "go with a depth image"),
        ({"depth": np.ones((8, 8)), "intrinsics": (6, 6, 4, 4), "viewpoints": [0, 0, 1]}, "give no viewpoints"),
    ],
)
def test_bad_views_name_what_is_wrong(kwargs, words):
    model = graspmix.GraspModel.load(graspmix.default_model_path())
    with pytest.raises(ValueError, match=None) as e:
        model.synthesize(**kwargs)
    assert words in str(e.value), str(e.value)


def test_an_organized_cloud_in_the_world_frame_is_refused(view):
    _, cam, depth, _ = view
    sensor = cam.pinhole().back_project(depth)
    world = Rotation.from_quat(cam.pose()[3:]).apply(sensor.reshape(-1, 3)) + cam.pose()[:3]  # NaN rows stay NaN
    with pytest.raises(ValueError, match="sensor frame"):
        scene_input(world.reshape(sensor.shape))


def test_an_eight_bit_png_is_not_a_depth_image(tmp_path):
    Image.fromarray(np.zeros((8, 8), np.uint8)).save(tmp_path / "d.png")
    with pytest.raises(ValueError, match="16-bit"):
        read_depth(tmp_path / "d.png")


@pytest.mark.parametrize("width, height", [(8000, 6000), (15000, 12000)])  # over our limit; over PIL's own too
def test_a_png_larger_than_a_depth_cameras_is_refused_before_decoding(tmp_path, width, height):
    """The header says the size: a 16-bit grey PNG of zeros written by hand (zlib, not a decoded image)."""

    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))

    z = zlib.compressobj()
    row = b"\0" * (1 + 2 * width)
    data = b"".join(z.compress(row) for _ in range(height)) + z.flush()
    header = struct.pack(">IIBBBBB", width, height, 16, 0, 0, 0, 0)
    path = tmp_path / "big.png"
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", data) + chunk(b"IEND", b""))
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no DecompressionBombWarning on the way
        with pytest.raises(ValueError, match="big.png"):
            read_depth(path)


def test_cli_synthesize_and_segment_on_a_depth_png(view, tmp_path, capsys):
    _, cam, _, png = view
    c = cam.pinhole()
    flags = [
        "--depth",
        str(png),
        "--intrinsics",
        f"{c.fx},{c.fy},{c.cx},{c.cy}",
        f"--camera-pose={','.join(map(str, cam.pose()))}",
    ]
    assert main(["segment", *flags]) == 0
    assert "plane: found" in capsys.readouterr().out
    out = tmp_path / "g.json"
    assert main(["synthesize", *flags, "--samples", "40", "--target", "largest", "--out", str(out)]) == 0
    grasps = graspmix.model.load_grasps(out)
    assert len(grasps["grasps"]) == 40 and grasps["cloud"] == ""  # a depth image is no cloud: the file has its view
    assert (tmp_path / grasps["view"]["depth"]).resolve() == png.resolve()  # relative to g.json's folder
    assert grasps["view"]["depth_scale"] is None
    np.testing.assert_allclose(grasps["view"]["intrinsics"], [c.fx, c.fy, c.cx, c.cy])
    np.testing.assert_allclose(grasps["view"]["camera_pose"], cam.pose())


def test_a_depth_synthesis_file_draws_its_objects(view, tmp_path, capsys):
    """grasps.json of a depth image keeps the view; plot reads the image again and draws the objects on the table:
    every drawn point lies within a voxel of the image's own returns (back-projected here by numpy and scipy),
    above the support plane."""
    _, cam, depth, png = view
    c = cam.pinhole()
    model = graspmix.GraspModel.load(graspmix.default_model_path("gmm"))
    opts = graspmix.SynthesisOptions(sampling=graspmix.SamplingSettings(n_samples=40))
    g = model.synthesize(depth=str(png), intrinsics=(c.fx, c.fy, c.cx, c.cy), camera_pose=cam.pose(), options=opts)
    g.save(tmp_path / "g.json")
    loaded = graspmix.GraspSet.load(tmp_path / "g.json")
    drawn = loaded.view_points()
    v, u = np.nonzero(np.isfinite(depth) & (depth > 0))
    z = np.round(depth[v, u] * 1000) / 1000  # the PNG's millimetres
    sensor = np.column_stack([(u - c.cx) * z / c.fx, (v - c.cy) * z / c.fy, z])
    pose = np.asarray(cam.pose())
    world = Rotation.from_quat(pose[3:]).apply(sensor) + pose[:3]
    gap, _ = cKDTree(world).query(drawn)
    assert len(drawn) > 500 and gap.max() < 0.003
    plane = np.asarray(loaded.plane)
    assert np.all(drawn @ plane[:3] + plane[3] > 0)
    assert main(["plot", "--grasps", str(tmp_path / "g.json"), "--png", str(tmp_path / "p.png")]) == 0
    assert (tmp_path / "p.png").stat().st_size > 0


@pytest.mark.parametrize(
    "argv, words",
    [
        (["--depth", "D"], "--intrinsics"),
        (["--depth", "D", "--intrinsics", "0,1,2,3"], "fx"),
        (["--depth", "D", "--intrinsics", "1,1,2,3", "--viewpoint", "0,0,1"], "--viewpoint with --depth"),
        (["--intrinsics", "1,1,2,3", "--cloud", "C"], "go with --depth"),
    ],
)
def test_cli_bad_depth_flags_exit_2_with_one_line(view, argv, words, tmp_path, capsys):
    _, _, _, png = view
    cloud = tmp_path / "c.npy"
    np.save(cloud, np.ones((10, 3)))
    argv = [str(png) if a == "D" else str(cloud) if a == "C" else a for a in argv]
    assert main(["synthesize", *argv]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and words in err[0], err


def test_organized_pcd_written_by_acquire_is_the_cameras_view(tmp_path, capsys):
    """acquire (one camera) writes the whole image organized, in the world frame, the camera's optical-frame pose
    as VIEWPOINT; read back it is that camera's view (the same scene as its depth image); a world-frame grid with no
    camera is no pinhole image and is taken as points; a VIEWPOINT and --camera-pose together are an error."""
    scene = data_path("scenes", "packed4.json")
    pcd = tmp_path / "view.pcd"
    assert main(["acquire", "--scene", str(scene), "--out", str(pcd)]) == 0
    loaded = _core.load_cloud(str(pcd))
    assert (loaded.width, loaded.height) == (640, 480) and loaded.has_viewpoint
    source, _, notes = scene_input(str(pcd))
    assert notes == []
    acq = scene_camera.acquire_scene(scenes.SceneSpec.load(str(scene)), views=1, noise=False, seed=0, keep="scene")
    cam = acq.cameras[0]
    T = [np.asarray(_core.camera_pose_matrix(p)) for p in (source.pose, cam.pose())]  # q and -q: one rotation
    assert np.allclose(T[0], T[1], atol=1e-6) and np.isclose(source.camera.fx, cam.pinhole().fx, rtol=1e-4)
    a, b = segment_view(source), segment_view(depth_view(acq.depth_images[0], cam.pinhole(), cam.pose()))
    assert np.allclose(a.plane, b.plane, atol=1e-4) and [o.n_points for o in a.objects] == [
        o.n_points for o in b.objects
    ]
    # the same grid with no VIEWPOINT: world-frame points, no camera's image
    bare = tmp_path / "bare.pcd"
    _core.save_cloud(str(bare), np.asarray(loaded.organized()).reshape(-1, 3), width=640, height=480)
    (points, viewpoints), _, notes = scene_input(str(bare))
    assert len(points) == len(loaded.points) and viewpoints is None
    assert notes == [NOT_A_CAMERA_VIEW.format(path=bare)]
    model = graspmix.GraspModel.load(graspmix.default_model_path())
    opts = graspmix.SynthesisOptions().updated({"sampling.n_samples": 20})
    grasps = model.synthesize(str(bare), opts, viewpoints=cam.eye, target="largest")
    assert grasps.scene.notes[0] == notes[0]  # the user is told
    assert main(["synthesize", "--cloud", str(pcd), f"--camera-pose={','.join(map(str, cam.pose()))}"]) == 2
    assert "VIEWPOINT" in capsys.readouterr().err


def test_the_workspace_crops_a_view_before_anything(view, tmp_path, capsys):
    """--workspace / segmentation.workspace: every object of the cropped view lies in the box, and the box's objects
    are those of the whole view whose points are mostly in it; the option survives SynthesisOptions' dict; a box
    that is not one, or holds nothing, is one line and exit 2."""
    _, cam, depth, png = view
    c = cam.pinhole()
    box = [-0.1, -0.2, -0.05, 0.05, 0.0, 0.3]
    v = depth_view(depth, (c.fx, c.fy, c.cx, c.cy), cam.pose())
    whole = segment_view(v)
    cropped = segment_view(v, settings=_core.SegmentationSettings(workspace=box))
    lo, hi = np.array(box[:3]), np.array(box[3:])
    assert len(cropped.objects) >= 1 and np.all((cropped.points >= lo) & (cropped.points <= hi))
    assert len(cropped.objects) < len(whole.objects)
    # Each object of the whole view with most of its points in the box has one in the crop within 2 cm.
    for o in whole.objects:
        pts = whole.points[o.rows]
        if np.mean(np.all((pts >= lo) & (pts <= hi), axis=1)) > 0.9:
            assert min(np.linalg.norm(np.asarray(k.centroid) - o.centroid) for k in cropped.objects) < 0.02
    opts = graspmix.SynthesisOptions().updated({"segmentation.workspace": box})
    assert graspmix.SynthesisOptions.from_dict(opts.to_dict()).segmentation.workspace == box
    flags = ["segment", "--depth", str(png), "--intrinsics", f"{c.fx},{c.fy},{c.cx},{c.cy}"]
    flags.append(f"--camera-pose={','.join(map(str, cam.pose()))}")
    assert main([*flags, f"--workspace={','.join(map(str, box))}"]) == 0
    capsys.readouterr()
    for bad, words in (("1,2,3", "x_min,y_min"), ("0,0,0,0,1,1", "below its maximum"), ("5,5,5,6,6,6", "nothing")):
        assert main([*flags, f"--workspace={bad}"]) == 2
        err = capsys.readouterr().err
        assert words in err and err.count("\n") == 1


@pytest.mark.parametrize("sigma", [0.003, 0.004])
def test_a_noisy_bare_table_seen_from_above_has_no_object_and_a_box_on_it_is_one(sigma):
    """A camera 0.8 m straight above a table, Gaussian depth noise of sigma a pixel (3-4 mm: a depth camera's at
    that range). The table's noise rule measures the fine blocks the objects are made of: before, it measured the
    table on coarse blocks (less scatter, and fewer of them below the table than fine ones above it), gave up, and
    the noise came out as up to 64 objects (the table itself one of 31,818 points at 4 mm)."""
    pose = [0, 0, 0.8, 1, 0, 0, 0]  # looking straight down
    noise = np.random.default_rng(1).normal(0, sigma, (480, 640))
    with pytest.raises(ValueError, match="no object above the support plane"):
        segment_view(depth_view(0.8 + noise, intrinsics=(579.41, 579.41, 320, 239), camera_pose=pose))
    depth = np.full((480, 640), 0.8)
    depth[200:280, 280:360] = 0.77  # a box 3 cm tall, about 5.5 x 5.5 cm, under the camera
    scene = segment_view(depth_view(depth + noise, intrinsics=(579.41, 579.41, 320, 239), camera_pose=pose))
    assert len(scene.objects) == 1
    np.testing.assert_allclose(scene.objects[0].centroid[:2], [0.0, 0.0], atol=0.01)


def test_a_w_first_camera_quaternion_is_named_when_it_tilts_the_table():
    """The camera 45 degrees down at the table (x, y, z, qx, qy, qz, qw); the same pose written w-first and read
    x, y, z, w tilts the table the camera sees (its normal in the camera's frame is the true one) by 45 degrees:
    the note names the order and the reading that levels it; a level table or another tilt gets none."""
    from graspmix.perception import quaternion_order_note

    true = np.array([0, -0.55, 0.55, *Rotation.from_euler("x", -135, degrees=True).as_quat()])
    w_first = np.concatenate([true[:3], true[[6, 3, 4, 5]]])  # [qw, qx, qy, qz] as a user may write it
    in_camera = Rotation.from_quat(true[3:]).inv().apply([0, 0, 1])  # the table's normal the camera sees
    seen = Rotation.from_quat(w_first[3:]).apply(in_camera)  # where the w-first pose puts it in the world
    note = quaternion_order_note(w_first, [*seen, 0.1])
    assert note is not None and "w-first" in note and "table then 0 degrees" in note
    assert ", ".join(f"{v:g}" for v in true[3:]) in note  # the pose to give
    assert quaternion_order_note(true, [0, 0, 1, 0.1]) is None  # level
    assert quaternion_order_note(w_first, [1, 0, 0, 0.1]) is None  # tilted, but not by the order
    assert quaternion_order_note(None, [*seen, 0.1]) is None and quaternion_order_note(w_first, None) is None


def test_an_organized_file_in_the_sensor_frame_with_its_cameras_viewpoint_says_how_to_fix_it(tmp_path):
    """packed4.pcd (world-frame points, its camera's pose as VIEWPOINT) written again with its points in the camera's
    frame and the same VIEWPOINT: the two disagree. It was segmented as points in the sensor frame (grasps 0.7 m off,
    a note about no camera); now an error saying what to write. Done as it says (VIEWPOINT the identity, the pose
    given), the scene is the original file's."""
    loaded = _core.load_cloud(str(data_path("scenes", "packed4.pcd")))
    pose = np.asarray(loaded.viewpoint)
    grid = loaded.organized(camera_pose=pose)
    H, W = grid.shape[:2]
    bad, good = tmp_path / "sensor_vp.pcd", tmp_path / "sensor.pcd"
    _core.save_cloud(str(bad), grid.reshape(-1, 3), viewpoint=pose, width=W, height=H)
    _core.save_cloud(str(good), grid.reshape(-1, 3), viewpoint=[0, 0, 0, 0, 0, 0, 1], width=W, height=H)
    with pytest.raises(ValueError, match="VIEWPOINT as 0 0 0 1 0 0 0 and give the pose as --camera-pose"):
        scene_input(str(bad))
    fixed = segment_view(scene_input(str(good), camera_pose=pose)[0])
    original = segment_view(scene_input(str(data_path("scenes", "packed4.pcd")))[0])
    assert len(fixed.objects) == len(original.objects)
    np.testing.assert_allclose(fixed.plane, original.plane, atol=1e-4)


def _oblique_table(tilt_deg: float, sigma: float, box: bool):
    """A depth image (m) of the table z = 0, optionally with a 6 x 6 x 4 cm box at the origin (its top and the face
    towards the camera, by exact ray intersection), from a camera 0.78 m from the origin looking at it tilt_deg
    below the horizon, with Gaussian depth noise sigma a pixel; and the camera's pose (PCL's axes)."""
    a = np.radians(tilt_deg)
    eye = np.array([0.0, -0.78 * np.cos(a), 0.78 * np.sin(a)])
    forward = -eye / np.linalg.norm(eye)
    right = np.cross(forward, [0.0, 0.0, 1.0])
    right /= np.linalg.norm(right)
    rot = np.stack([right, np.cross(forward, right), forward], axis=1)
    u, v = np.meshgrid(np.arange(640), np.arange(480))
    rays = np.stack([(u - 320) / 579.41, (v - 239) / 579.41, np.ones(u.shape)], axis=-1) @ rot.T  # z-depth 1
    surfaces = [(2, 0.0, lambda p: True)]  # (axis, the plane's value on it, where on that plane the surface is)
    if box:
        surfaces += [
            (2, 0.04, lambda p: (np.abs(p[..., 0]) < 0.03) & (np.abs(p[..., 1]) < 0.03)),
            (1, -0.03, lambda p: (np.abs(p[..., 0]) < 0.03) & (p[..., 2] > 0) & (p[..., 2] < 0.04)),
        ]
    depth = np.full(u.shape, np.inf)
    with np.errstate(divide="ignore", invalid="ignore"):
        for axis, at, on in surfaces:
            t = (at - eye[axis]) / rays[..., axis]
            hit = (t > 0) & on(eye + t[..., None] * rays)
            depth = np.where(hit, np.minimum(depth, t), depth)
    depth += np.random.default_rng(1).normal(0.0, sigma, depth.shape)
    return np.where(np.isfinite(depth), depth, 0.0), [*eye, *Rotation.from_matrix(rot).as_quat()]


@pytest.mark.parametrize("tilt,sigma", [(45, 0.003), (45, 0.004), (60, 0.004)])
def test_a_noisy_table_seen_at_a_slant_has_no_object_and_a_box_on_it_is_one(tilt, sigma):
    """A camera looking down at 45-60 degrees sees the near table along steep rays and the far table along grazing
    ones: the same depth noise a pixel lifts the near table's points about twice as far. The table's noise is
    measured where each fragment stands (before: one figure for the whole table, and 1-3 fragments of the near
    table, up to 8669 points, came out as objects; at 60 degrees a fragment joined to the box's base, cut off it by
    the split rule, stayed an object of 13,839 points)."""
    intrinsics = (579.41, 579.41, 320, 239)
    depth, pose = _oblique_table(tilt, sigma, box=False)
    with pytest.raises(ValueError, match="no object above the support plane"):
        segment_view(depth_view(depth, intrinsics=intrinsics, camera_pose=pose))
    depth, pose = _oblique_table(tilt, sigma, box=True)
    scene = segment_view(depth_view(depth, intrinsics=intrinsics, camera_pose=pose))
    assert len(scene.objects) == 1
    (box,) = scene.objects
    np.testing.assert_allclose(box.centroid[:2], [0.0, -0.01], atol=0.012)
    assert 0.05 < box.obb_extents.max() < 0.1


def test_a_principal_point_outside_the_image_is_noted(view, capsys):
    """A principal point outside the image (a sign slip, cx = -320, or the order cx, cy, fx, fy) segments without an
    error, the objects where the camera did not look: scene_input notes it, `segment` prints it as one line; the
    camera's own intrinsics give no note."""
    _, cam, _, png = view
    c = cam.pinhole()
    pose = cam.pose()
    for intrinsics, noted in (
        ((c.fx, c.fy, c.cx, c.cy), False),
        ((c.fx, c.fy, -c.cx, c.cy), True),
        ((c.cx, c.cy, c.fx, c.fy), True),
    ):
        _, _, notes = scene_input(depth=str(png), intrinsics=intrinsics, camera_pose=pose)
        assert any("principal point" in n for n in notes) == noted, intrinsics
        code = main(
            [
                "segment",
                "--depth",
                str(png),
                f"--intrinsics={','.join(map(str, intrinsics))}",
                f"--camera-pose={','.join(map(str, pose))}",
            ]
        )
        err = capsys.readouterr().err
        assert (err.count("principal point") == 1) == noted, (code, err)


def test_acquire_writes_a_depth_png_and_the_flags_that_go_with_it(tmp_path, capsys):
    """`acquire --depth-out` writes the camera's depth image as a driver does (16-bit PNG, millimetres) and prints the
    --depth, --intrinsics and --camera-pose to give it with: the PNG back-projected with them (numpy and scipy, here)
    lands on the organized cloud the same command wrote, pixel for pixel, to the millimetre; segmented with them it
    gives the cloud's objects. One camera only; neither output, or a depth image not a PNG, is one line, exit 2."""
    scene = str(data_path("scenes", "packed4.json"))
    png, pcd = tmp_path / "d.png", tmp_path / "v.pcd"
    argv = ["acquire", "--scene", scene, "--noise", "--seed", "3", "--depth-out", str(png), "--out", str(pcd)]
    assert main(argv) == 0
    line = capsys.readouterr().out.strip().split("\n")[-1]
    flags = line.split("give it as ")[1].split()
    assert flags[:2] == ["--depth", str(png)]
    fx, fy, cx, cy = map(float, flags[3].split(","))
    pose = np.array(flags[4].split("=")[1].split(","), dtype=float)
    depth = read_depth(png).astype(float) * 0.001
    v, u = np.nonzero(depth > 0)
    sensor = np.column_stack([(u - cx) * depth[v, u] / fx, (v - cy) * depth[v, u] / fy, depth[v, u]])
    world = Rotation.from_quat(pose[3:]).apply(sensor) + pose[:3]
    grid = _core.load_cloud(str(pcd)).organized()
    assert grid.shape == (480, 640, 3) and np.array_equal(np.isfinite(grid[..., 2]), depth > 0)
    np.testing.assert_allclose(world, grid[v, u], atol=0.001)  # half a millimetre of rounding, along a ray
    assert main(["segment", *flags, "--json"]) == 0
    from_png = json.loads(capsys.readouterr().out)["objects"]
    assert main(["segment", "--cloud", str(pcd), "--json"]) == 0
    from_pcd = json.loads(capsys.readouterr().out)["objects"]
    # The millimetres move the table's cut and the join rule's gaps a little: a 61-point piece of one object (2.4 cm)
    # stays apart from the PNG; every object of 100 points or more is the cloud's, within 5 mm.
    big_png, big_pcd = ([o["centroid"] for o in objs if o["n_points"] >= 100] for objs in (from_png, from_pcd))
    assert len(big_png) == len(big_pcd) == 4
    np.testing.assert_allclose(big_png, big_pcd, atol=0.005)
    for bad, words in (
        (["--views", "4", "--depth-out", str(tmp_path / "e.png")], "--views 1"),
        ([], "--out"),
        (["--depth-out", str(tmp_path / "e.jpg")], "PNG"),
    ):
        assert main(["acquire", "--scene", scene, *bad]) == 2
        err = capsys.readouterr().err
        assert words in err and err.count("\n") == 1, err


def test_write_depth_round_trips_to_the_millimetre_and_refuses_what_16_bits_cannot_hold(tmp_path):
    depth = np.random.default_rng(0).uniform(0.2, 3.0, (48, 64))
    depth[0, :5] = [0.0, np.nan, np.inf, 65.535, 0.0004]  # no return x3, the deepest value, rounds to 0 (none)
    path = tmp_path / "d.png"
    write_depth(path, depth)
    back = read_depth(path)
    assert back.dtype == np.uint16
    np.testing.assert_array_equal(back[0, :5], [0, 0, 0, 65535, 0])
    np.testing.assert_allclose(back[1:] * 0.001, depth[1:], atol=0.0005 + 1e-12)
    for bad in (np.full((4, 4), 70.0), np.full((4, 4), -0.5), np.zeros(5)):
        with pytest.raises(ValueError, match="depth"):
            write_depth(tmp_path / "e.png", bad)


def test_the_same_slanted_noisy_view_as_points_finds_its_table_under_a_box():
    """The 45-degree view of a box on a table with 4 mm of noise a pixel, given as its points with the camera's
    position (segment_scene's unorganized path): the plane rule judges a candidate on what rises above its noise
    when something does, so the noise fragments that reach the table's edges no longer refuse it (before: no
    plane, 3 objects, the table one of 199,881 points); an object's face seen alone keeps being refused
    (tests/cpp/perception/test_segmentation.cpp, ObjectOnlyCloudsHaveNoPlane)."""
    depth, pose = _oblique_table(45, 0.004, box=True)
    v, u = np.nonzero(depth > 0)
    z = depth[v, u]
    sensor = np.column_stack([(u - 320) * z / 579.41, (v - 239) * z / 579.41, z])
    points = Rotation.from_quat(pose[3:]).apply(sensor) + pose[:3]
    scene = segment_scene(points, viewpoints=pose[:3])
    assert scene.plane_found and abs(scene.plane[2]) > 0.999
    assert len(scene.objects) == 1
    np.testing.assert_allclose(scene.objects[0].centroid[:2], [0.0, -0.01], atol=0.012)
