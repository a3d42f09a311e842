"""A picture of a hand at its joint limits: every link's collision geometry (boxes, cylinders, spheres,
mesh triangles) posed by forward kinematics, the wrist frame's axes and the approach axis."""

from __future__ import annotations

import numpy as np

from .. import _core
from ..model.hands import describe_hand
from .plots import cube_axes, pyplot

MAX_TRIANGLES = 4000  # per link: a mesh with more is drawn with an even subset of its triangles
AXIS_COLOURS = ("tab:red", "tab:green", "tab:blue")  # x, y, z of the wrist frame


def plot_hand(urdf, path, *, title: str | None = None) -> dict:
    """Draws the hand of a URDF in two panels, every independent joint at its lower and at its upper
    limit (continuous joints at -+0.5 rad), with the wrist frame (x red, y green, z blue) and the
    approach axis (black, dashed). Writes `path` (png, pdf, svg); returns describe_hand's dict."""
    hand = _core.Hand.from_urdf(str(urdf))
    info = describe_hand(urdf, hand)
    lim = np.array(hand.joint_limits, dtype=float).reshape(-1, 2)
    lim = np.where(np.isfinite(lim), lim, np.array([-0.5, 0.5]))
    meshes = {name: hand.collision_mesh(name) for name in hand.link_names}
    plt = pyplot()
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    fig = plt.figure(figsize=(11, 5.5))
    posed = [_posed(hand, meshes, lim[:, i]) for i in range(2)]
    every = np.vstack([v for p in posed for v, _ in p.values() if len(v)] + [np.zeros((1, 3))])
    centre = (every.max(axis=0) + every.min(axis=0)) / 2
    span = max(float((every.max(axis=0) - every.min(axis=0)).max()) / 2, 1e-3)
    for col, limit in enumerate(("lower", "upper")):
        ax = fig.add_subplot(1, 2, col + 1, projection="3d")
        for i, (name, (v, t)) in enumerate(posed[col].items()):
            if len(t):
                colour = "0.6" if name == info["wrist"] else f"C{i % 10}"
                ax.add_collection3d(Poly3DCollection(v[t], facecolor=colour, edgecolor="k", linewidths=0.1, alpha=0.5))
        _frame(ax, span * 0.6, info["approach_axis"])
        cube_axes(ax, centre, span)
        width = info["opening_width"]
        text = f", opening {1000 * width[limit] + 0.0:.1f} mm" if width else ""
        joints = ", ".join(f"{n}={v:.3g}" for n, v in zip(hand.joint_names, lim[:, col]))
        ax.set_title(f"{limit} limits{text}\n{joints}", fontsize=8)
    fig.suptitle(title or f"{info['name']}: wrist '{info['wrist']}' (root link), in the wrist frame", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return info


def _posed(hand, meshes: dict, q: np.ndarray) -> dict:
    """link -> (vertices in the wrist frame, triangles) at configuration q."""
    from scipy.spatial.transform import Rotation  # here, not at import: scipy.spatial costs `import graspmix` 0.5 s

    poses = hand.fk(np.array([0, 0, 0, 0, 0, 0, 1.0]), q)
    out = {}
    for pose, name in zip(poses, hand.link_names):
        v, t = (np.asarray(a) for a in meshes[name])
        if len(t) > MAX_TRIANGLES:
            t = t[np.linspace(0, len(t) - 1, MAX_TRIANGLES).astype(int)]
        out[name] = (Rotation.from_quat(pose[3:]).apply(v) + pose[:3] if len(v) else v, t)
    return out


def _frame(ax, length: float, approach: dict) -> None:
    """The wrist frame's axes at the origin, the hand's approach axis and, where it differs, the direction
    from the wrist to the fingertips."""
    for k, colour in enumerate(AXIS_COLOURS):
        d = np.eye(3)[k] * length
        ax.plot([0, d[0]], [0, d[1]], [0, d[2]], color=colour, linewidth=2.5)
    a = np.asarray(approach["axis"]) * length * 1.6
    label = "approach axis [" + ", ".join(f"{v + 0.0:.2g}" for v in approach["axis"]) + "]"
    ax.plot([0, a[0]], [0, a[1]], [0, a[2]], color="k", linestyle="--", linewidth=1, label=label)
    if not approach["agrees"]:
        f = np.asarray(approach["fingers_direction"]) * length * 1.6
        ax.plot([0, f[0]], [0, f[1]], [0, f[2]], color="m", linestyle=":", linewidth=1.5, label="towards the fingers")
    ax.legend(loc="upper left", fontsize=7)
