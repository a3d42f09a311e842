"""Simulation: simulated depth cameras (acquisition), grasp execution in Bullet (C++) with its pybullet
reference, and recording demonstrations in pybullet."""

from . import acquisition
from .acquisition import AcquisitionSettings, TableWorld
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
    "SimObject",
    "SimResult",
    "SimSettings",
    "AcquisitionSettings",
    "TableWorld",
    "acquisition",
    "execute",
    "execute_file",
    "execute_pybullet",
    "grasp_arrays",
    "load_hand",
    "load_object",
    "make_settings",
    "record_demonstration",
    "rest_pose",
    "result_dict",
    "top_grasp",
]
