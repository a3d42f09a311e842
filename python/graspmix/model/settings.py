"""The settings of learning and synthesis as the Python front end takes them. Every value that C++ also
knows is read from the default-constructed C++ settings struct (the single source, docs/design.md);
keyword arguments, the command line and the experiment's protocol refer to these fields in turn.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _core

# The C++ defaults, read once from the default-constructed structs.
_SCENE = _core.SceneSettings()
_SEGMENTATION = _core.SegmentationSettings()
_SURFACE = _core.SurfaceFeatureSettings()
_POSE_MIXTURE = _core.PoseMixture().settings
_KDE = _core.KdeSettings()
_CONTACT = _core.ContactSettings()
_SYNTHESIS = _core.SynthesisSettings()
_AXIS = _core.AxisAlignmentSettings()
_COLLISION = _core.CollisionSettings()
_OCCUPANCY = _core.OccupancySettings()
_APPROACH = _core.ClearApproachSettings()
_QUALITY = _core.ContactQualitySettings()

METHODS = ("gmm", "kde")
METHOD_LABELS = {"gmm": "GMM", "kde": "KDE"}


def check_method(method: str) -> None:
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, got {method!r}")


def checked_viewpoints(viewpoints, n_points: int):
    """None, one viewpoint (3,) for every point, or one per point (n_points, 3), finite; ValueError otherwise."""
    if viewpoints is None:
        return None
    vp = np.asarray(viewpoints, dtype=float)
    if vp.shape != (3,) and vp.shape != (n_points, 3):
        raise ValueError(f"viewpoints: expected shape (3,) or ({n_points}, 3) for {n_points} points, got {vp.shape}")
    if not np.all(np.isfinite(vp)):
        raise ValueError("viewpoints: contains NaN or infinite values")
    return vp


@dataclass
class FeatureSettings:
    """Down-sampling and curvature radius: the demonstration and every query cloud pass through the
    same, or the contact models' feature densities compare unlike things."""

    voxel_size: float = _SCENE.voxel_size  # m, voxel grid before the features (SceneSettings)
    radius: float = _SURFACE.radius  # m, the paper's 1 cm (SurfaceFeatureSettings)

    def surface(self, points: np.ndarray, *, remove_plane: bool, seed: int = 0, viewpoints=None):
        """(SurfaceCloud, SceneResult) of raw points: clean-up (prepare_cloud), then features. A scene's
        known table is cut by segment_scene (graspmix.perception), which synthesis goes through."""
        viewpoints = checked_viewpoints(viewpoints, len(points))
        scene = _core.prepare_cloud(points, voxel_size=self.voxel_size, remove_plane=remove_plane, seed=seed)
        if len(scene.points) == 0:
            raise ValueError("the cloud is empty after clean-up")
        vp = viewpoints
        if vp is not None and vp.ndim == 2:
            vp = vp[scene.sources]  # each kept point carries its source point's camera (voxel centroids too)
        return _core.compute_surface_features(scene.points, radius=self.radius, viewpoints=vp), scene


@dataclass
class LearnSettings:
    """How contact models are learnt from a demonstration (GraspModel.learn's keywords)."""

    n_components: int = _POSE_MIXTURE.n_components  # K of the contact mixtures (GMM)
    kde_position_bandwidth: float = _KDE.position_bandwidth  # m
    kde_orientation_bandwidth: float = _KDE.orientation_bandwidth  # rad
    kde_feature_bandwidth: float = float(_KDE.feature_bandwidth[0])  # curvature units (one value, all features)
    max_distance: float = _CONTACT.max_distance  # m: object points this close to a link are its contacts
    contact_lambda: float = _CONTACT.lambda_  # 1/m^2: contact weight exp(-lambda d^2)
    min_points: int = _CONTACT.min_points  # fewest contacts for a link to get a model
    seed: int = 0
    # added to every covariance diagonal of GMM's contact mixtures (units of the data squared: m^2, rad^2,
    # curvature^2); it bounds how sharp a component can be, e.g. on the exactly flat faces of a rendered box
    gmm_reg_covar: float = _POSE_MIXTURE.reg_covar


@dataclass
class SynthesisOptions:
    """How grasps are synthesised on a cloud (GraspModel.synthesize's keywords)."""

    n_samples: int = _SYNTHESIS.n_samples  # grasps sampled and ranked
    n_optimise: int = _SYNTHESIS.n_optimise  # the best this many are annealed
    optimise: bool = _SYNTHESIS.optimise
    seed: int = 0
    remove_plane: bool = _SCENE.remove_plane  # find and remove the support plane by RANSAC
    approach_concentration: float = _AXIS.concentration  # log E = concentration (cos - 1)
    query_samples: int = _SYNTHESIS.query.n_samples  # N_Q samples per link for the query densities
    query_components: int = _SYNTHESIS.query.n_components  # K_Q of the GMM query densities (KDE: unused)
    kinematic: bool = True
    clear_pregrasp: bool = _SYNTHESIS.clear_pregrasp
    collision_beta: float = _COLLISION.beta  # 1/m: log W = -beta * depth
    contact_tolerance: float = _COLLISION.contact_tolerance  # m: depths up to this are touching
    collision_inside_weight: float = _COLLISION.inside_weight
    # "surface": W on the cloud's points (the paper's); "occupancy": W on an OccupancyMap of what the cameras
    # saw (unseen space is solid) plus the points' depths (CollisionSettings.model).
    collision: str = _COLLISION.model
    occupancy_resolution: float = _OCCUPANCY.resolution  # m: the occupancy map's cell (OccupancySettings)
    # the hard clear-approach expert: the open hand reaches its pre-grasp along its approach axis from stand_off
    # (m) back without touching the scene or the table (ClearApproachSettings)
    clear_approach: bool = True
    stand_off: float = _APPROACH.stand_off
    # m: on its way the open hand keeps this far from every point (they are balls of this radius). The clean-up's
    # points stand for 3 mm voxels: a hand clear of their centres by 1 mm (contact_tolerance) can still be
    # 1-2 mm inside the surface they sample, which Bullet calls a start in collision (more than 2 mm).
    approach_clearance: float = 0.002
    # the soft contact-quality expert: the hand closes from the pre-grasp until each finger meets the object, the
    # contacts scored by the antipodal friction-cone test with this Coulomb coefficient (ContactQualitySettings)
    contact_quality: bool = True
    friction: float = _QUALITY.friction
    # m: every point at most this far above the support plane (given or found), or below it, is dropped as
    # the table (SegmentationSettings.table_clearance; not the RANSAC inlier threshold plane_distance).
    table_clearance: float = _SEGMENTATION.table_clearance
