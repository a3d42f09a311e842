"""Learning from one demonstration and synthesising grasps: the Python face of the C++ synthesiser.

    model = graspmix.learn("data/demos/box_wsg50.json", method="gmm")
    model.save("box_gmm.json")
    grasps = graspmix.GraspModel.load("box_gmm.json").synthesize("data/mug.pcd")
    grasps.save("grasps.json")

File formats (demonstration, learnt model, grasps) are those of the design guide; every file is JSON
with a versioned "format" field.
"""

from __future__ import annotations

import dataclasses
import json
import time
from pathlib import Path
from typing import Callable, Iterable, Sequence

import numpy as np

from .. import _core
from ..io import MODEL_FORMAT, data_path, load_points, read_document, relative_path, require_field, resolve_path
from ..io.checks import (
    MAX_COMPONENTS,
    MAX_SAMPLES,
    check_float,
    check_input_file,
    check_int,
    check_output_path,
    check_path_text,
    check_seed,
)
from .demonstration import Demonstration
from .experts import COLLISION_MODELS
from .grasps import GraspSet
from .scene_synthesis import segment_query, synthesize_targets
from .serialization import config_dict, config_settings, density_from_json, density_to_json
from .settings import FeatureSettings, LearnSettings, SynthesisOptions, check_method

_L, _S = LearnSettings, SynthesisOptions  # the defaults of learn() and synthesize()


def default_model_path(method: str = "gmm") -> Path:
    """The bundled model learnt from the box demonstration with the WSG 50."""
    check_method(method)
    return data_path("models", f"box_wsg50_{method}.json")


