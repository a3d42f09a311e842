"""The visibility model and the pinhole camera through Python, against independent answers: numpy ray casting of a
plane with known intrinsics, a sampled sphere's ray intersection, the combination rule applied to the views'
own answers, and OctoMap (OccupancyMap) on a scene rendered by pybullet from one camera; bad input."""

import math
import re

import numpy as np
import pytest
from graspmix import PinholeCamera, SpaceState, VisibilityModel, VisibilitySettings, _core
from graspmix.io import data_path
from graspmix.perception import segment_scene
from scipy.spatial import cKDTree
from scipy.spatial.transform import Rotation

FREE, SURFACE, UNSEEN = int(SpaceState.SeenFree), int(SpaceState.Surface), int(SpaceState.Unseen)
TOL = VisibilitySettings().surface_tolerance
CAM = PinholeCamera(60.0, 62.0, 31.7, 24.2, 64, 48)
IDENTITY = [0, 0, 0, 0, 0, 0, 1]


def pixel_rays(cam, u, v):
    """Directions (N, 3) in the sensor frame of pixel coordinates u, v, scaled so that z = 1."""
    return np.stack([(u - cam.cx) / cam.fx, (v - cam.cy) / cam.fy, np.ones_like(u)], axis=1)


def test_the_camera_fits_the_intrinsics_a_cloud_was_made_with(rng):
    truth = PinholeCamera(612.375, 608.125, 322.6, 236.9, 160, 120)
    depth = rng.uniform(0.4, 1.2, size=(120, 160))
    depth[rng.random(depth.shape) < 0.2] = np.nan
    cloud = truth.back_project(depth)
    assert cloud.shape == (120, 160, 3)
    v, u = np.mgrid[0:120, 0:160]
    np.testing.assert_allclose(cloud[..., 0], (u - 322.6) * depth / 612.375, rtol=1e-15, atol=0)
    valid = np.isfinite(depth)
    np.testing.assert_allclose(truth.project(cloud[valid]), np.c_[u[valid], v[valid]], atol=1e-9)
    fit = PinholeCamera.fit(cloud)
    for name in ("fx", "fy", "cx", "cy"):
        assert getattr(fit.camera, name) == pytest.approx(getattr(truth, name), abs=1e-9)
    assert (fit.camera.width, fit.camera.height, fit.n_valid) == (160, 120, int(np.isfinite(depth).sum()))
    assert fit.rms_px < 1e-9
    # (H * W, 3) with its size, the same answer.
    again = PinholeCamera.fit(cloud.reshape(-1, 3), height=120, width=160)
    assert again.camera.fx == pytest.approx(truth.fx, abs=1e-9)
    np.testing.assert_allclose(truth.K, [[612.375, 0, 322.6], [0, 608.125, 236.9], [0, 0, 1]])


def test_a_plane_in_front_of_the_camera_on_both_sides_of_the_tolerance(rng):
    """A plane facing the camera at depth 1 m: a point at depth z on any ray has the surface at range |p| / z."""
    model = VisibilityModel.from_depth(np.ones((48, 64)), CAM, IDENTITY)
    u, v = rng.uniform(-0.49, 63.49, 500), rng.uniform(-0.49, 47.49, 500)
    rays = pixel_rays(CAM, u, v)
    norm = np.linalg.norm(rays, axis=1)
    for delta in (0.3, TOL * (1 + 1e-6), TOL * (1 - 1e-6), 0.0, -TOL * (1 - 1e-6), -TOL * (1 + 1e-6), -0.4):
        points = rays * (1.0 - delta / norm)[:, None]
        np.testing.assert_allclose(model.signed_distance(points), delta, atol=1e-12)
        want = FREE if delta > TOL else UNSEEN if delta < -TOL else SURFACE
        states = model.classify(points)
        assert states.dtype == np.uint8 and np.all(states == want)
    # Outside the image: past its first column, below its last row; behind the camera.
    outside = np.r_[
        pixel_rays(CAM, np.array([-0.51]), np.array([3.0])), pixel_rays(CAM, np.array([5.0]), np.array([47.51]))
    ]
    assert np.all(model.classify(np.r_[0.5 * outside, [[0, 0, -0.5]]]) == UNSEEN)
    assert np.all(np.isnan(model.signed_distance(0.5 * outside)))
    assert model.classify([0, 0, 0.5])[0] == SpaceState.SeenFree  # one point as (3,)


