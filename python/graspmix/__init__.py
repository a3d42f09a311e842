"""graspmix: generative grasp synthesis from one demonstration with parametric mixtures.

The C++ core lives in ``graspmix._core``; this package re-exports it and adds the Python-side tools in
layers, each importing only from the ones before it:

    io/          file formats and paths (the bundled data, JSON documents, object lists)
    perception/  the scene model: support plane, objects, targets, camera-frame clouds
    model/       demonstrations, learning, GraspModel and synthesis, Grasp/GraspSet, experts, settings
    sim/         simulated cameras, grasp execution in Bullet, recording demonstrations
    viz/         pictures
    experiment/  the paper's experiment: protocol, runs, statistics, report, runtime benchmark
    cli/         graspmix_cli
"""

import importlib as _importlib
import os as _os

# OpenMP threads that spin while they wait for work stall badly when other jobs share the cores (a batch of
# 200 grasps took 50-300 ms instead of 3-10 ms on a loaded 2-core machine): the core waits passively unless
# the user chose a policy. libgomp reads it when it loads, with _core below.
if "OMP_WAIT_POLICY" not in _os.environ and "GOMP_SPINCOUNT" not in _os.environ:
    _os.environ["OMP_WAIT_POLICY"] = "PASSIVE"
# numpy's OpenBLAS starts a thread per core when numpy loads, and they spin after any product: on 2 cores they took
# CPU from the C++ core's OpenMP threads (graspmix_cli synthesize on packed4.pcd 308 -> 299 ms, `import numpy`
# 104 -> 91 ms with one BLAS thread, medians of 6 and 8 alternating runs). graspmix's own products are small, so
# BLAS keeps to the calling thread unless the user chose otherwise (OPENBLAS_NUM_THREADS, GOTO_NUM_THREADS), and
# only if numpy was not loaded before graspmix.
if "OPENBLAS_NUM_THREADS" not in _os.environ and "GOTO_NUM_THREADS" not in _os.environ:
    _os.environ["OPENBLAS_NUM_THREADS"] = "1"

import numpy as _np  # noqa: E402

from . import _core, io, model, perception  # noqa: E402
from ._core import (
    # the parts of SynthesisOptions
    AnnealingSettings,
    # contact models, configuration model, experts, synthesis
    AxisAlignmentExpert,
    AxisAlignmentSettings,
    CleanupResult,
    ClearApproachSettings,
    # object representation
    CloudData,
    # hands and the collision expert
    CollisionBatchResult,
    CollisionExpert,
    CollisionFreeExpert,
    CollisionResult,
    CollisionSettings,
    # the unseen side of an object
    Completion,
    CompletionKind,
    CompletionSettings,
    ConfigModel,
    ConfigModelSettings,
    ContactModel,
    ContactQualityExpert,
    ContactQualitySettings,
    ContactSettings,
    Expert,
    FunctionExpert,
    # densities (foundation)
    GaussianMixture,
    GraspDepthExpert,
    GraspDepthSettings,
    GraspSynthesizer,
    Hand,
    KinematicFeasibilityExpert,
    KinematicFeasibilitySettings,
    OccupancySettings,
    # cameras and what they saw
    PinholeCamera,
    PinholeFit,
    PoseDensity,
    PoseKDE,
    PoseMixture,
    QuerySettings,
    SamplingSettings,
    SegmentationSettings,
    # simulation
    SimObject,
    SimResult,
    SimSettings,
    SpaceState,
    SurfaceCloud,
    SynthesizerSettings,
    VisibilityModel,
    VisibilitySettings,
    build_info,
    complete_object,
    compute_surface_features,
    contact_data,
    learn_contact_models,
    load_cloud,
    load_mesh,
    prepare_cloud,
    save_cloud,
)
from .io import data_path
from .model import (
    Demonstration,
    FeatureScale,
    Grasp,
    GraspModel,
    GraspSet,
    NoFeasibleGraspWarning,
    SynthesisOptions,
    default_model_path,
    describe_hand,
    expert,
    learn,
)
from .perception import CameraView, Scene, depth_view, organized_view, segment_scene, segment_view

# Loaded on first use (PEP 562), so that `import graspmix` and a command that needs neither pictures nor the
# simulator do not pay for matplotlib, pybullet and their modules: the layers above the model, the two
# plotting functions re-exported here and the version (importlib.metadata).
_LAZY_MODULES = {"sim", "viz", "experiment", "clutter", "cli"}
_LAZY_NAMES = {"plot_grasps": "viz", "plot_grasps_html": "viz"}


def __getattr__(name: str):
    if name in _LAZY_MODULES:
        return _importlib.import_module(f"{__name__}.{name}")
    if name in _LAZY_NAMES:
        return getattr(_importlib.import_module(f"{__name__}.{_LAZY_NAMES[name]}"), name)
    if name == "__version__":
        return io.package_version()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | _LAZY_MODULES | set(_LAZY_NAMES) | {"__version__"})


def _rowwise(fn, *arrays):
    """Calls a batched (N, d) core function; 1-D inputs are taken as one row and the result is 1-D."""
    single = all(_np.ndim(a) == 1 for a in arrays)
    out = fn(*[_np.atleast_2d(_np.asarray(a, dtype=float)) if _np.ndim(a) == 1 else a for a in arrays])
    return out[0] if single else out


def quat_log(q):
    """eq:log_map on quaternions [x, y, z, w], (N, 4) or (4,), canonicalised to w >= 0 first."""
    return _rowwise(_core.quat_log, q)


def quat_exp(w):
    """eq:exp_map on rotation vectors (N, 3) or (3,), half-angle convention."""
    return _rowwise(_core.quat_exp, w)


def pose_multiply(a, b):
    """a o b on poses [x, y, z, qx, qy, qz, qw], (N, 7) or (7,); a single pose is broadcast."""
    return _rowwise(_core.pose_multiply, a, b)


def pose_inverse(a):
    """The inverse of poses (N, 7) or (7,)."""
    return _rowwise(_core.pose_inverse, a)


# `from graspmix import *` gives the eager names and the pictures (graspmix.viz loads matplotlib only when it
# draws), never the simulator: sim, experiment and clutter load pybullet.
__all__ = sorted(
    {name for name in globals() if not name.startswith("_") and name not in ("annotations",)}
    | {"viz"}
    | set(_LAZY_NAMES)
)