class GraspModel:
    """Contact models M_i for every link that touched the object, the configuration model C, and how
    they were learnt; synthesises grasps on new clouds."""

    def __init__(
        self,
        hand: "_core.Hand",
        hand_path: Path,
        synthesizer: "_core.GraspSynthesizer",
        features: FeatureSettings,
        learn_settings: dict,
        demo: str | None = None,
    ):
        self._hand = hand
        self.hand_path = Path(hand_path)
        self.synthesizer = synthesizer
        self.features = features
        self.learn_settings = learn_settings
        self.demo = demo

    # -- properties
    @property
    def method(self) -> str:
        return self.synthesizer.method

    @property
    def hand(self) -> "_core.Hand":
        return self._hand

    @property
    def contact_links(self) -> list[str]:
        return [m.link_name for m in self.synthesizer.contact_models]

    def __repr__(self):
        return f"GraspModel(method={self.method!r}, hand={self.hand_path.name!r}, contact links={self.contact_links})"

    # -- learning
    @classmethod
    def learn(
        cls,
        demo: str | Path | Demonstration,
        method: str = "gmm",
        *,
        n_components: int = _L.n_components,
        kde_position_bandwidth: float = _L.kde_position_bandwidth,
        kde_orientation_bandwidth: float = _L.kde_orientation_bandwidth,
        kde_feature_bandwidth: float = _L.kde_feature_bandwidth,
        max_distance: float = _L.max_distance,
        contact_lambda: float = _L.contact_lambda,
        min_points: int = _L.min_points,
        voxel_size: float = FeatureSettings.voxel_size,
        radius: float = FeatureSettings.radius,
        seed: int = _L.seed,
        config: dict | None = None,
    ) -> "GraspModel":
        """Learns from one demonstration (a demonstration file or object)."""
        check_method(method)
        _check_learn_numbers(
            n_components=n_components,
            kde_position_bandwidth=kde_position_bandwidth,
            kde_orientation_bandwidth=kde_orientation_bandwidth,
            kde_feature_bandwidth=kde_feature_bandwidth,
            max_distance=max_distance,
            contact_lambda=contact_lambda,
            min_points=min_points,
            voxel_size=voxel_size,
            radius=radius,
            seed=seed,
        )
        if config is not None and not isinstance(config, dict):
            raise ValueError(f"config must be a dict of configuration-model settings, got {type(config).__name__}")
        s = LearnSettings(
            n_components,
            kde_position_bandwidth,
            kde_orientation_bandwidth,
            kde_feature_bandwidth,
            max_distance,
            contact_lambda,
            min_points,
            seed,
        )
        d = demo if isinstance(demo, Demonstration) else Demonstration.load(demo)
        hand = _core.Hand.from_urdf(str(check_input_file(d.hand_path, "hand")))
        feats = FeatureSettings(voxel_size=voxel_size, radius=radius)
        surface, _ = feats.surface(d.cloud, remove_plane=False, seed=seed)
        models = _core.learn_contact_models(
            hand,
            d.T_world_wrist,
            d.grasp_joints,
            surface.frames,
            surface.curvatures,
            _density_factory(method, s),
            _contact_settings(s),
        )
        cfg_settings = config_settings(config or {})
        cfg = _core.ConfigModel(
            hand.joints_array(d.pregrasp_joints), hand.joints_array(d.grasp_joints), hand.joint_limits, cfg_settings
        )
        learn_settings = {
            "n_components": n_components,
            "kde_position_bandwidth": kde_position_bandwidth,
            "kde_orientation_bandwidth": kde_orientation_bandwidth,
            "kde_feature_bandwidth": kde_feature_bandwidth,
            "max_distance": max_distance,
            "contact_lambda": contact_lambda,
            "min_points": min_points,
            "seed": seed,
            "config": config_dict(cfg_settings),
        }
        return cls(
            hand,
            d.hand_path,
            _core.GraspSynthesizer(hand, models, cfg),
            feats,
            learn_settings,
            str(d.source) if d.source else None,
        )

    # -- persistence
    def save(self, path: str | Path) -> None:
        path = check_output_path(path, "model file")
        base = path.resolve().parent
        cfg = self.synthesizer.config_model
        data = {
            "format": MODEL_FORMAT,
            "method": self.method,
            "hand": relative_path(self.hand_path, base),
            "demonstration": relative_path(Path(self.demo), base) if self.demo else None,
            "features": {"voxel_size": self.features.voxel_size, "radius": self.features.radius},
            "learn_settings": self.learn_settings,
            "config_model": {
                "pregrasp": cfg.pregrasp.tolist(),
                "grasp": cfg.grasp.tolist(),
                "settings": config_dict(cfg.settings),
            },
            "contact_models": [
                {"link": m.link_name, "n_points": m.n_points, "density": density_to_json(m.density)}
                for m in self.synthesizer.contact_models
            ],
        }
        path.write_text(json.dumps(data) + "\n")

    @classmethod
    def load(cls, path: str | Path) -> "GraspModel":
        path = check_path_text(path, "model")
        data = read_document(path, MODEL_FORMAT)
        check_method(require_field(data, "method", path, str))
        base = path.resolve().parent
        hand_path = resolve_path(require_field(data, "hand", path, str), base)
        hand = _core.Hand.from_urdf(str(check_input_file(hand_path, "hand")))
        f = require_field(data, "features", path, dict)
        feats = FeatureSettings(
            voxel_size=float(f.get("voxel_size", FeatureSettings.voxel_size)),
            radius=float(f.get("radius", FeatureSettings.radius)),
        )
        models = _load_contact_models(data, hand, hand_path, path)
        cfg = _load_config_model(require_field(data, "config_model", path, dict), hand, path)
        demo = data.get("demonstration")
        return cls(
            hand,
            hand_path,
            _core.GraspSynthesizer(hand, models, cfg),
            feats,
            data.get("learn_settings", {}),
            str(resolve_path(demo, base)) if demo else None,
        )

    # -- synthesis
    def synthesize(
        self,
        cloud,
        *,
        n_samples: int = _S.n_samples,
        n_optimise: int = _S.n_optimise,
        optimise: bool = _S.optimise,
        seed: int = _S.seed,
        remove_plane: bool = _S.remove_plane,
        plane=None,
        viewpoints=None,
        approach_axis: Sequence[float] | None = None,
        approach_concentration: float = _S.approach_concentration,
        reachable: Callable | None = None,
        experts: Iterable = (),
        query_samples: int = _S.query_samples,
        kinematic: bool = _S.kinematic,
        clear_pregrasp: bool = _S.clear_pregrasp,
        collision_beta: float = _S.collision_beta,
        contact_tolerance: float = _S.contact_tolerance,
        collision_inside_weight: float = _S.collision_inside_weight,
        collision: str = _S.collision,
        occupancy_resolution: float = _S.occupancy_resolution,
        table_clearance: float = _S.table_clearance,
        target="all",
        annealing: dict | None = None,
    ) -> GraspSet:
        """Grasps on a scene or object cloud: a path (PCD/PLY/npy) or an (N, 3) array of points.

        The cloud is segmented (graspmix.segment_scene) into its support plane and the objects on it;
        grasps are sampled on the target objects and checked for collision against all of them and the
        plane. target: "all" (every object, best grasps first), an object index, "point:x,y,z" (the object
        nearest the point), "largest", "nearest" (to the camera); every grasp records its object.
        viewpoints: the camera position (3,) or one per point (N, 3) (default: the file's); they orient the
        plane and the normals. remove_plane: search for the support plane (a table under the objects:
        segment_scene's rule); plane: give it instead ([a, b, c, d]; points within table_clearance of it
        are dropped); approach_axis: prefer wrists whose approach axis points along it (e.g. (0, 0, -1) for
        top grasps); reachable(wrists, joints) -> bool array: the hard reachability test; experts: more
        experts (graspmix.expert(...) or graspmix._core.Expert objects); annealing: AnnealingSettings fields
        to change. The other settings and their defaults (collision: "surface" or "occupancy"):
        SynthesisOptions."""
        # Every keyword but the cloud, plane, viewpoints, target, experts and annealing is a SynthesisOptions field.
        opts = _synthesis_options(locals())
        t0 = time.perf_counter()
        # Phase 1: the scene (support plane, objects) and the targets.
        points, name, file_viewpoints = load_points(cloud)
        viewpoints = file_viewpoints if viewpoints is None else viewpoints
        scene = segment_query(points, viewpoints, checked_plane(plane), opts, self.features)
        targets = scene.select(target)
        t_segment = time.perf_counter() - t0
        # Phases 2-3: features, query densities, sampling, ranking and annealing per target, ranked together.
        out = synthesize_targets(
            self,
            scene,
            targets,
            opts,
            self._synthesis_settings(opts, annealing),
            approach_axis=approach_axis,
            reachable=reachable,
            experts=experts,
            cloud=(points, viewpoints),
        )
        timing = dict(out.timing)
        timing["segmentation"] = t_segment
        timing["total"] = time.perf_counter() - t0
        # Features: everything before the synthesiser's own stages (the segmentation, i.e. the clean-up, included).
        timing["features"] = timing["total"] - sum(out.timing.values())
        return GraspSet(
            out.grasps,
            self.hand_path,
            self.method,
            name,
            timing,
            out.surface,
            scene.plane,
            out.evaluations,
            out.rejected,
            scene=scene,
            targets=targets,
        )

    def _synthesis_settings(self, opts: SynthesisOptions, annealing: dict | None) -> "_core.SynthesisSettings":
        if annealing is not None and not isinstance(annealing, dict):
            raise ValueError(f"annealing must be a dict of AnnealingSettings fields, got {type(annealing).__name__}")
        s = _core.SynthesisSettings()
        s.n_samples, s.n_optimise, s.optimise, s.seed = opts.n_samples, opts.n_optimise, opts.optimise, opts.seed
        s.clear_pregrasp = opts.clear_pregrasp
        q = s.query
        q.n_samples = opts.query_samples
        q.kde_bandwidths = (
            self.learn_settings.get("kde_position_bandwidth", _L.kde_position_bandwidth),
            self.learn_settings.get("kde_orientation_bandwidth", _L.kde_orientation_bandwidth),
        )
        s.query = q
        a = s.annealing
        for k, v in (annealing or {}).items():
            if not hasattr(a, k):
                raise ValueError(f"unknown annealing setting {k!r}")
            setattr(a, k, v)
        s.annealing = a
        return s


