"""Deprecated module path, kept for one release: recording demonstrations is
``graspmix.sim.demonstration``. Every name of the old module is here."""

from .model import Demonstration
from .sim.acquisition import AcquisitionSettings, Scene, acquire
from .sim.demonstration import record_demonstration

__all__ = ["AcquisitionSettings", "Demonstration", "Scene", "acquire", "record_demonstration"]
