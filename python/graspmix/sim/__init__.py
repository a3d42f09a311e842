"""Simulation: simulated depth cameras (acquisition), grasp execution in Bullet (C++) with its pybullet
reference, and recording demonstrations in pybullet.

Also the module path ``graspmix.sim`` of earlier versions: every name it had is here (the camera names
are in ``graspmix.sim.acquisition``).
"""

from ..io import GRASPS_FORMAT, default_hand_path, resolve_object, test_objects
from ..model.grasps import grasp_by_rank, load_grasps
from . import acquisition
from .acquisition import AcquisitionSettings, Scene
from .demonstration import record_demonstration
from .execution import (
    SimObject,
    SimResult,
    SimSettings,
    execute,
    execute_file,
    grasp_arrays,
    load_hand,
    load_object,
    make_settings,
    rest_pose,
    result_dict,
    top_grasp,
)
from .pybullet_reference import execute_pybullet

__all__ = [
    "GRASPS_FORMAT",
    "SimObject",
    "SimResult",
    "SimSettings",
    "AcquisitionSettings",
    "Scene",
    "acquisition",
    "default_hand_path",
    "execute",
    "execute_file",
    "execute_pybullet",
    "grasp_arrays",
    "grasp_by_rank",
    "load_grasps",
    "load_hand",
    "load_object",
    "make_settings",
    "record_demonstration",
    "resolve_object",
    "rest_pose",
    "result_dict",
    "test_objects",
    "top_grasp",
]