def checked_plane(plane):
    """None, or a plane [a, b, c, d] of 4 finite numbers with a non-zero normal (ValueError otherwise)."""
    if plane is None:
        return None
    plane = np.asarray(plane, dtype=float)
    if plane.shape != (4,) or not np.all(np.isfinite(plane)) or not np.linalg.norm(plane[:3]) > 0:
        raise ValueError("plane must be 4 finite numbers [a, b, c, d] with a non-zero normal")
    return plane


def _check_learn_numbers(**v) -> None:
    """learn()'s numbers, bounded before they reach a C++ cast (ValueError naming the keyword)."""
    check_int(v["n_components"], "n_components", 1, MAX_COMPONENTS)
    check_int(v["min_points"], "min_points", 1, 2**31 - 1)
    check_seed(v["seed"])
    for name in (
        "kde_position_bandwidth",
        "kde_orientation_bandwidth",
        "kde_feature_bandwidth",
        "max_distance",
        "contact_lambda",
        "radius",
    ):
        check_float(v[name], name, gt=0.0)
    check_float(v["voxel_size"], "voxel_size", 0.0)


def _synthesis_options(args: dict) -> SynthesisOptions:
    """synthesize()'s keywords as SynthesisOptions, its numbers bounded before they reach a C++ cast
    (ValueError naming the keyword)."""
    v = {f.name: args[f.name] for f in dataclasses.fields(SynthesisOptions)}
    check_int(v["n_samples"], "n_samples", 1, MAX_SAMPLES)
    check_int(v["n_optimise"], "n_optimise", 0, MAX_SAMPLES)
    check_int(v["query_samples"], "query_samples", 1, MAX_SAMPLES)
    check_seed(v["seed"])
    for name in ("approach_concentration", "collision_beta", "contact_tolerance", "collision_inside_weight"):
        check_float(v[name], name, 0.0)
    check_float(v["occupancy_resolution"], "occupancy_resolution", gt=0.0)
    if v["collision"] not in COLLISION_MODELS:
        raise ValueError(f"collision must be one of {', '.join(COLLISION_MODELS)}, got {v['collision']!r}")
    return SynthesisOptions(**v)


