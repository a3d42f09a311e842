"""The settings of learning as the Python front end takes them (synthesis: graspmix.model.options). Every value that C++ also
knows is read from the default-constructed C++ settings struct (the single source, docs/design.md);
keyword arguments, the command line and the experiment's protocol refer to these fields in turn.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _core

# The C++ defaults, read once from the default-constructed structs.
_SCENE = _core.CleanupSettings()
_SURFACE = _core.SurfaceFeatureSettings()
_POSE_MIXTURE = _core.PoseMixture().settings
_KDE = _core.KdeSettings()
_CONTACT = _core.ContactSettings()

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
class FeatureScale:
    """The scale of a model's surface features, saved with the model (GraspModel.features): the voxel grid and
    the curvature radius that the demonstration and every query cloud pass through alike, or the contact
    models' feature densities compare unlike things. (The other feature settings: SurfaceFeatureSettings.)"""

    voxel_size: float = _SCENE.voxel_size  # m, voxel grid before the features (CleanupSettings)
    radius: float = _SURFACE.radius  # m, the paper's 1 cm (SurfaceFeatureSettings)

    def surface(self, points: np.ndarray, *, remove_plane: bool, seed: int = 0, viewpoints=None):
        """(SurfaceCloud, CleanupResult) of raw points: clean-up (prepare_cloud), then features. A scene's
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
