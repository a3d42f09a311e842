"""The scene model against the renderer's ground truth: the support plane and its side on clouds rendered
with pybullet (one and four cameras, with and without noise), no plane on object-only clouds, clusters
against pybullet's segmentation mask, every target mode, the camera-frame input, bad inputs."""

import re

import graspmix
import numpy as np
import pybullet as p
import pytest
from graspmix import SpaceState, _core
from graspmix.perception import POINT_TARGET_MAX_DISTANCE, camera_to_world, parse_target, segment_scene
from graspmix.sim.acquisition import (
    AcquisitionSettings,
    Camera,
    TableWorld,
    acquire,
    apply_noise,
    back_project,
    ring_cameras,
)

EYE = (0.5, 0.1, 0.45)


def _up(plane):
    return plane is not None and plane[2] > 0.999 and abs(plane[3]) < 0.003


@pytest.mark.parametrize("noise", [False, True])
@pytest.mark.parametrize("n_cameras", [1, 4])
def test_rendered_table_is_found_and_faces_the_cameras(noise, n_cameras):
    cams = [Camera(eye=EYE)] if n_cameras == 1 else ring_cameras(4)
    acq = acquire("objects/mug.urdf", noise=noise, seed=2, settings=AcquisitionSettings(cameras=cams, keep="scene"))
    scene = segment_scene(acq.points, acq.viewpoints)
    assert scene.plane_found and not scene.plane_given
    assert _up(scene.plane), scene.to_dict()["candidates"]
    assert np.all(scene.points @ scene.plane[:3] + scene.plane[3] > _core.SegmentationSettings().table_clearance)
    # the mug (at the origin) is the largest object, and no table point is left in it
    mug = scene.objects[scene.select("largest")[0]]
    assert np.linalg.norm(mug.centroid[:2] - acq.object_pose[:2]) < 0.03
    assert mug.obb_extents.max() < 0.16


def test_the_cameras_decide_the_side_not_the_points():
    # The same cloud turned upside down (z -> -z with the camera): the plane must turn with it.
    acq = acquire(
        "objects/mug.urdf", noise=True, seed=3, settings=AcquisitionSettings(cameras=[Camera(eye=EYE)], keep="scene")
    )
    flip = np.diag([1.0, -1.0, -1.0])
    scene = segment_scene(acq.points @ flip, np.asarray(EYE) @ flip)
    assert scene.plane_found and scene.plane[2] < -0.999


@pytest.mark.parametrize("shape", ["mug", "box", "flat", "on_side"])
@pytest.mark.parametrize("n_cameras", [1, 4])
def test_object_only_clouds_have_no_plane(box_urdf, shape, n_cameras):
    obj = {
        "mug": "objects/mug.urdf",
        "box": box_urdf((0.06, 0.05, 0.1)),
        "flat": box_urdf((0.12, 0.08, 0.025)),
        "on_side": box_urdf((0.12, 0.025, 0.08)),
    }[shape]
    cams = [Camera(eye=EYE)] if n_cameras == 1 else ring_cameras(4)
    acq = acquire(obj, noise=True, seed=4, settings=AcquisitionSettings(cameras=cams, keep="object"))
    scene = segment_scene(acq.points, acq.viewpoints)
    assert not scene.plane_found, scene.to_dict()["candidates"]
    assert scene.plane is None
    assert scene.result.n_plane == 0


# Three objects on plane.urdf: (urdf, position, scale); sizes clearly apart so "largest" has one answer.
OBJECTS = [
    ("cube.urdf", (0.0, 0.0), 0.08),
    ("cube.urdf", (-0.03, 0.13), 0.05),
    ("sphere_small.urdf", (0.08, -0.1), 1.0),
]


@pytest.fixture(scope="module")
def rendered():
    """A pybullet scene of three objects seen by one camera: the cloud, its viewpoint, and per point the
    body id from pybullet's segmentation mask (the ground truth); the bodies' ids and positions."""
    with TableWorld("cube_small.urdf", AcquisitionSettings()) as world:
        p.removeBody(world.body, physicsClientId=world.client)
        bodies = []
        for urdf, (x, y), scale in OBJECTS:
            b = p.loadURDF(urdf, (x, y, 1.0), globalScaling=scale, physicsClientId=world.client)
            lo, _ = p.getAABB(b, -1, physicsClientId=world.client)
            p.resetBasePositionAndOrientation(b, (x, y, 1.0 - lo[2]), (0, 0, 0, 1), physicsClientId=world.client)
            bodies.append(b)
        cam = Camera(eye=EYE, width=320, height=240)
        depth, seg = world.render_depth(cam)
        points, flat = back_project(depth, cam)
        ids = seg.ravel()[flat]
        centres = [np.array(p.getBasePositionAndOrientation(b, physicsClientId=world.client)[0]) for b in bodies]
    return points, np.asarray(EYE), ids, bodies, centres


