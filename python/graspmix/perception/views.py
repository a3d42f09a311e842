"""One depth camera's view as its driver gives it: a depth image with its intrinsics, or an organized cloud in the
sensor frame (x right, y down, z forward; NaN where nothing was hit), and the camera's pose in the world
(T_world_camera = [x, y, z, qx, qy, qz, qw], from the robot's kinematics). segment_view makes its scene in image
space (graspmix._core.segment_depth / segment_organized, include/graspmix/perception/depth_scene.hpp).

    view = depth_view("depth.png", intrinsics=(fx, fy, cx, cy), camera_pose=pose)   # 16-bit PNG in mm
    view = organized_view(cloud_hw3, camera_pose=pose)
    scene = segment_view(view)
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import _core
from ..io import as_points, check_input_file, quote, sha256_file
from .scene import in_world

IDENTITY_POSE = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0)
# m per unit of an integer depth image when no depth_scale is given: millimetres, as RealSense, Kinect and ROS
# (16UC1) write depth; a floating-point image is taken in metres (ROS's 32FC1).
INTEGER_DEPTH_SCALE = 0.001
DEPTH_SUFFIXES = (".png", ".npy")


@dataclass(frozen=True)
class CameraView:
    """One camera's view: depth (H, W) in metres along z (NaN: no return), camera (graspmix.PinholeCamera), pose
    (7,) T_world_camera; organized (H, W, 3) the sensor-frame cloud when the view was given as one (its own x and
    y are used, not the depths re-projected)."""

    depth: np.ndarray
    camera: object
    pose: np.ndarray
    organized: np.ndarray | None = None

    @property
    def position(self) -> np.ndarray:
        """(3,) the camera's position in the world."""
        return self.pose[:3].copy()

    def world_points(self) -> np.ndarray:
        """(N, 3) the points of the pixels with a return, in the world frame."""
        cloud = self.organized if self.organized is not None else self.camera.back_project(self.depth)
        pts = cloud.reshape(-1, 3)
        pts = pts[np.all(np.isfinite(pts), axis=1)]
        T = np.asarray(_core.camera_pose_matrix(self.pose))
        return pts @ T[:3, :3].T + T[:3, 3]


def _numbers(value, what: str) -> np.ndarray:
    """value as an array of floats; ValueError naming `what` for text, ragged lists or anything not numbers."""
    try:
        out = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{what}: expected numbers, got {value!r:.80}") from None
    return out


def checked_pose(camera_pose) -> np.ndarray:
    """(7,) T_world_camera, a unit quaternion (the C++ check, kUnitQuaternionTolerance); None is the identity (the
    world is the camera's frame)."""
    pose = _numbers(IDENTITY_POSE if camera_pose is None else camera_pose, "camera_pose")
    if pose.shape != (7,):
        raise ValueError(f"camera_pose: expected 7 numbers x, y, z, qx, qy, qz, qw, got shape {pose.shape}")
    _core.camera_pose_matrix(pose)  # the C++ check (a unit quaternion, finite)
    return pose


# A depth PNG larger than this is refused before it is decoded (today's depth cameras: 1-2 Mpx; PIL warns at 89 Mpx).
MAX_DEPTH_PIXELS = 40_000_000


def read_depth(path) -> np.ndarray:
    """The depth image of a file: a 16-bit single-channel PNG (millimetres, as RealSense and ROS write it) or a .npy
    (H, W) array; ValueError naming the file for anything else (an 8-bit or colour PNG is not a depth image)."""
    p = check_input_file(path, "depth")
    if p.suffix.lower() not in DEPTH_SUFFIXES:
        raise ValueError(f"{quote(str(path))}: a depth image is a 16-bit PNG or a .npy array, got {quote(p.suffix)}")
    if p.suffix.lower() == ".npy":
        try:
            return np.load(p, allow_pickle=False)
        except (ValueError, OSError) as e:
            raise ValueError(f"{quote(str(path))}: cannot read the depth array ({e})") from None
    from PIL import Image, UnidentifiedImageError

    try:
        with warnings.catch_warnings():  # the size is this function's to judge, below, in one line
            warnings.simplefilter("ignore", Image.DecompressionBombWarning)
            im = Image.open(p)
        with im:
            if im.width * im.height > MAX_DEPTH_PIXELS:
                raise ValueError(
                    f"{quote(str(path))}: {im.width} x {im.height} pixels is not a depth camera's image (at most "
                    f"{MAX_DEPTH_PIXELS:,} pixels)"
                )
            mode = im.mode
            if mode not in ("I;16", "I;16B", "I"):
                raise ValueError(
                    f"{quote(str(path))}: a depth PNG has one 16-bit channel (millimetres), this one is {mode!r} "
                    "(8-bit or colour: a picture, not a depth image)"
                )
            return np.asarray(im)
    except (UnidentifiedImageError, Image.DecompressionBombError, OSError) as e:
        raise ValueError(f"{quote(str(path))}: cannot read the PNG ({e})") from None