def _density_factory(method: str, s: LearnSettings) -> Callable:
    if method == "gmm":
        return lambda: _core.PoseMixture(n_components=s.n_components, seed=s.seed)
    return lambda: _core.PoseKDE(
        position_bandwidth=s.kde_position_bandwidth,
        orientation_bandwidth=s.kde_orientation_bandwidth,
        feature_bandwidth=s.kde_feature_bandwidth,
    )


def _contact_settings(s: LearnSettings) -> "_core.ContactSettings":
    contact = _core.ContactSettings()
    contact.max_distance, contact.lambda_, contact.min_points = s.max_distance, s.contact_lambda, s.min_points
    return contact


def _load_contact_models(data: dict, hand, hand_path: Path, path: Path) -> list:
    models = []
    for i, entry in enumerate(require_field(data, "contact_models", path, list)):
        where = f"{path}: contact model {i}"
        link_name = entry.get("link")
        if link_name not in hand.link_names:
            raise ValueError(
                f"{where}: link {link_name!r} is not a link of hand '{hand_path.name}' "
                f"(links: {', '.join(hand.link_names)}); was the model learnt for another hand?"
            )
        density = density_from_json(entry.get("density", {}), where)
        if density.kind != data["method"]:
            raise ValueError(f"{where}: a {density.kind} density in a {data['method']} model")
        models.append(_core.ContactModel(hand.link_index(link_name), link_name, density, int(entry.get("n_points", 0))))
    return models


def _load_config_model(c: dict, hand, path: Path) -> "_core.ConfigModel":
    try:
        return _core.ConfigModel(
            np.asarray(c["pregrasp"], float),
            np.asarray(c["grasp"], float),
            hand.joint_limits,
            config_settings(c.get("settings", {})),
        )
    except KeyError as e:
        raise ValueError(f"{path}: config_model misses {e}") from None
    except ValueError as e:
        raise ValueError(f"{path}: config_model: {e} (was the model learnt for another hand?)") from None


def learn(demo, method: str = "gmm", **kwargs) -> GraspModel:
    """Learns a GraspModel from one demonstration file (see GraspModel.learn for the settings)."""
    return GraspModel.learn(demo, method, **kwargs)
