"""A scene (SceneSpec) as depth cameras see it: rendered with pybullet, each point labelled with the object
it lies on (the renderer's segmentation mask: -1 the table, else the index in spec.objects) and the
position of the camera that saw it.

One camera by default, fixed as a real one would be above a table: SCENE_CAMERA, 640 x 480 like a
structured-light or stereo depth camera, 55 cm in front of the workspace's centre and 55 cm above the
table, looking at the centre (45 degrees down). views=n > 1: the paper's ring of n cameras
(acquisition.ring_cameras).
"""

from __future__ import annotations

import numpy as np

from ..io import pybullet_data_path, resolve_object
from ..io.checks import check_int, check_seed, quote
from .acquisition import (
    Acquisition,
    AcquisitionSettings,
    Camera,
    apply_noise,
    back_project,
    render_depth,
    ring_cameras,
)
from .execution import load_object
from .scenes import SceneSpec

SCENE_CAMERA = Camera(eye=(0.0, -0.55, 0.55), target=(0.0, 0.0, 0.0), width=640, height=480)


def scene_cameras(views: int = 1) -> list[Camera]:
    """views = 1: SCENE_CAMERA; views = n > 1: the paper's ring of n cameras."""
    views = check_int(views, "views", 1, 64)
    return [SCENE_CAMERA] if views == 1 else ring_cameras(views)


class _Renderer:
    """A pybullet DIRECT world with plane.urdf and the scene's objects at their link poses."""

    def __init__(self, spec: SceneSpec):
        import pybullet as p

        self.client = p.connect(p.DIRECT)
        try:
            p.setAdditionalSearchPath(str(pybullet_data_path()), physicsClientId=self.client)
            self.plane = p.loadURDF("plane.urdf", physicsClientId=self.client)
            self.bodies = []
            for i, o in enumerate(spec.objects):
                try:
                    load_object(o.urdf)  # the URDF checked whole (and bounded) before pybullet reads it
                except ValueError as e:
                    raise ValueError(f"scene object {i} ({quote(o.urdf)}): {e}") from None
                try:
                    body = p.loadURDF(
                        str(resolve_object(o.urdf)),
                        o.pose[:3].tolist(),
                        o.pose[3:].tolist(),
                        globalScaling=float(o.scale),
                        physicsClientId=self.client,
                    )
                except p.error as e:
                    raise ValueError(f"scene object {i} ({quote(o.urdf)}): pybullet cannot load it ({e})") from None
                self.bodies.append(body)
        except Exception:
            p.disconnect(self.client)
            raise

    def render(self, cam: Camera) -> tuple[np.ndarray, np.ndarray]:
        """Metric depth (inf where nothing was hit) and the label per pixel (-1 table, -2 nothing, else the
        object's index)."""
        depth, seg = render_depth(self.client, cam)
        labels = np.full(seg.shape, -2)
        labels[seg == self.plane] = -1
        for i, body in enumerate(self.bodies):
            labels[seg == body] = i
        return depth, labels

    def close(self):
        import pybullet as p

        p.disconnect(self.client)


def acquire_scene(
    spec: SceneSpec,
    views: int = 1,
    noise: bool = False,
    seed: int = 0,
    keep: str = "scene",
    cameras: list[Camera] | None = None,
    settings: AcquisitionSettings | None = None,
) -> Acquisition:
    """The scene's points (world frame) from `views` cameras (or the given ones), with per-point viewpoints,
    camera indices and labels (Acquisition.labels: -1 table, else the object's index in spec.objects, from
    the noise-free segmentation mask); the depth noise model when noise is on (seeded; settings'
    pixel_noise_std and depth_noise_std). keep: "scene" (what the camera sees: the table too) or "object"
    (the objects' pixels only)."""
    if keep not in ("object", "scene"):
        raise ValueError(f"keep must be 'object' or 'scene', got {quote(keep)}")
    check_seed(seed)
    spec.check()
    cams = list(cameras) if cameras is not None else scene_cameras(views)
    s = settings or AcquisitionSettings()
    rng = np.random.default_rng(seed)
    renderer = _Renderer(spec)
    pts, views_, idx, labels, images, masks = [], [], [], [], [], []
    try:
        for i, cam in enumerate(cams):
            depth, lab = renderer.render(cam)
            if noise:
                depth = apply_noise(depth, rng, s.pixel_noise_std, s.depth_noise_std)
            images.append(depth)
            masks.append(lab >= 0)
            world, flat = back_project(depth, cam)
            lab = lab.ravel()[flat]
            keep_rows = lab >= (0 if keep == "object" else -1)
            pts.append(world[keep_rows])
            labels.append(lab[keep_rows])
            views_.append(np.tile(np.asarray(cam.eye, dtype=float), (int(keep_rows.sum()), 1)))
            idx.append(np.full(int(keep_rows.sum()), i))
    finally:
        renderer.close()
    points = np.vstack(pts)
    if len(points) == 0:
        raise ValueError("acquire_scene: no camera sees anything of the scene (check the cameras)")
    return Acquisition(
        points=points,
        viewpoints=np.vstack(views_),
        camera_index=np.concatenate(idx),
        depth_images=images,
        object_pose=spec.poses,
        cameras=cams,
        noise=noise,
        seed=seed,
        object_masks=masks,
        keep=keep,
        labels=np.concatenate(labels),
    )
