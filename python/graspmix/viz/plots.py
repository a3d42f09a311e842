"""Pictures of graspmix results (matplotlib, Agg backend: no display needed)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import _core
from ..io import check_digest, load_points
from ..model.options import TABLE_CLEARANCE


def pyplot():
    """matplotlib.pyplot on the Agg backend (files only, no display needed)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def cube_axes(ax, centre, half: float, view: tuple | None = None) -> None:
    """A 3D axes as a cube of half-width `half` (m) around `centre`, labelled in metres, seen from
    view = (elevation, azimuth) in degrees (None: matplotlib's default)."""
    for setter, c in zip((ax.set_xlim, ax.set_ylim, ax.set_zlim), centre):
        setter(c - half, c + half)
    ax.set_box_aspect((1, 1, 1))
    if view is not None:
        ax.view_init(elev=view[0], azim=view[1])
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_zlabel("z (m)")


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


def plane_frame(plane):
    """(origin, u, v, n) of the plane [a, b, c, d] (n its unit normal), or the cloud's own axes without a plane."""
    if plane is None:
        return np.zeros(3), np.eye(3)[0], np.eye(3)[1], np.eye(3)[2]
    plane = np.asarray(plane, dtype=float)
    norm = np.linalg.norm(plane[:3])
    n, d = plane[:3] / norm, plane[3] / norm
    u = np.cross(n, [1.0, 0, 0] if abs(n[0]) < 0.9 else [0, 1.0, 0])
    u /= np.linalg.norm(u)
    return -d * n, u, np.cross(n, u), n


@dataclass
class GraspDrawing:
    """What a picture of grasps shows, in the world frame: the cloud's points (a seeded subset, the table's
    points dropped when the plane is known), the support plane as a square patch, and per drawn grasp its
    links' collision meshes at the grasp joints and its tool centre point."""

    points: np.ndarray  # (M, 3), possibly empty
    plane_patch: np.ndarray | None  # (4, 3) corners, or None
    hands: list  # per grasp: a list of (vertices (V, 3), triangles (T, 3)), one per link with geometry
    tcps: list  # per grasp: (3,) or None
    labels: list  # per grasp: "#rank: log L ..., opening ..."


def _grasp_rows(grasps, top: int):
    rows = list(grasps.grasps if hasattr(grasps, "grasps") else grasps)[: max(int(top), 0)]
    if not rows:
        raise ValueError("plot_grasps: there are no grasps to draw")
    return rows


def _cloud_points(grasps, cloud, plane) -> np.ndarray:
    """The points to draw: `cloud` (a path or (N, 3) points), else the synthesis' scene (its objects), else
    the grasps file's depth image (its view) or cloud when it exists, else none; the support plane's points are
    dropped."""
    if cloud is None:
        scene = getattr(grasps, "scene", None)
        if scene is not None:
            return np.asarray(scene.points, dtype=float)
        surface = getattr(grasps, "surface", None)
        if surface is not None:
            return np.asarray(surface.points, dtype=float)
        name = getattr(grasps, "cloud", "")
        cloud = grasps.view_points() if getattr(grasps, "view", None) is not None else name
        if not isinstance(cloud, np.ndarray) and (not name or not Path(name).is_file()):
            return np.zeros((0, 3))
        if not isinstance(cloud, np.ndarray):
            check_digest(name, getattr(grasps, "cloud_sha256", ""), "cloud")
    points = np.asarray(load_points(cloud)[0], dtype=float)
    if points.ndim != 2 or points.shape[1] != 3:
        raise ValueError(f"plot_grasps: cloud must be (N, 3) points, got shape {points.shape}")
    if plane is not None and len(points):
        o, _, _, n = plane_frame(plane)
        points = points[np.abs((points - o) @ n) > TABLE_CLEARANCE]
    return points


def _link_meshes(hand, grasp) -> list:
    """The collision meshes of every link of `hand` at the grasp's wrist and grasp joints (world)."""
    out = []
    links = hand.fk(np.asarray(grasp.T_world_wrist, dtype=float), grasp.grasp_joints)
    for name, pose in zip(hand.link_names, links):
        V, T = hand.collision_mesh(name)
        if len(T) == 0:
            continue
        W = _core.pose_multiply(np.tile(pose, (len(V), 1)), np.hstack([V, np.tile([0, 0, 0, 1.0], (len(V), 1))]))
        out.append((W[:, :3], np.asarray(T)))
    return out


