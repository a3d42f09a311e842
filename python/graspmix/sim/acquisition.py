"""Simulated depth-camera acquisition with pybullet (DIRECT mode, no window).

An object from pybullet_data (or any URDF) rests at a fixed pose on a support plane; fixed depth
cameras look at it; their depth buffers become metric depth, optionally corrupted with the noise
model of Johns et al. 2016 that the paper uses (eq:noise_model)::

    z~(u, v) = z(u + N(0, sigma_p^2), v + N(0, sigma_p^2)) + N(0, sigma_d^2)

with sigma_p = 1 pixel and sigma_d = 1 mm, and are back-projected into the world frame and stitched.
The lateral shift reads the depth of the nearest pixel to the shifted position (a real sensor
does not blend depths across an edge, so no interpolation).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

import numpy as np

from .. import _core
from ..io import pybullet_data_path, resolve_object
from ..io.checks import check_float, check_int, check_seed, quote
from ..model.settings import FeatureScale


def _import_pybullet_quietly() -> None:
    """pybullet prints its build time on stderr when first imported, which would turn a CLI's one-line
    error into two; import it once with stderr pointed at /dev/null."""
    import os
    import sys

    if "pybullet" in sys.modules:
        return
    try:
        sys.stderr.flush()
        saved = os.dup(2)
    except (OSError, ValueError):  # no real stderr (embedded interpreters): leave the import to its users
        return
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, 2)
        os.close(devnull)
        import pybullet  # noqa: F401
    except ImportError:
        pass  # reported by the first function that needs it
    finally:
        os.dup2(saved, 2)
        os.close(saved)


_import_pybullet_quietly()


@dataclass
class Camera:
    """A pinhole depth camera. Units: metres, degrees for the vertical field of view."""

    eye: tuple[float, float, float]
    target: tuple[float, float, float] = (0.0, 0.0, 0.05)
    up: tuple[float, float, float] = (0.0, 0.0, 1.0)
    width: int = 320
    height: int = 240
    fov_deg: float = 45.0
    near: float = 0.05
    far: float = 3.0

    def view_matrix(self) -> np.ndarray:
        """World -> camera (OpenGL convention: the camera looks along -z), 4x4."""
        import pybullet as p

        return np.asarray(p.computeViewMatrix(self.eye, self.target, self.up)).reshape(4, 4).T

    def projection(self) -> list[float]:
        import pybullet as p

        return p.computeProjectionMatrixFOV(self.fov_deg, self.width / self.height, self.near, self.far)

    def pinhole(self):
        """The camera's intrinsics as a driver gives them (graspmix.PinholeCamera): its depth images (back_project's
        pixel convention) are a pinhole camera's with fx = fy = height / (2 tan(fov / 2)), cx = width / 2 and
        cy = height / 2 - 1 (TinyRenderer samples pixel (u, v) at window position (u, height - 1 - v))."""
        from .. import _core

        f = self.height / (2.0 * math.tan(math.radians(self.fov_deg) / 2.0))
        return _core.PinholeCamera(f, f, self.width / 2.0, self.height / 2.0 - 1.0, self.width, self.height)

    def pose(self) -> list[float]:
        """T_world_camera [x, y, z, qx, qy, qz, qw] of the camera's optical frame (x right, y down, z forward, as
        PCL's and ROS's optical frames): what a robot's kinematics give for the camera."""
        from scipy.spatial.transform import Rotation

        R = np.linalg.inv(self.view_matrix())[:3, :3] @ np.diag([1.0, -1.0, -1.0])  # OpenGL's camera: y up, z back
        return [*map(float, self.eye), *map(float, Rotation.from_matrix(R).as_quat())]


def ring_cameras(
    n: int = 4,
    distance: float = 0.5,
    eye_height: float = 0.35,
    target=(0.0, 0.0, 0.05),
    start_deg: float = 45.0,
    **camera,
) -> list[Camera]:
    """n cameras evenly spaced on a circle of radius `distance` around the target at height `eye_height`,
    all looking at the target (the paper uses 4). Other keywords go to every Camera."""
    cams = []
    for i in range(n):
        a = math.radians(start_deg + 360.0 * i / n)
        eye = (target[0] + distance * math.cos(a), target[1] + distance * math.sin(a), eye_height)
        cams.append(Camera(eye=eye, target=tuple(target), **camera))
    return cams


