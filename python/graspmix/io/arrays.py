"""Numbers from files: (N, d) arrays (.npy, .csv, whitespace text) and point clouds as (N, 3) arrays."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .checks import check_input_file


def load_array(path) -> np.ndarray:
    """A non-empty 2-D float array from .npy, .csv or whitespace-separated text."""
    p = check_input_file(path)
    try:
        if p.suffix == ".npy":
            data = np.load(p, allow_pickle=False)
        else:
            data = np.loadtxt(p, delimiter="," if p.suffix == ".csv" else None, ndmin=2)
    except (ValueError, OSError) as e:
        raise ValueError(f"{path}: cannot read numbers ({e})") from None
    if data.ndim != 2 or data.shape[0] == 0:
        raise ValueError(f"{path}: expected a non-empty 2-D array, got shape {data.shape}")
    return np.asarray(data, dtype=float)


def as_points(cloud) -> np.ndarray:
    """An (N, 3) float array of points, N > 0; ValueError naming the problem otherwise."""
    try:
        pts = np.asarray(cloud, dtype=float)
    except (TypeError, ValueError):
        raise ValueError("cloud must be a file path or an (N, 3) array of points") from None
    if pts.ndim != 2 or pts.shape[1] != 3:
        raise ValueError(f"cloud must be an (N, 3) array, got shape {pts.shape}")
    if len(pts) == 0:
        raise ValueError("cloud is empty")
    return pts


def load_points(cloud):
    """(points (N, 3), name, viewpoints) of a cloud given as a file (PCD/PLY/npy) or as an array. viewpoints:
    the file's per-point camera positions (N, 3) (fields vp_x vp_y vp_z) when it has them, else the position
    of its VIEWPOINT (3,) when it has one, else None (and None for an array)."""
    from .. import _core

    if isinstance(cloud, (str, Path)):
        check_input_file(cloud, "cloud")
        loaded = _core.load_cloud(str(cloud))
        if len(loaded.viewpoints):
            return loaded.points, str(cloud), loaded.viewpoints
        return loaded.points, str(cloud), (loaded.viewpoint[:3] if loaded.has_viewpoint else None)
    return as_points(cloud), "<array>", None