def write_depth(path, depth) -> None:
    """Writes a depth image ((H, W) metres; 0, NaN or inf: no return) as a 16-bit PNG in millimetres, as a RealSense or
    ROS driver does (read_depth reads it back, to the millimetre); ValueError for a depth under 0 or beyond 65.535 m
    (what 16 bits of millimetres hold)."""
    from PIL import Image

    d = np.asarray(depth, dtype=float)
    if d.ndim != 2 or d.size == 0:
        raise ValueError(f"depth: expected an (H, W) image, got shape {d.shape}")
    hit = np.isfinite(d) & (d != 0)
    mm = np.round(np.where(hit, d, 0.0) / INTEGER_DEPTH_SCALE)
    if np.any(mm < 0) or np.any(mm > np.iinfo(np.uint16).max):
        raise ValueError(
            f"depth: a 16-bit PNG in millimetres holds 0-65.535 m, got {d[hit].min():g}-{d[hit].max():g} m"
        )
    Image.fromarray(mm.astype(np.uint16)).save(path, format="PNG")


def pinhole(intrinsics, width: int, height: int):
    """A PinholeCamera of an image width x height from intrinsics: a PinholeCamera (its size must match), a 3x3
    matrix K, or (fx, fy, cx, cy); ValueError naming what is wrong (zero or negative focal lengths included)."""
    if isinstance(intrinsics, _core.PinholeCamera):
        if (intrinsics.width, intrinsics.height) != (width, height):
            raise ValueError(
                f"intrinsics: the camera is {intrinsics.width} x {intrinsics.height}, the image {width} x {height}"
            )
        return intrinsics
    k = _numbers(intrinsics, "intrinsics")
    if k.shape == (3, 3):
        if not np.allclose(k[[1, 2, 2, 2], [0, 0, 1, 2]], [0, 0, 0, 1]) or k[0, 1] != 0:
            raise ValueError(f"intrinsics: a pinhole K is [[fx, 0, cx], [0, fy, cy], [0, 0, 1]], got {k.tolist()}")
        k = k[[0, 1, 0, 1], [0, 1, 2, 2]]
    if k.shape != (4,):
        raise ValueError(f"intrinsics: expected K (3, 3) or fx, fy, cx, cy, got shape {k.shape}")
    return _core.PinholeCamera(*map(float, k), width, height)


def depth_view(depth, intrinsics, camera_pose=None, depth_scale=None) -> CameraView:
    """A view from a depth image ((H, W) array or a file read by read_depth) with its intrinsics (pinhole()) and the
    camera's pose (None: the identity); depth_scale: metres per unit (None: INTEGER_DEPTH_SCALE for an integer
    image, 1 for floating point). 0, NaN and inf are no return."""
    d = read_depth(depth) if isinstance(depth, (str, Path)) else np.asarray(depth)
    if d.ndim != 2 or d.size == 0:
        raise ValueError(f"depth: expected an (H, W) image, got shape {d.shape}")
    if d.dtype.kind not in "uif":
        raise ValueError(f"depth: expected numbers, got dtype {d.dtype}")
    scale = INTEGER_DEPTH_SCALE if d.dtype.kind in "ui" else 1.0
    if depth_scale is not None:
        scale = _numbers(depth_scale, "depth_scale")
        if scale.shape != ():
            raise ValueError(f"depth_scale: expected one number (metres per unit), got shape {scale.shape}")
        scale = float(scale)
    if not (np.isfinite(scale) and scale > 0):
        raise ValueError(f"depth_scale: expected metres per unit > 0, got {depth_scale!r}")
    metres = d.astype(float) * scale  # 0, NaN and inf stay no return; a negative depth is the C++ check's error
    camera = pinhole(intrinsics, d.shape[1], d.shape[0])
    camera.check_image(metres)
    return CameraView(metres, camera, checked_pose(camera_pose))


def organized_view(points, camera_pose=None) -> CameraView:
    """A view from an organized cloud (H, W, 3) in the sensor frame (NaN rows: no return) and the camera's pose
    (None: the identity); its intrinsics are fitted (PinholeCamera.fit), so a cloud that is not a pinhole image in
    the sensor frame is a ValueError saying so."""
    pts = np.asarray(points, dtype=float)
    if pts.ndim != 3 or pts.shape[2] != 3:
        raise ValueError(f"organized cloud: expected shape (H, W, 3) in the sensor frame, got {pts.shape}")
    fit = _core.PinholeCamera.fit(pts)
    return CameraView(pts[:, :, 2].copy(), fit.camera, checked_pose(camera_pose), organized=pts)