@dataclass
class AcquisitionSettings:
    cameras: list[Camera] = field(default_factory=ring_cameras)
    object_position: tuple[float, float, float] = (
        0.0,
        0.0,
        0.0,
    )  # x, y of the object; z is set so it rests on the plane
    object_orientation: tuple[float, float, float, float] = (0.0, 0.0, 0.0, 1.0)
    object_scale: float = 1.0
    pixel_noise_std: float = 1.0  # sigma_p, pixels
    depth_noise_std: float = 0.001  # sigma_d, metres
    keep: str = "object"  # "object": pixels that see the object (segmentation mask); "scene": everything hit


@dataclass
class Acquisition:
    points: np.ndarray  # (N, 3) world frame
    viewpoints: np.ndarray  # (N, 3) the position of the camera that saw each point
    camera_index: np.ndarray  # (N,)
    depth_images: list[np.ndarray]  # metric depth per camera (noisy if noise was on), inf where nothing was hit
    object_pose: np.ndarray  # (7,) the object's base pose in the world
    cameras: list[Camera]
    noise: bool
    seed: int
    object_masks: list[np.ndarray] = field(default_factory=list)  # per camera: pixels whose ray hits the object
    keep: str = "object"  # what the acquisition kept (AcquisitionSettings.keep)
    plane: np.ndarray | None = None  # [a, b, c, d] of the support plane when a clean-up found it
    labels: np.ndarray | None = None  # (N,) of a scene: -1 the table, else the object's index (acquire_scene)

    def view_input(self) -> dict:
        """The first camera's depth image with its intrinsics and pose, as GraspModel.synthesize takes a view."""
        camera = self.cameras[0]
        return {"depth": self.depth_images[0], "intrinsics": camera.pinhole(), "camera_pose": camera.pose()}

    def per_pixel(self, per_point: np.ndarray, fill) -> np.ndarray:
        """(H * W, ...) values of the first camera's pixels from values per point: a one-camera scene acquisition
        keeps every return in the image's row order (acquire_scene, keep "scene"); `fill` where nothing was hit."""
        depth = self.depth_images[0]
        per_point = np.asarray(per_point)
        out = np.full((depth.size, *per_point.shape[1:]), fill, dtype=np.result_type(per_point, np.asarray(fill)))
        out[np.flatnonzero(np.isfinite(depth))] = per_point
        return out


def depth_from_buffer(buffer: np.ndarray, near: float, far: float) -> np.ndarray:
    """OpenGL depth buffer values in [0, 1] to metric depth along the optical axis."""
    return far * near / (far - (far - near) * buffer)


def apply_noise(depth: np.ndarray, rng: np.random.Generator, pixel_std: float, depth_std: float) -> np.ndarray:
    """eq:noise_model on one metric depth image (inf = no return)."""
    h, w = depth.shape
    v, u = np.mgrid[0:h, 0:w]
    su = np.clip(np.rint(u + rng.normal(0.0, pixel_std, (h, w))), 0, w - 1).astype(int)
    sv = np.clip(np.rint(v + rng.normal(0.0, pixel_std, (h, w))), 0, h - 1).astype(int)
    return depth[sv, su] + rng.normal(0.0, depth_std, (h, w))


def back_project(depth: np.ndarray, cam: Camera) -> tuple[np.ndarray, np.ndarray]:
    """Metric depth image -> world points (M, 3) of the finite pixels, and their flat pixel indices."""
    h, w = depth.shape
    v, u = np.mgrid[0:h, 0:w]
    tan_y = math.tan(math.radians(cam.fov_deg) / 2.0)
    tan_x = tan_y * w / h
    # pybullet's TinyRenderer samples image pixel (u, v) at window position (u, h - 1 - v) exactly, not
    # at the pixel centre: found against an analytic cube, and exact there to float precision.
    x_ndc = 2.0 * u / w - 1.0
    y_ndc = 1.0 - 2.0 * (v + 1.0) / h
    ok = np.isfinite(depth)
    z = depth[ok]
    pts_cam = np.stack([x_ndc[ok] * tan_x * z, y_ndc[ok] * tan_y * z, -z, np.ones_like(z)], axis=1)
    world = pts_cam @ np.linalg.inv(cam.view_matrix()).T
    return world[:, :3], np.flatnonzero(ok)


