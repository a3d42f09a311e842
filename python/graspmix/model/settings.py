"""The settings of learning and synthesis, with their defaults: every Python-side default of the grasp
pipeline is written here once; keyword arguments, the command line and the experiment's protocol refer
to these fields instead of restating numbers.

Some of these differ on purpose from the C++ structs' defaults that the bindings expose (the Python front
end was tuned on the bundled demonstration): see DEFAULT_DISAGREEMENTS, checked by the tests.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import _core

METHODS = ("gmm", "kde")
METHOD_LABELS = {"gmm": "GMM", "kde": "KDE"}


def check_method(method: str) -> None:
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, got {method!r}")


@dataclass
class FeatureSettings:
    """Down-sampling and curvature radius: the demonstration and every query cloud pass through the
    same, or the contact models' feature densities compare unlike things."""

    voxel_size: float = 0.003  # m, voxel grid before the features (= C++ SceneSettings::voxel_size)
    radius: float = 0.01  # m, the paper's 1 cm (= C++ SurfaceSettings::radius)
    # m: with a known support plane (synthesize(plane=...)), every point at most this far above it (or
    # below it) is dropped as the table before anything else. A cut in Python, not the RANSAC inlier
    # threshold C++ SceneSettings::plane_distance, which has the same name and value (5 mm). Not stored in
    # model files: a loaded model always has the default.
    plane_distance: float = 0.005

    def surface(self, points: np.ndarray, *, remove_plane: bool, seed: int = 0, viewpoints=None, plane=None):
        """(SurfaceCloud, SceneResult) of raw points: clean-up, then features. With a known support
        plane [a, b, c, d], the points within plane_distance of it or below it are dropped first (the
        table of a scene)."""
        if plane is not None:
            points, viewpoints = self.cut_plane(points, plane, viewpoints)
        scene = _core.prepare_cloud(points, voxel_size=self.voxel_size, remove_plane=remove_plane, seed=seed)
        if len(scene.points) == 0:
            raise ValueError("the cloud is empty after clean-up")
        vp = None
        if viewpoints is not None:
            vp = np.asarray(viewpoints, dtype=float)
            if vp.ndim == 2:
                vp = vp[scene.indices]
        return _core.compute_surface_features(scene.points, radius=self.radius, viewpoints=vp), scene

    def cut_plane(self, points: np.ndarray, plane, viewpoints=None):
        """(points, viewpoints) strictly farther than plane_distance above the plane (its side is the one
        most points are on); per-point viewpoints follow their points."""
        n = np.asarray(plane, dtype=float)
        dist = (points @ n[:3] + n[3]) / np.linalg.norm(n[:3])
        if np.median(dist) < 0:
            dist = -dist
        keep = dist > self.plane_distance
        points = points[keep]
        if viewpoints is not None and np.ndim(viewpoints) == 2:
            viewpoints = np.asarray(viewpoints)[keep]
        if len(points) == 0:
            raise ValueError("no point of the cloud lies above the given support plane")
        return points, viewpoints


@dataclass
class LearnSettings:
    """How contact models are learnt from a demonstration (GraspModel.learn's keywords)."""

    n_components: int = 2  # K of the contact mixtures (GMM)
    kde_position_bandwidth: float = 0.005  # m (= C++ KdeSettings)
    kde_orientation_bandwidth: float = 0.15  # rad (= C++ KdeSettings)
    kde_feature_bandwidth: float = 0.005  # curvature units (C++ KdeSettings: empty, i.e. must be given)
    max_distance: float = 0.01  # m: object points this close to a link are its contacts (= C++ ContactSettings)
    contact_lambda: float = 5000.0  # 1/m^2: contact weight exp(-lambda d^2) (= C++ ContactSettings::lambda)
    min_points: int = 10  # fewest contacts for a link to get a model (= C++ ContactSettings)
    seed: int = 0


@dataclass
class SynthesisOptions:
    """How grasps are synthesised on a cloud (GraspModel.synthesize's keywords)."""

    n_samples: int = 200  # grasps sampled and ranked (= C++ SynthesisSettings)
    n_optimise: int = 10  # the best this many are annealed (= C++ SynthesisSettings)
    optimise: bool = True
    seed: int = 0
    remove_plane: bool = True  # find and remove the support plane by RANSAC (= C++ SceneSettings)
    # log E = concentration (cos - 1): 20 makes a 90-degree deviation cost 20 nats, comparable to the
    # contact terms, so the preference decides between otherwise similar grasps (C++ default: 5).
    approach_concentration: float = 20.0
    query_samples: int = 500  # N_Q samples per link for the query densities (= C++ QuerySettings)
    kinematic: bool = True
    clear_pregrasp: bool = True  # (= C++ SynthesisSettings)
    collision_beta: float = 2000.0  # 1/m: log W = -beta * depth (C++ CollisionSettings: 1000)
    # m: depths up to this are touching, not penetrating: a cloud is a noisy surface (C++: 1e-9)
    contact_tolerance: float = 0.001
    collision_inside_weight: float = 0.0  # (= C++ CollisionSettings)


# The Python defaults above that differ from the C++ defaults of the same quantity: (setting, Python
# value, C++ value, C++ location). Checked against the bindings by the tests, so a change on either side
# is noticed; C++ is to become the single source.
DEFAULT_DISAGREEMENTS = (
    ("SynthesisOptions.collision_beta", 2000.0, 1000.0, "CollisionSettings::beta (collision.hpp)"),
    ("SynthesisOptions.contact_tolerance", 1e-3, 1e-9, "CollisionSettings::contact_tolerance (collision.hpp)"),
    ("SynthesisOptions.approach_concentration", 20.0, 5.0, "AxisAlignmentExpert concentration (experts.hpp)"),
    ("LearnSettings.n_components", 2, 1, "GmmSettings::n_components (gmm.hpp; PoseMixture's binding: 2)"),
)
