"""A picture of a recorded demonstration: the object's cloud with the hand at its pre-grasp and grasp."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .. import _core
from .plots import cube_axes, pyplot


def hand_triangles(hand, T_world_wrist, joints) -> list:
    """The hand's collision geometry at a configuration: one (T, 3, 3) array of world triangles per link
    that has any (graspmix's own forward kinematics of the hand)."""
    out = []
    for name, pose in zip(hand.link_names, hand.fk(np.asarray(T_world_wrist, dtype=float), joints)):
        V, T = hand.collision_mesh(name)
        if len(T):
            frames = np.hstack([V, np.tile([0.0, 0.0, 0.0, 1.0], (len(V), 1))])
            out.append(_core.pose_multiply(np.tile(pose, (len(V), 1)), frames)[:, :3][T])
    return out


def plot_demonstration(demo, path: str | Path, *, max_points: int = 8000, seed: int = 0) -> None:
    """Writes a PNG of a Demonstration from two viewpoints: its object cloud (grey), the hand at the
    pre-grasp (outline, light) and at the recorded grasp (solid), with the joint values in the title."""
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    plt = pyplot()
    hand = _core.Hand.from_urdf(str(demo.hand_path))
    P = np.asarray(demo.cloud, dtype=float)
    rng = np.random.default_rng(seed)
    if len(P) > max_points:
        P = P[rng.choice(len(P), max_points, replace=False)]
    pre = hand_triangles(hand, demo.T_world_wrist, demo.pregrasp_joints)
    grasp = hand_triangles(hand, demo.T_world_wrist, demo.grasp_joints)
    pts = np.vstack([P] + [t.reshape(-1, 3) for t in pre + grasp])
    centre, half = (pts.max(0) + pts.min(0)) / 2, (pts.max(0) - pts.min(0)).max() / 2
    fig = plt.figure(figsize=(12, 6))
    for view, (elev, azim) in enumerate([(20, -60), (20, 30)]):
        ax = fig.add_subplot(1, 2, view + 1, projection="3d")
        ax.scatter(P[:, 0], P[:, 1], P[:, 2], s=1, c="0.35", linewidths=0)
        for tris in pre:
            ax.add_collection3d(Poly3DCollection(tris, facecolor="none", edgecolor="tab:orange", linewidths=0.2))
        for tris in grasp:
            ax.add_collection3d(Poly3DCollection(tris, alpha=0.6, facecolor="tab:blue", edgecolor="none"))
        cube_axes(ax, centre, half, (elev, azim))

    def fmt(joints: dict) -> str:
        return ", ".join(f"{k}={v:.3f}" for k, v in joints.items())

    fig.suptitle(
        f"{Path(demo.hand_path).name}: pre-grasp (orange outline) {fmt(demo.pregrasp_joints)}\n"
        f"recorded grasp (blue) {fmt(demo.grasp_joints)}; {len(demo.cloud)} object points",
        fontsize=9,
    )
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
