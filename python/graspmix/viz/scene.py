"""A picture of a segmented scene: the objects coloured by label over the support plane, completed points hollow."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..perception import kind_name
from .plots import plane_frame, pyplot


def plot_scene(scene, path: str | Path, cloud: np.ndarray | None = None, max_background: int = 20000) -> None:
    """Top view (on the plane) and side view (height over it) of scene.objects in colour (their completed points, if
    Scene.complete ran, as hollow markers of the same colour), with the rest of `cloud` (the input points,
    subsampled) in grey. scene: a graspmix.Scene."""
    plt = pyplot()
    o, u, v, n = plane_frame(scene.plane)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.8))
    if cloud is not None and len(cloud):
        step = max(1, len(cloud) // max_background)
        bg = np.asarray(cloud)[::step] - o
        axes[0].scatter(bg @ u, bg @ v, s=0.3, c="0.8", rasterized=True)
        axes[1].scatter(bg @ u, bg @ n, s=0.3, c="0.8", rasterized=True)
    cmap = plt.get_cmap("tab10")
    for obj in scene.objects:
        q = obj.points - o
        colour = cmap(obj.index % 10)
        axes[0].scatter(q @ u, q @ v, s=1.5, color=colour, label=f"{obj.index}: {obj.n_points} pts")
        axes[1].scatter(q @ u, q @ n, s=1.5, color=colour)
        c = obj.centroid - o
        axes[0].annotate(str(obj.index), (c @ u, c @ v), fontsize=11, weight="bold")
        done, _ = scene.completed(obj.index)
        if len(done):  # completed points: hollow markers of the object's colour
            q = done - o
            kind = kind_name(scene.completions[obj.index].kind)
            style = dict(s=4, facecolors="none", edgecolors=[colour], linewidths=0.4)
            axes[0].scatter(q @ u, q @ v, label=f"{obj.index}: {kind} +{len(done)} pts (hollow)", **style)
            axes[1].scatter(q @ u, q @ n, **style)
    if scene.objects:  # frame the objects, with a margin of table around them
        q = scene.points - o
        for ax, (a, b) in zip(axes, ((u, v), (u, n))):
            pad = 0.1
            ax.set_xlim((q @ a).min() - pad, (q @ a).max() + pad)
            ax.set_ylim((q @ b).min() - pad, (q @ b).max() + pad)
    what = "given" if scene.plane_given else ("found" if scene.plane_found else "none: cloud axes")
    axes[0].set_title(f"top view on the support plane ({what})", fontsize=10)
    axes[1].set_title("side view: height over the plane (m)", fontsize=10)
    for ax in axes:
        ax.set_aspect("equal", adjustable="box")
        ax.set_xlabel("m")
    axes[1].axhline(0.0, color="k", lw=0.8)
    axes[0].legend(fontsize=8, markerscale=5, loc="best")
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