def test_a_pixel_with_no_return_says_nothing_unless_no_return_is_free():
    depth = np.ones((48, 64))
    depth[10, 20], depth[11, 20], depth[12, 20] = np.nan, 0.0, np.inf
    rays = pixel_rays(CAM, np.array([20.3, 20.0, 19.8]), np.array([9.7, 11.0, 12.2]))
    model = VisibilityModel.from_depth(depth, CAM, IDENTITY)
    assert model.views[0]["n_returns"] == 48 * 64 - 3
    assert np.all(model.classify(0.5 * rays) == UNSEEN) and np.all(np.isnan(model.signed_distance(0.5 * rays)))
    free = VisibilityModel.from_depth(depth, CAM, IDENTITY, no_return_is_free=True)
    assert np.all(free.classify(0.5 * rays) == FREE) and np.all(free.signed_distance(0.5 * rays) == np.inf)
    assert free.classify(pixel_rays(CAM, np.array([21.0]), np.array([10.0])) * 1.2)[0] == UNSEEN  # its neighbour


def test_the_spherical_image_of_a_sampled_sphere(rng):
    """200k points on a sphere (radius 10 cm) seen from 60 cm: along a direction inside half its silhouette the
    ray enters it at b - h (b = D cos t, h = sqrt(R^2 - D^2 sin^2 t)); a bin holds its nearest point, which
    differs from that by less than 2.5 mm there."""
    c, r = np.array([0.4, -0.2, 0.3]), 0.1
    viewpoint = c + 0.6 * np.array([0.0, -0.6, 0.8])
    s = rng.normal(size=(200000, 3))
    model = VisibilityModel.from_points(c + r * s / np.linalg.norm(s, axis=1, keepdims=True), viewpoint)
    view = model.views[0]
    assert view["kind"] == "spherical" and view["angular_resolution"] == 0.005 and view["camera"] is None
    np.testing.assert_allclose(view["T_world_sensor"][:3], viewpoint)
    axis = (c - viewpoint) / 0.6
    silhouette = math.asin(r / 0.6)
    theta = 0.5 * silhouette * np.sqrt(rng.random(1000))
    side = np.cross(axis, rng.normal(size=(1000, 3)))
    side /= np.linalg.norm(side, axis=1, keepdims=True)
    dirs = Rotation.from_rotvec(side * theta[:, None]).apply(axis)
    near = 0.6 * np.cos(theta) - np.sqrt(r**2 - (0.6 * np.sin(theta)) ** 2)
    at = lambda t: viewpoint + dirs * t[:, None]  # noqa: E731
    np.testing.assert_allclose(model.signed_distance(at(near - 0.02)), 0.02, atol=0.003)
    assert np.all(model.classify(at(near - 0.02)) == FREE)
    assert np.all(model.classify(at(near + 0.001)) == SURFACE)
    assert np.all(model.classify(at(near + 0.03)) == UNSEEN)
    # Beside the sphere by 5 bins and more: no point there, unseen.
    beside = Rotation.from_rotvec(side * (silhouette + 0.025 + 0.05 * rng.random(1000))[:, None]).apply(axis)
    assert np.all(model.classify(viewpoint + 0.5 * beside) == UNSEEN)


