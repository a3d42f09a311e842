"""The grasp model layer: demonstrations, learning contact and configuration models, GraspModel and its
synthesis, Grasp and GraspSet (grasps.json), experts, and the settings with their defaults."""

from ..io import DEMO_FORMAT, GRASPS_FORMAT, MODEL_FORMAT, PACKAGE_PREFIX, data_path
from .demonstration import Demonstration
from .experts import expert
from .grasp_frames import GraspFrameSettings
from .grasp_model import GraspModel, default_model_path, learn
from .grasps import (
    EXECUTION_KEYS,
    STAGE_LABELS,
    STAGES,
    Grasp,
    GraspSet,
    NoFeasibleGraspWarning,
    grasp_by_rank,
    load_grasps,
)
from .hands import describe_hand, hand_urdf_from_robot
from .options import SynthesisOptions
from .settings import (
    METHOD_LABELS,
    METHODS,
    FeatureScale,
    LearnSettings,
    check_method,
)

__all__ = [
    "DEMO_FORMAT",
    "GRASPS_FORMAT",
    "MODEL_FORMAT",
    "PACKAGE_PREFIX",
    "METHODS",
    "METHOD_LABELS",
    "EXECUTION_KEYS",
    "STAGES",
    "STAGE_LABELS",
    "data_path",
    "default_model_path",
    "Demonstration",
    "FeatureScale",
    "LearnSettings",
    "SynthesisOptions",
    "Grasp",
    "GraspSet",
    "NoFeasibleGraspWarning",
    "GraspFrameSettings",
    "GraspModel",
    "learn",
    "describe_hand",
    "hand_urdf_from_robot",
    "expert",
    "check_method",
    "load_grasps",
    "grasp_by_rank",
]