def _label(g, k: int) -> str:
    text = f"#{k + 1 if g.rank is None else g.rank}"
    if g.log_likelihood is not None:
        text += f": log L {float(g.log_likelihood):.2f}"
    if g.opening_width is not None:
        text += f", opening {g.opening_width * 1e3:.1f} mm"
    return text


def grasp_drawing(
    grasps, hand=None, *, cloud=None, plane=None, top: int = 3, max_points: int = 8000, seed: int = 0
) -> GraspDrawing:
    """The geometry plot_grasps and plot_grasps_html draw. grasps: a GraspSet (its hand, plane and cloud
    are used unless given) or a list of Grasps (then hand is needed)."""
    rows = _grasp_rows(grasps, top)
    hand = hand if hand is not None else grasps.get_hand() if hasattr(grasps, "get_hand") else None
    if hand is None:
        raise ValueError("plot_grasps: give the hand the grasps are for")
    plane = plane if plane is not None else getattr(grasps, "plane", None)
    points = _cloud_points(grasps, cloud, plane)
    if len(points) > max_points:
        points = points[np.sort(np.random.default_rng(seed).choice(len(points), max_points, replace=False))]
    hands = [_link_meshes(hand, g) for g in rows]
    patch = None
    if plane is not None:
        o, u, v, n = plane_frame(plane)
        allp = np.vstack([points, *[W for meshes in hands for W, _ in meshes]])
        centre = allp.mean(axis=0)
        centre = centre - ((centre - o) @ n) * n
        half = max(0.6 * float((allp.max(0) - allp.min(0)).max()), 0.05)
        patch = np.array([centre + half * (a * u + b * v) for a, b in ((-1, -1), (1, -1), (1, 1), (-1, 1))])
    tcps = [None if g.T_world_tcp is None else np.asarray(g.T_world_tcp[:3]) for g in rows]
    return GraspDrawing(points, patch, hands, tcps, [_label(g, k) for k, g in enumerate(rows)])


COLOURS = ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple"]


def plot_grasps(
    grasps,
    hand=None,
    path=None,
    *,
    cloud=None,
    plane=None,
    top: int = 3,
    max_points: int = 8000,
    seed: int = 0,
    title: str | None = None,
):
    """The cloud, the support plane (a grey patch) and the hands of the best `top` grasps as their links'
    collision shapes (the first drawn strongest, a black dot at each tool centre point), from two
    viewpoints. grasps: a GraspSet (also one from GraspSet.load) or a list of grasps with `hand`; cloud: a
    path or (N, 3) points instead of the set's own. Writes `path` (png, pdf, svg) and returns it, or
    returns the matplotlib Figure when path is None."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    d = grasp_drawing(grasps, hand, cloud=cloud, plane=plane, top=top, max_points=max_points, seed=seed)
    plt = pyplot()
    fig = plt.figure(figsize=(12, 6))
    allp = np.vstack([d.points, *[W for meshes in d.hands for W, _ in meshes], *[t for t in d.tcps if t is not None]])
    centre, span = (allp.max(0) + allp.min(0)) / 2, (allp.max(0) - allp.min(0)).max() / 2
    for view, (elev, azim) in enumerate([(25, -60), (70, 30)]):
        ax = fig.add_subplot(1, 2, view + 1, projection="3d")
        if d.plane_patch is not None:
            ax.add_collection3d(Poly3DCollection([d.plane_patch], alpha=0.25, facecolor="0.6", edgecolor="0.4"))
        if len(d.points):
            ax.scatter(d.points[:, 0], d.points[:, 1], d.points[:, 2], s=1, c="0.35", linewidths=0)
        for k, meshes in enumerate(d.hands):
            colour = COLOURS[k % len(COLOURS)]
            for W, T in meshes:
                ax.add_collection3d(
                    Poly3DCollection(W[T], alpha=0.35 if k else 0.55, facecolor=colour, edgecolor="none")
                )
            if d.tcps[k] is not None:
                ax.scatter(*d.tcps[k], s=12, c="k")
        cube_axes(ax, centre, span, (elev, azim))
    labels = ", ".join(f"{lab} ({COLOURS[k % len(COLOURS)].split(':')[1]})" for k, lab in enumerate(d.labels))
    fig.suptitle((title + "\n" if title else "") + labels, fontsize=9)
    fig.tight_layout()
    if path is None:
        return fig
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)
