"""A picture of a simulated acquisition's depth images."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .plots import pyplot


def plot_depth_images(acq, path: str | Path) -> None:
    """A picture of the depth images, one panel per camera, cropped to the object (its depth in colour,
    metres; the rest grey; white: no return). acq: a graspmix.sim.acquisition.Acquisition."""
    plt = pyplot()
    n = len(acq.depth_images)
    fig, axes = plt.subplots(1, n, figsize=(3.2 * n, 3.0), squeeze=False)
    masks = acq.object_masks or [np.isfinite(d) for d in acq.depth_images]
    obj = np.concatenate([d[m & np.isfinite(d)] for d, m in zip(acq.depth_images, masks)])
    lo, hi = (np.percentile(obj, 1), np.percentile(obj, 99)) if len(obj) else (0, 1)
    for i, (ax, d, m) in enumerate(zip(axes[0], acq.depth_images, masks)):
        # The object in colour (its own depth range), the rest grey, cropped around the object.
        ax.imshow(np.where(np.isfinite(d) & ~m, 1.0, np.nan), cmap="gray", vmin=0, vmax=1.6)
        im = ax.imshow(np.where(m & np.isfinite(d), d, np.nan), vmin=lo, vmax=hi, cmap="viridis")
        if m.any():
            rows, cols = np.flatnonzero(m.any(1)), np.flatnonzero(m.any(0))
            pad = 10
            ax.set_xlim(max(cols[0] - pad, 0) - 0.5, min(cols[-1] + pad, d.shape[1] - 1) + 0.5)
            ax.set_ylim(min(rows[-1] + pad, d.shape[0] - 1) + 0.5, max(rows[0] - pad, 0) - 0.5)
        ax.set_title(f"camera {i}", fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
    fig.colorbar(im, ax=axes[0].tolist(), shrink=0.8, label="depth (m)")
    fig.suptitle(f"{len(acq.points)} points, noise {'on' if acq.noise else 'off'} (seed {acq.seed})", fontsize=10)
    fig.savefig(path, dpi=110)
    plt.close(fig)
