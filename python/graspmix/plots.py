"""Pictures of graspmix results (matplotlib, Agg backend: no display needed)."""
from __future__ import annotations

from pathlib import Path

import numpy as np


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot_surface_features(surface, path, *, max_points: int = 20000, seed: int = 0, title: str | None = None,
                          normals: int = 0):
    """The cloud coloured by k1 and by k2 side by side, like the paper's Fig. point_cloud_and_feat.

    surface: a SurfaceCloud (or anything with ``points`` (N, 3) and ``curvatures`` (N, 2)).
    max_points: a seeded random subset is drawn when the cloud is larger. normals: draw that many
    normals (also a seeded subset) as short arrows on the k1 panel. Writes ``path`` (png, pdf, svg).
    """
    plt = _pyplot()
    P = np.asarray(surface.points)
    K = np.asarray(surface.curvatures)
    if P.shape[0] == 0:
        raise ValueError("plot_surface_features: the cloud is empty")
    rng = np.random.default_rng(seed)
    idx = np.arange(P.shape[0]) if P.shape[0] <= max_points else np.sort(rng.choice(P.shape[0], max_points, replace=False))
    vmax = float(np.quantile(K[idx, 0], 0.99)) or 1e-12  # shared colour scale, robust to a few spikes
    fig = plt.figure(figsize=(11, 5))
    span = (P[idx].max(axis=0) - P[idx].min(axis=0)).max() / 2
    centre = (P[idx].max(axis=0) + P[idx].min(axis=0)) / 2
    for col, name in enumerate(["k1", "k2"]):
        ax = fig.add_subplot(1, 2, col + 1, projection="3d")
        sc = ax.scatter(P[idx, 0], P[idx, 1], P[idx, 2], c=K[idx, col], s=2, cmap="viridis", vmin=0, vmax=vmax,
                        linewidths=0)
        if col == 0 and normals:
            N = np.asarray(surface.normals)
            j = rng.choice(P.shape[0], min(normals, P.shape[0]), replace=False)
            ax.quiver(P[j, 0], P[j, 1], P[j, 2], N[j, 0], N[j, 1], N[j, 2], length=span / 8, color="crimson",
                      linewidth=0.6)
        for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
            setter(c - span, c + span)
        ax.set_xlabel("x [m]")
        ax.set_ylabel("y [m]")
        ax.set_zlabel("z [m]")
        ax.set_title(f"{name} (PCL principal curvature)")
        fig.colorbar(sc, ax=ax, shrink=0.6, label=name)
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(Path(path), dpi=120)
    plt.close(fig)
    return Path(path)
