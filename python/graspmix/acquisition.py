"""Deprecated module path, kept for one release: the simulated cameras are ``graspmix.sim.acquisition``
(and the depth-image picture ``graspmix.viz.plot_depth_images``). Every name of the old module is here."""

from .io import pybullet_data_path, resolve_object
from .sim.acquisition import (
    Acquisition,
    AcquisitionSettings,
    Camera,
    Scene,
    acquire,
    apply_noise,
    back_project,
    clean_up,
    ring_cameras,
)
from .viz.depth import plot_depth_images

__all__ = [
    "Acquisition",
    "AcquisitionSettings",
    "Camera",
    "Scene",
    "acquire",
    "apply_noise",
    "back_project",
    "clean_up",
    "plot_depth_images",
    "pybullet_data_path",
    "resolve_object",
    "ring_cameras",
]
