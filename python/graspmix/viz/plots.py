"""Pictures of graspmix results (matplotlib, Agg backend: no display needed)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .. import _core


def pyplot():
    """matplotlib.pyplot on the Agg backend (files only, no display needed)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot_surface_features(
    surface, path, *, max_points: int = 20000, seed: int = 0, title: str | None = None, normals: int = 0
):
    """The cloud coloured by k1 and by k2 side by side, like the paper's Fig. point_cloud_and_feat.

    surface: a SurfaceCloud (or anything with ``points`` (N, 3) and ``curvatures`` (N, 2)).
    max_points: a seeded random subset is drawn when the cloud is larger. normals: draw that many
    normals (also a seeded subset) as short arrows on the k1 panel. Writes ``path`` (png, pdf, svg).
    """
    plt = pyplot()
    P = np.asarray(surface.points)
    K = np.asarray(surface.curvatures)
    if P.shape[0] == 0:
        raise ValueError("plot_surface_features: the cloud is empty")
    rng = np.random.default_rng(seed)
    idx = (
        np.arange(P.shape[0])
        if P.shape[0] <= max_points
        else np.sort(rng.choice(P.shape[0], max_points, replace=False))
    )
    vmax = float(np.quantile(K[idx, 0], 0.99)) or 1e-12  # shared colour scale, robust to a few spikes
    fig = plt.figure(figsize=(11, 5))
    span = (P[idx].max(axis=0) - P[idx].min(axis=0)).max() / 2
    centre = (P[idx].max(axis=0) + P[idx].min(axis=0)) / 2
    for col, name in enumerate(["k1", "k2"]):
        ax = fig.add_subplot(1, 2, col + 1, projection="3d")
        sc = ax.scatter(
            P[idx, 0], P[idx, 1], P[idx, 2], c=K[idx, col], s=2, cmap="viridis", vmin=0, vmax=vmax, linewidths=0
        )
        if col == 0 and normals:
            N = np.asarray(surface.normals)
            j = rng.choice(P.shape[0], min(normals, P.shape[0]), replace=False)
            ax.quiver(
                P[j, 0], P[j, 1], P[j, 2], N[j, 0], N[j, 1], N[j, 2], length=span / 8, color="crimson", linewidth=0.6
            )
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


def plot_grasps(grasps, hand, path, *, top: int = 3, max_points: int = 8000, seed: int = 0, title: str | None = None):
    """The object's cloud with the collision geometry of the best `top` grasps' hands (the first drawn
    strongest), from two viewpoints. grasps: a GraspSet (its surface is drawn) or anything with
    ``surface.points`` and ``grasps`` as in grasps.json; hand: the graspmix.Hand they are for."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    plt = pyplot()
    P = np.asarray(grasps.surface.points)
    rows = grasps.grasps[:top]
    if not rows:
        raise ValueError("plot_grasps: there are no grasps to draw")
    rng = np.random.default_rng(seed)
    idx = np.arange(len(P)) if len(P) <= max_points else rng.choice(len(P), max_points, replace=False)
    meshes = {name: hand.collision_mesh(name) for name in hand.link_names}
    colours = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple"]
    fig = plt.figure(figsize=(12, 6))
    everything = [P[idx]]
    for view, (elev, azim) in enumerate([(25, -60), (70, 30)]):
        ax = fig.add_subplot(1, 2, view + 1, projection="3d")
        ax.scatter(P[idx, 0], P[idx, 1], P[idx, 2], s=1, c="0.35", linewidths=0)
        for k, g in enumerate(rows):
            links = hand.fk(np.asarray(g["T_world_wrist"]), g["grasp_joints"])
            for name, pose in zip(hand.link_names, links):
                V, T = meshes[name]
                if len(T) == 0:
                    continue
                W = _core.pose_multiply(
                    np.tile(pose, (len(V), 1)), np.hstack([V, np.tile([0, 0, 0, 1.0], (len(V), 1))])
                )[:, :3]
                everything.append(W)
                ax.add_collection3d(
                    Poly3DCollection(
                        W[T], alpha=0.35 if k else 0.55, facecolor=colours[k % len(colours)], edgecolor="none"
                    )
                )
        allp = np.vstack(everything)
        centre, span = (allp.max(0) + allp.min(0)) / 2, (allp.max(0) - allp.min(0)).max() / 2
        for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
            setter(c - span, c + span)
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=elev, azim=azim)
        ax.set_xlabel("x (m)")
        ax.set_ylabel("y (m)")
        ax.set_zlabel("z (m)")
    labels = ", ".join(
        f"#{g['rank']} ({colours[k % len(colours)].split(':')[1]}): log L {g['log_likelihood']:.2f}"
        for k, g in enumerate(rows)
    )
    fig.suptitle((title + "\n" if title else "") + labels, fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