def test_views_combine_surface_first_then_free_then_unseen(rng):
    """Two cameras facing each other across a slab: the combined answer is the rule applied to each view's."""
    depth_a = rng.uniform(0.9, 1.1, size=(48, 64))
    depth_b = rng.uniform(0.9, 1.1, size=(48, 64))
    depth_b[rng.random(depth_b.shape) < 0.1] = np.nan
    facing_back = [0, 0, 2.0, 0, 1, 0, 0]  # at z = 2, turned by pi about y: looking down -z
    a = VisibilityModel.from_depth(depth_a, CAM, IDENTITY)
    b = VisibilityModel.from_depth(depth_b, CAM, facing_back)
    both = VisibilityModel()
    assert both.n_views == 0 and np.all(both.classify(np.zeros((3, 3)) + 1) == UNSEEN)
    both.add_view(a)
    both.add_view(b)
    assert len(both) == both.n_views == 2
    points = np.c_[rng.uniform(-0.3, 0.3, (20000, 2)), rng.uniform(0.5, 1.5, 20000)]
    sa, sb = a.classify(points), b.classify(points)
    want = np.where((sa == SURFACE) | (sb == SURFACE), SURFACE, np.where((sa == FREE) | (sb == FREE), FREE, UNSEEN))
    got = both.classify(points)
    np.testing.assert_array_equal(got, want)
    assert min(np.count_nonzero(got == s) for s in (FREE, SURFACE, UNSEEN)) > 100
    d = both.signed_distance(points)
    np.testing.assert_array_equal(
        np.where(np.isnan(d), UNSEEN, np.where(d > TOL, FREE, np.where(d >= -TOL, SURFACE, UNSEEN))), got
    )
    with pytest.raises(ValueError, match="settings differ"):
        both.add_view(VisibilityModel.from_depth(depth_a, CAM, IDENTITY, surface_tolerance=0.01))


def pybullet_camera(cam, shape):
    """The PinholeCamera and T_world_camera of a simulated camera (graspmix.sim.acquisition.Camera): from the
    back-projection its images are made with, x = (2u / w - 1) tan_x z and y = (2 (v + 1) / h - 1) tan_y z in
    the sensor frame, so fx = w / (2 tan_x), cx = w / 2, fy = h / (2 tan_y), cy = h / 2 - 1; the sensor frame is
    OpenGL's camera frame turned by pi about x."""
    h, w = shape
    tan_y = math.tan(math.radians(cam.fov_deg) / 2)
    K = PinholeCamera(w / (2 * tan_y * w / h), h / (2 * tan_y), w / 2, h / 2 - 1, w, h)
    T_camera_world = np.diag([1.0, -1.0, -1.0, 1.0]) @ cam.view_matrix()
    T = np.linalg.inv(T_camera_world)
    return K, np.r_[T[:3, 3], Rotation.from_matrix(T[:3, :3]).as_quat()], T_camera_world


@pytest.fixture(scope="module")
def rendered():
    """The bundled packed scene (four objects on a table) from the default scene camera, no noise."""
    from graspmix.sim import scenes
    from graspmix.sim.acquisition import back_project
    from graspmix.sim.scene_camera import acquire_scene

    acq = acquire_scene(scenes.SceneSpec.load(str(data_path("scenes", "packed4.json"))), views=1)
    depth = acq.depth_images[0]
    K, pose, T_camera_world = pybullet_camera(acq.cameras[0], depth.shape)
    organized = np.full((depth.size, 3), np.nan)
    world, flat = back_project(depth, acq.cameras[0])
    organized[flat] = world @ T_camera_world[:3, :3].T + T_camera_world[:3, 3]
    return acq, depth, K, pose, organized.reshape(*depth.shape, 3)


def test_the_rendered_cameras_intrinsics_come_back_from_its_organized_cloud(rendered):
    acq, depth, K, pose, organized = rendered
    model = VisibilityModel.from_organized(organized, pose)
    fitted = model.views[0]["camera"]
    for name in ("fx", "fy", "cx", "cy"):
        assert getattr(fitted, name) == pytest.approx(getattr(K, name), abs=1e-6)
    assert model.views[0]["fit_rms_px"] < 1e-6
    np.testing.assert_allclose(model.views[0]["T_world_sensor"][:3], acq.cameras[0].eye, atol=1e-6)
    # The depth image's model answers alike on the scene's own points: every one is surface.
    by_depth = VisibilityModel.from_depth(depth, K, pose)
    assert np.all(by_depth.classify(acq.points) == SURFACE) and np.all(model.classify(acq.points) == SURFACE)