def render_depth(client: int, cam: Camera) -> tuple[np.ndarray, np.ndarray]:
    """What camera `cam` sees of pybullet world `client`: metric depth (inf where nothing was hit) and the
    segmentation mask (body id per pixel, < 0 for nothing)."""
    import pybullet as p

    _, _, _, buf, seg = p.getCameraImage(
        cam.width,
        cam.height,
        cam.view_matrix().T.ravel().tolist(),
        cam.projection(),
        renderer=p.ER_TINY_RENDERER,
        physicsClientId=client,
    )
    buf = np.asarray(buf, dtype=float).reshape(cam.height, cam.width)
    seg = np.asarray(seg).reshape(cam.height, cam.width)
    depth = depth_from_buffer(buf, cam.near, cam.far)
    depth[(buf >= 1.0) | (seg < 0)] = np.inf
    return depth, seg


class TableWorld:
    """A pybullet DIRECT world with a support plane at z = 0 and one object resting on it."""

    def __init__(self, object_path: str | Path, settings: AcquisitionSettings | None = None):
        import pybullet as p

        self.settings = settings or AcquisitionSettings()
        self.object_path = resolve_object(object_path)
        self.client = p.connect(p.DIRECT)
        try:
            p.setAdditionalSearchPath(str(pybullet_data_path()), physicsClientId=self.client)
            self.plane = p.loadURDF("plane.urdf", physicsClientId=self.client)
            s = self.settings
            try:
                self.body = p.loadURDF(
                    str(self.object_path),
                    s.object_position,
                    s.object_orientation,
                    globalScaling=s.object_scale,
                    physicsClientId=self.client,
                )
            except p.error as e:
                raise ValueError(f"{object_path}: pybullet cannot load it ({e})") from None
            # Rest the object on the plane: lift it so its lowest point touches z = 0.
            lo, _ = p.getAABB(self.body, -1, physicsClientId=self.client)
            pos, orn = p.getBasePositionAndOrientation(self.body, physicsClientId=self.client)
            p.resetBasePositionAndOrientation(
                self.body, (pos[0], pos[1], pos[2] - lo[2]), orn, physicsClientId=self.client
            )
        except Exception:
            p.disconnect(self.client)
            raise

    def object_pose(self) -> np.ndarray:
        import pybullet as p

        pos, orn = p.getBasePositionAndOrientation(self.body, physicsClientId=self.client)
        return np.array([*pos, *orn])

    def render_depth(self, cam: Camera) -> tuple[np.ndarray, np.ndarray]:
        """Metric depth (inf where nothing was hit) and the segmentation mask (body id per pixel)."""
        return render_depth(self.client, cam)

    def close(self):
        import pybullet as p

        if self.client is not None and p.isConnected(self.client):
            p.disconnect(self.client)
        self.client = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