def _body_of(scene, ids):
    """Per object, the body id most of its points come from, and that fraction."""
    out = []
    for o in scene.objects:
        truth = ids[scene.sources[o.rows]]
        values, counts = np.unique(truth, return_counts=True)
        out.append((int(values[np.argmax(counts)]), counts.max() / len(truth)))
    return out


def test_clusters_are_the_rendered_objects(rendered):
    points, eye, ids, bodies, _ = rendered
    scene = segment_scene(points, eye)
    assert _up(scene.plane)
    found = _body_of(scene, ids)
    assert sorted(b for b, _ in found) == sorted(bodies)
    assert all(purity > 0.98 for _, purity in found)
    assert np.array_equal(scene.labels, np.repeat(np.arange(len(scene.objects)), [o.n_points for o in scene.objects]))


def test_every_target_picks_the_intended_object(rendered):
    points, eye, ids, bodies, centres = rendered
    scene = segment_scene(points, eye)
    body = dict(enumerate(b for b, _ in _body_of(scene, ids)))
    assert scene.select("all") == list(range(3))
    assert body[scene.select("largest")[0]] == bodies[0]  # the 8 cm cube
    for k, c in enumerate(centres):
        assert body[scene.select(f"point:{c[0]},{c[1]},{c[2]}")[0]] == bodies[k]
    # nearest to the camera: the body with the pixel nearest to it, from the mask alone
    dist = {b: np.min(np.linalg.norm(points[ids == b] - eye, axis=1)) for b in bodies}
    assert body[scene.select("nearest")[0]] == min(dist, key=dist.get)
    far_camera = np.array([-0.5, -0.1, 0.45])  # seen from the other side, another object is nearest
    dist = {b: np.min(np.linalg.norm(points[ids == b] - far_camera, axis=1)) for b in bodies}
    assert body[scene.select("nearest", camera=far_camera)[0]] == min(dist, key=dist.get)
    assert scene.select(2) == [2] and scene.select("1") == [1]
    with pytest.raises(ValueError, match="names no object"):
        scene.select(f"point:0.5,0.5,{POINT_TARGET_MAX_DISTANCE}")
    with pytest.raises(ValueError, match="no object 3"):
        scene.select(3)


def test_parse_target_forms_and_errors():
    assert str(parse_target("point:0.1,-2,3e-2")) == "point:0.1,-2,0.03"
    assert parse_target(" largest ").kind == "largest" and parse_target("7").index == 7
    for bad in ["point:1,2", "point:1,2,nan", "biggest", "-1", "", "9999999999999", 2**31, -1]:
        with pytest.raises(ValueError, match="target"):
            parse_target(bad)
    assert parse_target(str(2**31 - 1)).index == 2**31 - 1  # the largest index C++ holds


def test_camera_frame_cloud_gives_the_same_scene(rendered):
    points, eye, _, _, _ = rendered
    # T_world_camera: a rotation of 120 degrees about (1, 1, 1) / sqrt(3) (x -> y -> z -> x), at the eye
    q = np.array([0.5, 0.5, 0.5, 0.5])
    R = np.array([[0, 0, 1], [1, 0, 0], [0, 1, 0]], dtype=float)
    in_camera = (points - eye) @ R  # R^T (p - eye) per row
    world, camera = camera_to_world(in_camera, np.concatenate([eye, q]))
    np.testing.assert_allclose(world, points, atol=1e-12)
    np.testing.assert_allclose(camera, eye)
    a, b = segment_scene(points, eye), segment_scene(in_camera)  # no viewpoint: the camera at the origin
    assert len(a.objects) == len(b.objects) == 3
    np.testing.assert_allclose(b.plane[:3], R.T @ a.plane[:3], atol=1e-3)
    with pytest.raises(ValueError, match="not a unit quaternion"):
        camera_to_world(in_camera, [0, 0, 0, 0, 0, 0, 2])