def test_agrees_with_the_octomap_occupancy_map_away_from_surfaces(rendered):
    """Points sampled around the objects (their box grown by 3 cm), more than two cells above the table and more
    than a cell's diagonal from any observed point, where OctoMap's cells are free or unknown: the visibility
    model calls them SeenFree and Unseen alike for 99% of them from the depth image (99.3% here) and 98% from the
    points' spherical image (98.9%). The disagreements are OctoMap's discretisation: a cell any ray crosses is
    free, though the shadow of a silhouette edge covers part of it (every disagreement of the depth image's model
    lies in a cell whose corners it classifies both SeenFree and Unseen); the spherical image adds its coarser
    bins, each holding its nearest point, which widen every shadow by a bin or two (0.005 rad: 3-4 mm)."""
    acq, depth, K, pose, _ = rendered
    scene = segment_scene(acq.points, acq.viewpoints)
    occ = _core.OccupancyMap(acq.points, acq.viewpoints, scene.points, scene.plane)
    h = occ.resolution
    rng = np.random.default_rng(0)
    points = rng.uniform(scene.points.min(0) - 0.03, scene.points.max(0) + 0.03, size=(200000, 3))
    points = points[points @ scene.plane[:3] + scene.plane[3] > 2 * h]
    points = points[cKDTree(acq.points).query(points)[0] > math.sqrt(3) * h]
    cells = occ.state(points)
    assert np.count_nonzero(cells == 1) == 0 and np.count_nonzero(cells == 2) > 3000  # no occupied cell here
    by_depth = VisibilityModel.from_depth(depth, K, pose)
    by_points = VisibilityModel.from_points(acq.points, np.asarray(acq.cameras[0].eye))
    expected = np.where(cells == 0, FREE, UNSEEN)
    for model, rate in ((by_depth, 0.99), (by_points, 0.98)):
        states = model.classify(points)
        assert np.count_nonzero(states == SURFACE) == 0
        assert np.mean(states == expected) > rate
        assert np.mean(states[cells == 2] == UNSEEN) > 0.99  # what OctoMap never reached, the model did not see
    # Every disagreement of the depth image's model is in a cell that straddles its own free/unseen boundary.
    wrong = points[by_depth.classify(points) != expected]
    corners = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)], float)
    cell_lo = occ.region_min + h * np.floor((wrong - occ.region_min) / h)
    at_corners = np.stack([by_depth.classify(cell_lo + h * c) for c in corners], axis=1)
    assert np.all((at_corners == FREE).any(axis=1) & (at_corners == UNSEEN).any(axis=1))


