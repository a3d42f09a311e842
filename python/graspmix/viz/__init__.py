"""Pictures of graspmix results (matplotlib on the Agg backend: files, no display): surface features,
a hand at its joint limits, grasps on a cloud (also as an interactive HTML page, plotly), depth images of an
acquisition, a segmented scene, and the experiment's figures."""

from ..model.grasps import register_grasp_plotter
from .depth import plot_depth_images
from .experiment import plot_runtime, plot_success
from .grasps_html import grasps_figure, plot_grasp_set, plot_grasps_html
from .hand import plot_hand
from .plots import grasp_drawing, plot_grasps, plot_surface_features, pyplot
from .scene import plot_scene

register_grasp_plotter(plot_grasp_set)  # GraspSet.plot (the model layer cannot import this one)

__all__ = [
    "plot_depth_images",
    "grasp_drawing",
    "grasps_figure",
    "plot_grasps",
    "plot_grasps_html",
    "plot_hand",
    "plot_runtime",
    "plot_scene",
    "plot_success",
    "plot_surface_features",
    "pyplot",
]