def acquire(
    object_path: str | Path,
    noise: bool = False,
    seed: int = 0,
    settings: AcquisitionSettings | None = None,
    postprocess: Callable[[Acquisition], Acquisition] | None = None,
) -> Acquisition:
    """Renders every camera, applies the noise model if asked (seeded), back-projects and stitches.

    With settings.keep == "object", only pixels whose (noise-free) ray hits the object are kept, as
    a segmented sensor would give; "scene" keeps the support plane too, for prepare_cloud to remove.
    postprocess: the clean-up of the stitched cloud (crop, voxel grid, outliers, plane removal), called
    on the Acquisition and returning one (e.g. with fewer points); None keeps the stitched cloud.
    """
    settings = settings or AcquisitionSettings()
    check_seed(seed)
    check_acquisition_settings(settings)
    rng = np.random.default_rng(seed)
    with TableWorld(object_path, settings) as scene:
        pts, views, idx, images, masks = [], [], [], [], []
        for i, cam in enumerate(settings.cameras):
            depth, seg = scene.render_depth(cam)
            if noise:
                depth = apply_noise(depth, rng, settings.pixel_noise_std, settings.depth_noise_std)
            images.append(depth)
            masks.append(seg == scene.body)
            world, flat = back_project(depth, cam)
            if settings.keep == "object":
                keep = seg.ravel()[flat] == scene.body
                world = world[keep]
            pts.append(world)
            views.append(np.tile(np.asarray(cam.eye, dtype=float), (len(world), 1)))
            idx.append(np.full(len(world), i))
        pose = scene.object_pose()
    points = np.vstack(pts)
    if len(points) == 0:
        raise ValueError(f"{object_path}: no camera sees the object (check camera and object placement)")
    acq = Acquisition(
        points=points,
        viewpoints=np.vstack(views),
        camera_index=np.concatenate(idx),
        depth_images=images,
        object_pose=pose,
        cameras=list(settings.cameras),
        noise=noise,
        seed=seed,
        object_masks=masks,
        keep=settings.keep,
    )
    if postprocess is not None:
        acq = postprocess(acq)
        if not isinstance(acq, Acquisition) or len(acq.points) == 0:
            raise ValueError(f"{object_path}: the clean-up left no points (or returned no Acquisition)")
    return acq


def check_acquisition_settings(s: AcquisitionSettings) -> None:
    """The settings' numbers finite and in range, the images of a bounded size; ValueError naming the field."""
    if s.keep not in ("object", "scene"):
        raise ValueError(f"keep must be 'object' or 'scene', got {quote(s.keep)}")
    if not s.cameras:
        raise ValueError("at least one camera is needed")
    check_float(s.object_scale, "object_scale", gt=0.0)
    check_float(s.pixel_noise_std, "pixel_noise_std", 0.0)
    check_float(s.depth_noise_std, "depth_noise_std", 0.0)
    for name, n in (("object_position", 3), ("object_orientation", 4)):
        v = np.asarray(getattr(s, name), dtype=float) if not isinstance(getattr(s, name), str) else None
        if v is None or v.shape != (n,) or not np.all(np.isfinite(v)):
            raise ValueError(f"{name} must be {n} finite numbers, got {quote(getattr(s, name))}")
    for i, cam in enumerate(s.cameras):
        check_int(cam.width, f"cameras[{i}].width", 1, 4096)
        check_int(cam.height, f"cameras[{i}].height", 1, 4096)
        check_float(cam.fov_deg, f"cameras[{i}].fov_deg", gt=0.0, hi=179.0)
        near = check_float(cam.near, f"cameras[{i}].near", gt=0.0)
        check_float(cam.far, f"cameras[{i}].far", gt=near)


def clean_up(
    voxel_size: float = FeatureScale.voxel_size,
    remove_outliers: bool = True,
    remove_plane: bool | None = None,
    seed: int = 0,
) -> Callable[[Acquisition], Acquisition]:
    """The clean-up of the object representation (graspmix.prepare_cloud) as an acquire() postprocess:
    voxel grid, statistical outlier removal and, for a scene acquisition, RANSAC removal of the support
    plane (remove_plane=None: only when settings.keep == "scene" left the plane in; the plane found is
    kept in Acquisition.plane). Viewpoints and camera indices follow the points that survive."""
    check_float(voxel_size, "voxel_size", 0.0)
    check_seed(seed)

    def run(acq: Acquisition) -> Acquisition:
        plane_too = remove_plane if remove_plane is not None else acq.keep == "scene"
        scene = _core.prepare_cloud(
            acq.points, voxel_size=voxel_size, remove_outliers=remove_outliers, remove_plane=plane_too, seed=seed
        )
        rows = np.asarray(scene.sources)  # each kept point's source row (indices are -1 for voxel centroids)
        return dataclasses.replace(
            acq,
            points=np.asarray(scene.points),
            viewpoints=acq.viewpoints[rows],
            camera_index=acq.camera_index[rows],
            plane=np.asarray(scene.plane) if scene.plane_found else acq.plane,
        )

    return run