def segment_view(view: CameraView, plane=None, settings=None):
    """The support plane and the objects of one camera's view (the Scene of segment_scene, in the world frame):
    graspmix._core.segment_organized for a view given as an organized cloud, else segment_depth."""
    from .scene import Scene

    if view.organized is not None:
        result = _core.segment_organized(view.organized, view.pose, plane, camera=view.camera, settings=settings)
    else:
        result = _core.segment_depth(view.depth, view.camera, view.pose, plane, settings=settings)
    return Scene(result, view.position)


def organized_file_view(loaded, camera_pose=None) -> CameraView | None:
    """The view of an organized cloud file (graspmix._core.load_cloud's CloudData, height > 1; None otherwise): its
    points in the sensor frame given camera_pose (then the file's VIEWPOINT must be the identity), or in the frame
    where its VIEWPOINT is the camera's optical frame (x right, y down, z forward: the world, the VIEWPOINT the
    camera's pose), or, with neither, in the camera's frame. None when the grid is no pinhole image in that camera's
    frame (e.g. a world-frame grid without its camera): it is then taken as points."""
    if loaded.height <= 1:
        return None
    pose = camera_pose
    if camera_pose is not None and loaded.has_viewpoint:
        raise ValueError(
            f"{loaded.path}: the file gives its camera's pose (VIEWPOINT) and camera_pose is given too: give one"
        )
    if camera_pose is None and loaded.has_viewpoint:
        pose = np.asarray(loaded.viewpoint, dtype=float)
        grid = loaded.organized(camera_pose=pose)  # into the camera's frame (NaN holes stay NaN)
    else:
        grid = loaded.organized()
    try:
        return organized_view(grid, pose)
    except ValueError as e:
        if "sensor frame" not in str(e):
            raise
    if camera_pose is None and loaded.has_viewpoint and _is_sensor_grid(loaded.organized()):
        raise ValueError(
            f"{loaded.path}: its points are a camera's image in their own frame (the sensor's), but its VIEWPOINT "
            "(the camera's pose in the world) says they are in the world: write the VIEWPOINT as 0 0 0 1 0 0 0 and "
            "give the pose as --camera-pose (camera_pose=), or write the points in the world frame"
        )
    return None


def _is_sensor_grid(grid: np.ndarray) -> bool:
    """Whether an organized (H, W, 3) grid is a pinhole camera's image in its own frame."""
    try:
        organized_view(grid, None)
    except ValueError:
        return False
    return True


# A table tilted more than this from the world's z axis, which a w-first reading of the camera pose's quaternion
# would level to within LEVEL_DEG, is noted as the likely mistake (quaternion_order_note).
TILTED_DEG, LEVEL_DEG = 30.0, 10.0


def _tilt_deg(normal: np.ndarray) -> float:
    return float(np.degrees(np.arccos(min(1.0, abs(normal[2]) / np.linalg.norm(normal)))))


def quaternion_order_note(camera_pose, plane) -> str | None:
    """A note when the support plane found from a camera with this pose stands tilted from the world's z axis and
    the pose's quaternion read w-first ([qw, qx, qy, qz], as some libraries write it) would make it level: the
    quaternion order is the likely mistake. None otherwise (no pose, no plane, a level table, or a tilt the other
    order does not explain)."""
    if camera_pose is None or plane is None:
        return None
    pose = checked_pose(camera_pose)
    normal = np.asarray(plane, dtype=float)[:3]
    tilt = _tilt_deg(normal)
    if tilt <= TILTED_DEG:
        return None
    R = np.asarray(_core.camera_pose_matrix(pose))[:3, :3]
    other = np.concatenate([pose[:3], pose[[4, 5, 6, 3]]])  # what [qw, qx, qy, qz] meant, as x, y, z, w
    R_other = np.asarray(_core.camera_pose_matrix(other))[:3, :3]
    level = _tilt_deg(R_other @ (R.T @ normal))
    if level > LEVEL_DEG:
        return None
    q = ", ".join(f"{v:g}" for v in pose[3:])
    meant = ", ".join(f"{v:g}" for v in other[3:])
    return (
        f"the table found is {tilt:.0f} degrees from the world's z axis; the camera pose's quaternion is read qx, qy, "
        f"qz, qw: if [{q}] was meant w-first (qw, qx, qy, qz), give [{meant}] (the table then {level:.0f} degrees)"
    )