def test_known_plane_and_bad_inputs(rendered):
    points, eye, _, _, _ = rendered
    given = segment_scene(points, eye, plane=[0, 0, -3, 0])
    assert given.plane_given and not given.plane_found
    np.testing.assert_allclose(given.plane, [0, 0, 1, 0])
    assert len(given.objects) == 3 and given.viewpoints.shape == (len(given.points), 3)
    table = points[points[:, 2] < 0.002]
    with pytest.raises(ValueError, match="no object above the support plane"):
        segment_scene(table, eye, plane=[0, 0, 1, 0])
    with pytest.raises(ValueError, match="viewpoints"):
        segment_scene(points, np.zeros((5, 3)))
    with pytest.raises(ValueError, match="viewpoints"):
        segment_scene(points, [0, 0])
    with pytest.raises(ValueError, match="NaN"):
        segment_scene(np.full((10, 3), np.nan))
    with pytest.raises(ValueError, match="cluster_tolerance"):
        segment_scene(points, eye, cluster_tolerance=-1)
    with pytest.raises(ValueError, match="merge_through_fraction"):
        segment_scene(points, eye, merge_through_fraction=1.5)
    with pytest.raises(ValueError, match="merge_inset"):
        segment_scene(points, eye, merge_inset=float("nan"))
    with pytest.raises(ValueError, match="unknown setting"):
        segment_scene(points, eye, tolerance=1)


def test_defaults_come_from_cpp_and_the_dict_is_json(rendered):
    import json

    assert _core.SegmentationSettings().voxel_size == _core.CleanupSettings().voxel_size
    points, eye, _, _, _ = rendered
    d = json.loads(json.dumps(segment_scene(points, eye).to_dict(), allow_nan=False))
    assert d["plane_found"] and len(d["objects"]) == 3 and d["candidates"][0]["accepted"]
    assert graspmix.segment_scene is segment_scene


# ---- the merge rule: a cluster seen through a larger one is part of it ------------------------------------

OPEN_BOX = """<?xml version="1.0"?>
<robot name="open_box"><link name="base">{parts}
  <inertial><mass value="0.5"/><inertia ixx="1e-3" iyy="1e-3" izz="1e-3" ixy="0" ixz="0" iyz="0"/></inertial>
</link></robot>"""


def _open_box(tmp_path, side=0.16, height=0.08, wall=0.005):
    """A box without a lid: a floor and four walls of `wall` thickness, origin at the floor's centre."""
    parts = [((0, 0, wall / 2), (side, side, wall))]
    for sx, sy in [(1, 0), (-1, 0), (0, 1), (0, -1)]:
        size = (wall, side, height) if sx else (side, wall, height)
        parts.append(((sx * (side - wall) / 2, sy * (side - wall) / 2, height / 2), size))
    xml = "".join(
        f'<{tag}><origin xyz="{x} {y} {z}"/><geometry><box size="{a} {b} {c}"/></geometry></{tag}>'
        for (x, y, z), (a, b, c) in parts
        for tag in ("visual", "collision")
    )
    path = tmp_path / "open_box.urdf"
    path.write_text(OPEN_BOX.format(parts=xml))
    return path


def _render(bodies, eye, seed):
    """One noisy view (the acquisition's noise model) of bodies [(urdf, (x, y), scale)] resting on plane.urdf."""
    settings = AcquisitionSettings()
    with TableWorld("cube_small.urdf", settings) as world:
        p.removeBody(world.body, physicsClientId=world.client)
        for urdf, (x, y), scale in bodies:
            b = p.loadURDF(str(urdf), (x, y, 1.0), globalScaling=scale, physicsClientId=world.client)
            lo, _ = p.getAABB(b, -1, physicsClientId=world.client)
            p.resetBasePositionAndOrientation(b, (x, y, 1.0 - lo[2]), (0, 0, 0, 1), physicsClientId=world.client)
        cam = Camera(eye=eye, width=320, height=240)
        depth, _ = world.render_depth(cam)
    depth = apply_noise(depth, np.random.default_rng(seed), settings.pixel_noise_std, settings.depth_noise_std)
    return back_project(depth, cam)[0]


@pytest.mark.parametrize("eye", [EYE, (0.6, 0.0, 0.3)])
@pytest.mark.parametrize("seed", range(4))
def test_a_mug_seen_into_is_one_object(eye, seed):
    acq = acquire(
        "objects/mug.urdf", noise=True, seed=seed, settings=AcquisitionSettings(cameras=[Camera(eye=eye)], keep="scene")
    )
    scene = segment_scene(acq.points, acq.viewpoints)
    assert len(scene.objects) == 1, scene.to_dict()["objects"]
    assert (
        scene.result.n_merged
        == len(segment_scene(acq.points, acq.viewpoints, merge_seen_through=False, join_occluded=False)) - 1
    )