@pytest.mark.parametrize(
    "call, message",
    [
        (lambda: VisibilityModel.from_depth(np.zeros((0, 0)), CAM, IDENTITY), "depth: expected a 48 x 64"),
        (lambda: VisibilityModel.from_depth(np.full((48, 64), np.nan), CAM, IDENTITY), "depth: no pixel"),
        (lambda: VisibilityModel.from_depth(np.ones((48, 64, 1)), CAM, IDENTITY), "depth: expected a 2-D array"),
        (lambda: VisibilityModel.from_depth(np.ones((64, 48)), CAM, IDENTITY), "depth: expected a 48 x 64"),
        (lambda: VisibilityModel.from_depth(-np.ones((48, 64)), CAM, IDENTITY), "depth: pixel (row 0, column 0)"),
        (lambda: VisibilityModel.from_depth(np.ones((48, 64)), CAM, [0, 0, 0, 0, 0, 0, 2]), "T_world_camera"),
        (lambda: VisibilityModel.from_depth(np.ones((48, 64)), CAM, [0, 0, 0, 0, 0, 1]), "T_world_camera"),
        (lambda: VisibilityModel.from_depth(np.ones((48, 64)), CAM, IDENTITY, surface_tolerance=-1), "surface_tol"),
        (lambda: VisibilityModel.from_depth(np.ones((48, 64)), CAM, IDENTITY, tolerance=0.01), "unknown setting"),
        (lambda: VisibilityModel.from_organized(np.ones((10, 3)), IDENTITY), "needs height and width"),
        (lambda: VisibilityModel.from_organized(np.ones((4, 5, 2)), IDENTITY), "points: expected shape (H, W, 3)"),
        (lambda: VisibilityModel.from_organized(np.full((4, 5, 3), np.nan), IDENTITY), "points: the intrinsics"),
        (lambda: VisibilityModel.from_points(np.zeros((0, 3)), [0, 0, 1]), "points: no finite point"),
        (lambda: VisibilityModel.from_points(np.full((5, 3), np.nan), [0, 0, 1]), "points: no finite point"),
        (lambda: VisibilityModel.from_points(np.ones((5, 2)), [0, 0, 1]), "points: expected shape (N, 3)"),
        (lambda: VisibilityModel.from_points(np.ones((5, 3)), [0, 0]), "viewpoint: expected 3 values"),
        (lambda: VisibilityModel.from_points(np.ones((5, 3)), [0, 0, 0], angular_resolution=0), "angular_resol"),
        (lambda: PinholeCamera(0.0, 500, 320, 240, 640, 480), "fx must be"),
        (lambda: PinholeCamera(500, -500, 320, 240, 640, 480), "fy must be"),
        (lambda: PinholeCamera(500, 500, 320, np.nan, 640, 480), "cy must be"),
        (lambda: PinholeCamera(500, 500, 320, 240, 0, 480), "width must be"),
        (lambda: CAM.back_project(np.ones((47, 64))), "depth: expected a 48 x 64"),
        (lambda: PinholeCamera.fit(np.ones((48, 64, 3)) + [0, 0, 1]), "focal lengths"),
    ],
)
def test_bad_input_is_a_value_error_naming_it(call, message):
    with pytest.raises(ValueError, match=re.escape(message)):
        call()


def test_classify_checks_its_points():
    model = VisibilityModel.from_depth(np.ones((48, 64)), CAM, IDENTITY)
    with pytest.raises(ValueError, match="classify: points"):
        model.classify(np.ones((4, 2)))
    with pytest.raises(ValueError, match="signed_distance: points"):
        model.signed_distance("nothing")
    assert model.classify(np.zeros((0, 3))).shape == (0,)


def test_a_depth_scenes_model_keeps_the_images_3x3_median(rng):
    # segment_depth's visibility model holds the depth image median-filtered over 3 x 3 windows (the default
    # visibility_median_window = 1): read back along each pixel's ray (d = z (1 + s / |q|) at depth z), it is scipy's
    # median where the window is all returns, and the upper middle of the window's returns where some are missing.
    from scipy.ndimage import maximum_filter, median_filter

    H, W = 120, 160
    cam = PinholeCamera(200.0, 200.0, 79.5, 59.5, W, H)
    v, u = np.mgrid[0:H, 0:W].astype(float)
    depth = 0.6 + 0.0005 * (u - 80) + rng.normal(0.0, 0.001, (H, W))  # a table, tilted, with noise
    depth[40:80, 60:100] -= 0.08 + rng.normal(0.0, 0.001, (40, 40))  # a box on it
    holes = rng.random((H, W)) < 0.03
    depth[holes] = np.nan
    scene = _core.segment_depth(depth, cam, IDENTITY, None)
    z = 0.5
    q = pixel_rays(cam, u.ravel() + 0.25, v.ravel() + 0.25) * z  # a quarter pixel in: no rounding at a pixel's edge
    s = scene.visibility.signed_distance(q)
    kept = (z * (1.0 + s / np.linalg.norm(q, axis=1))).reshape(H, W)
    full = ~maximum_filter(holes, size=3, mode="constant", cval=True)  # windows of nine returns
    expected = median_filter(np.where(holes, 0.0, depth), size=3)
    assert full.sum() > 12000
    np.testing.assert_allclose(kept[full], expected[full], rtol=1e-12)
    partial = np.argwhere(~full & ~holes)
    assert len(partial) > 1500
    for r, c in partial:
        window = depth[max(r - 1, 0) : r + 2, max(c - 1, 0) : c + 2]
        values = np.sort(window[np.isfinite(window)])
        assert kept[r, c] == pytest.approx(values[len(values) // 2], rel=1e-12), (r, c)