# What scene_input says when an organized file is taken as points (the scene's notes).
NOT_A_CAMERA_VIEW = (
    "{path}: organized, but no camera's image in its frame (no VIEWPOINT with the camera's optical-frame pose, "
    "no --camera-pose): segmented as points, not in image space"
)


def scene_input(cloud=None, depth=None, intrinsics=None, depth_scale=None, camera_pose=None, viewpoints=None):
    """(source, name, notes) of a synthesis' or segmentation's input (notes: what the scene should tell its user,
    e.g. NOT_A_CAMERA_VIEW): source one camera's view (a CameraView: a depth image
    with its intrinsics, an organized (H, W, 3) array, or an organized cloud file, organized_file_view) or a cloud
    (points (N, 3), viewpoints) in the world frame (a file's own viewpoints unless `viewpoints` are given; with
    camera_pose, points given in that camera's frame are mapped to the world and the camera is their viewpoint).
    ValueError for inputs that do not go together (a depth image and a cloud, intrinsics without a depth image,
    viewpoints with a view: its camera is its pose)."""
    view, name, notes = None, None, []
    if depth is not None:
        if cloud is not None:
            raise ValueError("give a cloud or a depth image (depth=...), not both")
        if intrinsics is None:
            raise ValueError("depth: a depth image needs its camera's intrinsics (intrinsics=K or (fx, fy, cx, cy))")
        view = depth_view(depth, intrinsics, camera_pose, depth_scale)
        name = str(depth) if isinstance(depth, (str, Path)) else "<depth image>"
        notes = _principal_point_notes(view.camera)
    elif intrinsics is not None or depth_scale is not None:
        raise ValueError("intrinsics and depth_scale go with a depth image (depth=...)")
    elif cloud is None:
        raise ValueError("no input: give a cloud (a path, an (N, 3) or (H, W, 3) array) or a depth image (depth=...)")
    elif isinstance(cloud, (str, Path)):
        check_input_file(cloud, "cloud")
        loaded = _core.load_cloud(str(cloud))
        view, name = organized_file_view(loaded, camera_pose), str(cloud)
        if view is None:
            points, file_viewpoints = np.asarray(loaded.points), _file_viewpoints(loaded)
            notes = [NOT_A_CAMERA_VIEW.format(path=cloud)] if loaded.height > 1 else []
            return in_world(points, file_viewpoints if viewpoints is None else viewpoints, camera_pose), name, notes
    elif _ndim(cloud) == 3:
        view, name = organized_view(cloud, camera_pose), "<organized cloud>"
    else:
        return in_world(as_points(cloud), viewpoints, camera_pose), "<array>", []
    if viewpoints is not None:
        raise ValueError("viewpoints: a camera view's viewpoint is its camera (camera_pose); give no viewpoints")
    return view, name, notes


def _principal_point_notes(camera) -> list[str]:
    """A note when the principal point lies outside the image: right for a crop of a larger image, else a slip of
    a sign or of the order fx, fy, cx, cy (the objects then land where the camera did not look, without an error)."""
    if 0 <= camera.cx <= camera.width and 0 <= camera.cy <= camera.height:
        return []
    return [
        f"intrinsics: the principal point (cx {camera.cx:g}, cy {camera.cy:g}) lies outside the {camera.width} x "
        f"{camera.height} image: right only for a crop of a larger image; check the order fx, fy, cx, cy and the signs"
    ]


def depth_record(depth, view: CameraView, depth_scale=None) -> dict | None:
    """What a GraspSet keeps of a depth image file so the view can be read again (GraspSet.view): its path, the
    intrinsics fx, fy, cx, cy, the depth scale as given, the camera's pose and the file's SHA-256 (GraspSet.view_points
    refuses a file replaced since); None for an array (no file)."""
    if not isinstance(depth, (str, Path)):
        return None
    c = view.camera
    return {
        "depth": str(Path(depth).resolve()),
        "sha256": sha256_file(depth),
        "intrinsics": [float(c.fx), float(c.fy), float(c.cx), float(c.cy)],
        "depth_scale": None if depth_scale is None else float(depth_scale),
        "camera_pose": [float(x) for x in view.pose],
    }


def _ndim(cloud) -> int:
    """The number of dimensions of an array-like, -1 for a ragged one (as_points then names the problem)."""
    try:
        return np.ndim(cloud)
    except ValueError:
        return -1


def _file_viewpoints(loaded):
    """A cloud file's per-point camera positions (N, 3), else its VIEWPOINT's position (3,), else None."""
    if len(loaded.viewpoints):
        return np.asarray(loaded.viewpoints)
    return np.asarray(loaded.viewpoint[:3]) if loaded.has_viewpoint else None