def test_the_merge_rule_did_the_work_on_a_split_mug():
    # the view where the inner wall behind the opening is a second cluster without the rule
    acq = acquire(
        "objects/mug.urdf", noise=True, seed=0, settings=AcquisitionSettings(cameras=[Camera(eye=EYE)], keep="scene")
    )
    apart = segment_scene(acq.points, acq.viewpoints, merge_seen_through=False, join_occluded=False)
    assert len(apart.objects) == 2
    inner = apart.objects[1]  # the inner wall: on the far side of the mug's axis from the camera
    towards_camera = np.asarray(EYE[:2]) / np.linalg.norm(EYE[:2])
    assert inner.centroid[:2] @ towards_camera < 0 < apart.objects[0].centroid[:2] @ towards_camera
    whole = segment_scene(acq.points, acq.viewpoints)
    assert len(whole.objects) == 1 and whole.result.n_merged == 1
    assert whole.objects[0].n_points == apart.objects[0].n_points + inner.n_points


@pytest.mark.parametrize("eye", [EYE, (-0.5, 0.0, 0.4), (0.0, 0.5, 0.4), (0.4, 0.4, 0.3), (0.3, -0.1, 0.6)])
@pytest.mark.parametrize("sizes", [(0.05, 0.05), (0.08, 0.05)])
def test_boxes_1cm_apart_are_not_merged(eye, sizes):
    gap = 0.01
    centres = (sizes[0] / 2, sizes[0] + gap + sizes[1] / 2)
    bodies = [("cube.urdf", (c, 0.0), s) for c, s in zip(centres, sizes)]
    points = _render(bodies, eye, seed=1)
    scene = segment_scene(points, np.asarray(eye))
    # the rule joins nothing: the clusters are those found without it (flying pixels at the boxes' edges
    # sometimes bridge the gap for the Euclidean clustering itself, before the rule)
    assert scene.result.n_merged == 0
    assert len(scene.objects) == len(
        segment_scene(points, np.asarray(eye), merge_seen_through=False, join_occluded=False).objects
    )
    # each object is one box: (nearly) every point on its side of the gap (the geometry is the ground truth)
    if len(scene.objects) == 2:
        for o in scene.objects:
            side = o.points[:, 0] > sizes[0] + gap / 2
            assert max(side.mean(), 1 - side.mean()) > 0.98


def test_a_small_box_inside_an_open_box_stays_its_own_object(tmp_path):
    # What happens (segmentation.hpp): the container's thin floor goes with the table and its walls come apart;
    # the lines of sight to the cube cross no wall's envelope, so the rule leaves the cube alone.
    bodies = [(_open_box(tmp_path), (0.0, 0.0), 1.0), ("cube.urdf", (0.0, 0.0), 0.04)]
    points = _render(bodies, EYE, seed=2)
    scene = segment_scene(points, np.asarray(EYE))
    cubes = [o for o in scene.objects if np.linalg.norm(o.centroid[:2]) < 0.01]
    assert len(cubes) == 1
    inside = np.all(
        np.abs(cubes[0].points[:, :2]) < 0.02 + 0.003, axis=1
    )  # the cube's footprint (+ noise; flying pixels at its edges)
    assert inside.mean() > 0.95 and cubes[0].points[:, 2].max() < 0.005 + 0.04 + 0.003


def test_step_seconds_add_up():
    acq = acquire(
        "objects/mug.urdf", noise=True, seed=1, settings=AcquisitionSettings(cameras=[Camera(eye=EYE)], keep="scene")
    )
    r = segment_scene(acq.points, acq.viewpoints).result
    steps = r.step_seconds
    assert set(steps) == {
        "voxel",
        "visibility",
        "candidates",
        "table_cut",
        "outliers",
        "clusters",
        "merge",
        "join",
        "split",
        "objects",
    }
    assert all(v >= 0 for v in steps.values()) and sum(steps.values()) <= r.seconds


