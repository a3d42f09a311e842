"""graspmix: generative grasp synthesis from one demonstration with parametric mixtures.

The C++ core lives in ``graspmix._core``; this package re-exports it and adds the Python-side tools
(command line, plots, experiment protocol).
"""
from importlib import metadata as _metadata

import numpy as _np

from . import _core
from ._core import (
    GaussianMixture,
    PoseDensity,
    PoseKDE,
    PoseMixture,
    build_info,
)

try:
    __version__ = _metadata.version("graspmix")
except _metadata.PackageNotFoundError:  # running from a source tree
    __version__ = build_info()["graspmix"]


def _rowwise(fn, name, *arrays):
    """Calls a batched (N, d) core function; 1-D inputs are taken as one row and the result is 1-D."""
    single = all(_np.ndim(a) == 1 for a in arrays)
    out = fn(*[_np.atleast_2d(_np.asarray(a, dtype=float)) if _np.ndim(a) == 1 else a for a in arrays])
    return out[0] if single else out


def quat_log(q):
    """eq:log_map on quaternions [x, y, z, w], (N, 4) or (4,), canonicalised to w >= 0 first."""
    return _rowwise(_core.quat_log, "quat_log", q)


def quat_exp(w):
    """eq:exp_map on rotation vectors (N, 3) or (3,), half-angle convention."""
    return _rowwise(_core.quat_exp, "quat_exp", w)


def pose_multiply(a, b):
    """a o b on poses [x, y, z, qx, qy, qz, qw], (N, 7) or (7,); a single pose is broadcast."""
    return _rowwise(_core.pose_multiply, "pose_multiply", a, b)


def pose_inverse(a):
    """The inverse of poses (N, 7) or (7,)."""
    return _rowwise(_core.pose_inverse, "pose_inverse", a)


__all__ = [
    "GaussianMixture",
    "PoseDensity",
    "PoseKDE",
    "PoseMixture",
    "build_info",
    "pose_inverse",
    "pose_multiply",
    "quat_exp",
    "quat_log",
]

# ---- hands and the collision expert (issue 4) ----
from ._core import CollisionBatchResult, CollisionExpert, CollisionResult, Hand, load_mesh  # noqa: E402

__all__ += ["CollisionBatchResult", "CollisionExpert", "CollisionResult", "Hand", "load_mesh"]

# ---- simulation: acquisition and grasp execution (issue 6) ----
from ._core import SimObject, SimResult, SimSettings  # noqa: E402
from . import acquisition, sim  # noqa: E402

__all__ += ["SimObject", "SimResult", "SimSettings", "acquisition", "sim"]
