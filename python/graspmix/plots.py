"""Deprecated module path, kept for one release: pictures are ``graspmix.viz``. Every name of the old
module is here."""

from .viz.plots import plot_grasps, plot_surface_features

__all__ = ["plot_grasps", "plot_surface_features"]