def test_the_scene_models_what_its_cameras_saw():
    """segment_scene's visibility model: one spherical view per distinct camera, built from the voxelised cloud.
    What it says is checked against the geometry of the scene: the mug's points are on the surface, a point
    between the camera and the mug is seen free, a point under the table's top (behind its seen surface) is
    unseen. No viewpoint: no model."""
    cams = [Camera(eye=EYE), Camera(eye=(-EYE[0], -EYE[1], EYE[2]))]
    acq = acquire("objects/mug.urdf", noise=False, seed=1, settings=AcquisitionSettings(cameras=cams, keep="scene"))
    scene = segment_scene(acq.points, acq.viewpoints)
    v = scene.result.visibility
    assert v.n_views == 2 and [w["kind"] for w in v.views] == ["spherical", "spherical"]
    states = v.classify(scene.points)
    assert np.mean(states != SpaceState.SeenFree) > 0.99  # nothing the cameras saw is in front of itself
    c = scene.objects[0].centroid
    eye = np.asarray(EYE, dtype=float)
    assert v.classify(c + 0.8 * (eye - c) / np.linalg.norm(eye - c) * 0.3)[0] == SpaceState.SeenFree
    assert v.classify(np.array([0.3, 0.3, -0.05]))[0] == SpaceState.Unseen  # under the table's top
    assert segment_scene(acq.points, plane=[0, 0, 1, 0]).result.visibility is None


def test_a_camera_given_below_the_table_is_named_as_the_likely_cause(rendered):
    """The plane is turned towards the cameras: a viewpoint mirrored below the table puts the three objects behind
    it, and the error says how many points lie there and asks about the camera's position (with a given plane, about
    the plane too). The count is of the cleaned cloud's points: some, and no more than numpy finds behind z = 0 in
    the raw cloud."""
    points, eye, _, _, _ = rendered
    below = eye * np.array([1.0, 1.0, -1.0])
    clearance = graspmix.SegmentationSettings().table_clearance
    raw_behind = int(np.sum(points[:, 2] > clearance))  # above the table: behind it seen from below
    for plane, also in ((None, ""), ([0, 0, 1, 0], "the plane given right, and ")):
        with pytest.raises(ValueError, match="no object above the support plane") as err:
            segment_scene(points, below, plane=plane)
        m = re.search(
            r"; (\d+) points lie behind it, on the side away from the cameras: is (.*)the camera's position",
            str(err.value),
        )
        assert m, str(err.value)
        assert 20 <= int(m.group(1)) <= raw_behind and m.group(2) == also


def test_a_cloud_of_only_a_table_has_no_object(tmp_path, capsys):
    """A flat noisy table and nothing on it: seen from a camera above, the table is found and nothing stands on
    it; with no viewpoint (the PCD convention's camera at the origin, in the table's own plane) the table is
    refused as the support only because the camera lies in it, and it is still no object to grasp: the error
    says to give the camera. Both are errors, also through the CLI."""
    from graspmix.cli import main

    rng = np.random.default_rng(0)
    table = np.c_[rng.uniform(-0.3, 0.3, (20000, 2)), rng.normal(0.0, 0.001, 20000)]
    with pytest.raises(ValueError, match="no object above the support plane") as err:
        segment_scene(table, [0.0, 0.0, 1.0])
    assert "behind it, on the side away" not in str(err.value)  # nothing behind the table to name
    with pytest.raises(ValueError, match="no object found: 100% of the cloud lies in one plane.*camera"):
        segment_scene(table)
    graspmix.save_cloud(str(tmp_path / "table.pcd"), table)
    assert main(["synthesize", "--cloud", str(tmp_path / "table.pcd"), "--out", str(tmp_path / "g.json")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "no object" in err and not (tmp_path / "g.json").exists()


def test_pcls_console_stays_quiet(tmp_path, capfd):
    """A workspace that leaves RANSAC degenerate samples (PCL printed "Sample points too similar or collinear!" on
    stderr from C++): the command's own lines only."""
    from graspmix.cli.main import main
    from graspmix.io import data_path

    argv = ["synthesize", "--cloud", str(data_path("scenes", "packed4.pcd")), "--out", str(tmp_path / "g.json")]
    assert main([*argv, "--workspace=-0.1,-0.2,-0.05,0.0,0.0,0.2"]) == 0
    assert "pcl::" not in capfd.readouterr().err


def test_the_points_the_clean_up_dropped_are_kept_aside(rendered):
    # The outliers and small clusters above the table, voxelised: as many as the counts say, none kept as an
    # object's, each within a voxel of an input point pybullet's mask says is an object's (not the table's).
    from scipy.spatial import cKDTree

    points, eye, ids, bodies, _ = rendered
    scene = segment_scene(points, eye)
    r = scene.result
    dropped = np.asarray(r.dropped)
    assert dropped.shape == (r.n_outliers + r.n_small_clusters, 3)
    assert len(dropped) > 0
    assert cKDTree(scene.points).query(dropped)[0].min() > 0
    on_objects = cKDTree(points[np.isin(ids, bodies)])
    assert on_objects.query(dropped)[0].max() <= 0.003 * np.sqrt(3) + 1e-9
