"""Pictures of graspmix results (matplotlib on the Agg backend: files, no display): surface features,
a hand at its joint limits, grasps on a cloud, depth images of an acquisition, a segmented scene, and
the experiment's figures."""

from .depth import plot_depth_images
from .experiment import plot_runtime, plot_success
from .hand import plot_hand
from .plots import plot_grasps, plot_surface_features, pyplot
from .scene import plot_scene

__all__ = [
    "plot_depth_images",
    "plot_grasps",
    "plot_hand",
    "plot_runtime",
    "plot_scene",
    "plot_success",
    "plot_surface_features",
    "pyplot",
]
