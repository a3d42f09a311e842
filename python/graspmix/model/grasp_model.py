"""Learning from one demonstration and synthesising grasps: the Python face of the C++ synthesiser.

    model = graspmix.learn("data/demos/box_wsg50.json", method="gmm")
    model.save("box_gmm.json")
    grasps = graspmix.GraspModel.load("box_gmm.json").synthesize("data/mug.pcd")
    grasps.save("grasps.json")

File formats (demonstration, learnt model, grasps) are those of the design guide; every file is JSON
with a versioned "format" field.
"""
from __future__ import annotations

import json
import math
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Iterable, Sequence

import numpy as np

from . import _core

MODEL_FORMAT = "graspmix.model/1"
DEMO_FORMAT = "graspmix.demo/1"
GRASPS_FORMAT = "graspmix.grasps/1"
METHODS = ("gmm", "kde")


def data_path(*parts: str) -> Path:
    """A file of the bundled data (hands, demonstrations, default models, example clouds)."""
    here = Path(__file__).resolve().parent
    for root in (here / "data", here.parent.parent / "data"):  # installed package, then source tree
        if root.is_dir():
            return root.joinpath(*parts)
    raise FileNotFoundError("graspmix's bundled data folder is missing from this installation")


def default_model_path(method: str = "gmm") -> Path:
    _check_method(method)
    return data_path("models", f"box_wsg50_{method}.json")


def _check_method(method: str) -> None:
    if method not in METHODS:
        raise ValueError(f"method must be one of {', '.join(METHODS)}, got {method!r}")


def _read_json(path: Path, what: str) -> dict:
    if not path.is_file():
        raise ValueError(f"{path}: no such {what} file")
    try:
        data = json.loads(path.read_text())
    except (json.JSONDecodeError, UnicodeDecodeError) as e:
        raise ValueError(f"{path}: not valid JSON ({e})") from None
    if not isinstance(data, dict):
        raise ValueError(f"{path}: expected a JSON object at the top level")
    return data


def _field(data: dict, key: str, path: Path, kind=None):
    if key not in data:
        raise ValueError(f"{path}: missing field '{key}'")
    value = data[key]
    if kind is not None and not isinstance(value, kind):
        raise ValueError(f"{path}: field '{key}' has the wrong type ({type(value).__name__})")
    return value


PACKAGE_PREFIX = "package://graspmix/"


def _resolve(path_text: str, base: Path) -> Path:
    """A path from a file: package://graspmix/... (the bundled data), absolute, or relative to the file's
    folder (then to the bundled data)."""
    if path_text.startswith(PACKAGE_PREFIX):
        return data_path(path_text[len(PACKAGE_PREFIX):])
    p = Path(path_text)
    if p.is_absolute():
        return p
    for candidate in (base / p, data_path(path_text)):
        if candidate.exists():
            return candidate.resolve()
    return (base / p).resolve()


def _relative(target: Path, base: Path) -> str:
    """How a file refers to target: package://graspmix/... for the bundled data, else relative to base when
    it can be (keeps files movable with their data)."""
    import os

    root = data_path().resolve()
    try:
        return PACKAGE_PREFIX + target.resolve().relative_to(root).as_posix()
    except ValueError:
        pass
    try:
        return os.path.relpath(target.resolve(), base.resolve())
    except ValueError:
        return str(target.resolve())


# ---- demonstrations ----------------------------------------------------------------------------

@dataclass
class Demonstration:
    """One demonstrated grasp: a hand, the object's cloud, the wrist pose and the pre-grasp/grasp joints."""

    hand_path: Path
    cloud: np.ndarray
    T_world_wrist: np.ndarray
    pregrasp_joints: dict
    grasp_joints: dict
    cloud_path: Path | None = None
    source: Path | None = None

    @classmethod
    def load(cls, path: str | Path) -> "Demonstration":
        path = Path(path)
        data = _read_json(path, "demonstration")
        fmt = data.get("format", DEMO_FORMAT)
        if fmt != DEMO_FORMAT:
            raise ValueError(f"{path}: format is {fmt!r}, expected {DEMO_FORMAT!r}")
        base = path.resolve().parent
        hand = _resolve(_field(data, "hand", path, str), base)
        cloud_field = _field(data, "cloud", path)
        if isinstance(cloud_field, str):
            cloud_path = _resolve(cloud_field, base)
            cloud = _core.load_cloud(str(cloud_path)).points
        else:
            cloud_path = None
            cloud = np.asarray(cloud_field, dtype=float)
            if cloud.ndim != 2 or cloud.shape[1] != 3 or len(cloud) == 0:
                raise ValueError(f"{path}: inline 'cloud' must be a non-empty list of [x, y, z]")
        wrist = np.asarray(_field(data, "T_world_wrist", path, list), dtype=float)
        if wrist.shape != (7,) or not np.all(np.isfinite(wrist)):
            raise ValueError(f"{path}: 'T_world_wrist' must be 7 finite numbers [x, y, z, qx, qy, qz, qw]")
        pre = _field(data, "pregrasp_joints", path, dict)
        grasp = _field(data, "grasp_joints", path, dict)
        return cls(hand, cloud, wrist, pre, grasp, cloud_path, path.resolve())

    def save(self, path: str | Path, inline_cloud: bool = False) -> None:
        path = Path(path)
        base = path.resolve().parent
        data = {"format": DEMO_FORMAT, "hand": _relative(self.hand_path, base)}
        if inline_cloud or self.cloud_path is None:
            data["cloud"] = np.round(self.cloud, 6).tolist()
        else:
            data["cloud"] = _relative(self.cloud_path, base)
        data["T_world_wrist"] = [float(x) for x in self.T_world_wrist]
        data["pregrasp_joints"] = {k: float(v) for k, v in self.pregrasp_joints.items()}
        data["grasp_joints"] = {k: float(v) for k, v in self.grasp_joints.items()}
        path.write_text(json.dumps(data, indent=1) + "\n")


# ---- object processing shared by learning and synthesis -----------------------------------------

@dataclass
class FeatureSettings:
    """Down-sampling and curvature radius: the demonstration and every query cloud pass through the
    same, or the contact models' feature densities compare unlike things."""

    voxel_size: float = 0.003  # m
    radius: float = 0.01  # m, the paper's 1 cm
    plane_distance: float = 0.005  # m: points this close to a known support plane (or below it) are the table

    def surface(self, points: np.ndarray, *, remove_plane: bool, seed: int = 0, viewpoints=None, plane=None):
        """(SurfaceCloud, SceneResult) of raw points: clean-up, then features. With a known support
        plane [a, b, c, d], the points on it or below it are dropped first (the table of a scene)."""
        if plane is not None:
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
        scene = _core.prepare_cloud(points, voxel_size=self.voxel_size, remove_plane=remove_plane, seed=seed)
        if len(scene.points) == 0:
            raise ValueError("the cloud is empty after clean-up")
        vp = None
        if viewpoints is not None:
            vp = np.asarray(viewpoints, dtype=float)
            if vp.ndim == 2:
                vp = vp[scene.indices]
        return _core.compute_surface_features(scene.points, radius=self.radius, viewpoints=vp), scene


# ---- densities to and from JSON ----------------------------------------------------------------

def _density_to_json(d) -> dict:
    if d.kind == "gmm":
        j = d.joint
        return {"kind": "gmm", "reference": d.reference.tolist(), "weights": j.weights_.tolist(),
                "means": j.means_.tolist(), "covariances": j.covariances_.tolist()}
    return {"kind": "kde", "position_bandwidth": d.position_bandwidth,
            "orientation_bandwidth": d.orientation_bandwidth, "feature_bandwidth": d.feature_bandwidth.tolist(),
            "poses": np.hstack([d.positions, d.orientations]).tolist(), "features": d.features.tolist(),
            "weights": d.weights.tolist()}


def _density_from_json(data: dict, where: str):
    try:
        kind = data["kind"]
        if kind == "gmm":
            joint = _core.GaussianMixture.from_parameters(np.asarray(data["weights"], float), np.asarray(data["means"], float),
                                                          np.asarray(data["covariances"], float))
            return _core.PoseMixture.from_parameters(np.asarray(data["reference"], float), joint)
        if kind == "kde":
            kde = _core.PoseKDE(position_bandwidth=float(data["position_bandwidth"]),
                                orientation_bandwidth=float(data["orientation_bandwidth"]),
                                feature_bandwidth=np.asarray(data["feature_bandwidth"], float))
            poses = np.asarray(data["poses"], float)
            feats = np.asarray(data["features"], float).reshape(len(poses), -1)
            return kde.fit(poses, feats, np.asarray(data["weights"], float))
        raise ValueError(f"unknown density kind {kind!r}")
    except KeyError as e:
        raise ValueError(f"{where}: density misses field {e}") from None
    except (TypeError, ValueError) as e:
        raise ValueError(f"{where}: {e}") from None


# ---- grasps ------------------------------------------------------------------------------------

@dataclass
class GraspSet:
    """Synthesised grasps, best first, as written to grasps.json."""

    grasps: list[dict]
    hand_path: Path
    method: str
    cloud: str
    timing: dict
    surface: object = None  # the query object's SurfaceCloud
    plane: np.ndarray | None = None
    evaluations: int = 0
    rejected: int = 0

    def __len__(self):
        return len(self.grasps)

    def __getitem__(self, i):
        return self.grasps[i]

    def best(self) -> dict:
        return self.grasps[0]

    def to_json(self, base: Path | None = None) -> dict:
        """The grasps.json content; paths are written relative to `base` (the file's folder) when given."""
        hand, cloud = str(self.hand_path), self.cloud
        if base is not None:
            hand = _relative(self.hand_path, base)
            if Path(cloud).exists():
                cloud = _relative(Path(cloud), base)
        return {"format": GRASPS_FORMAT, "hand": hand, "method": self.method, "cloud": cloud,
                "timing_s": self.timing, "grasps": self.grasps}

    def save(self, path: str | Path) -> None:
        def clean(x):
            if isinstance(x, float) and not math.isfinite(x):
                return None if math.isnan(x) else ("-inf" if x < 0 else "inf")
            if isinstance(x, dict):
                return {k: clean(v) for k, v in x.items()}
            if isinstance(x, list):
                return [clean(v) for v in x]
            return x

        # Non-finite log values (a grasp a hard expert rejected) are written as the strings "-inf"/"inf".
        path = Path(path)
        path.write_text(json.dumps(clean(self.to_json(path.resolve().parent)), indent=1) + "\n")


# ---- the model ---------------------------------------------------------------------------------

class GraspModel:
    """Contact models M_i for every link that touched the object, the configuration model C, and how
    they were learnt; synthesises grasps on new clouds."""

    def __init__(self, hand: "_core.Hand", hand_path: Path, synthesizer: "_core.GraspSynthesizer",
                 features: FeatureSettings, learn_settings: dict, demo: str | None = None):
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
        return (f"GraspModel(method={self.method!r}, hand={self.hand_path.name!r}, "
                f"contact links={self.contact_links})")

    # -- learning
    @classmethod
    def learn(cls, demo: str | Path | Demonstration, method: str = "gmm", *, n_components: int = 2,
              kde_position_bandwidth: float = 0.005, kde_orientation_bandwidth: float = 0.15,
              kde_feature_bandwidth: float = 0.005, max_distance: float = 0.01, contact_lambda: float = 5000.0,
              min_points: int = 10, voxel_size: float = 0.003, radius: float = 0.01, seed: int = 0,
              config: dict | None = None) -> "GraspModel":
        """Learns from one demonstration (a demonstration file or object)."""
        _check_method(method)
        d = demo if isinstance(demo, Demonstration) else Demonstration.load(demo)
        hand = _core.Hand.from_urdf(str(d.hand_path))
        feats = FeatureSettings(voxel_size=voxel_size, radius=radius)
        surface, _ = feats.surface(d.cloud, remove_plane=False, seed=seed)
        contact = _core.ContactSettings()
        contact.max_distance, contact.lambda_, contact.min_points = max_distance, contact_lambda, min_points
        if method == "gmm":
            def make():
                return _core.PoseMixture(n_components=n_components, seed=seed)
        else:
            def make():
                return _core.PoseKDE(position_bandwidth=kde_position_bandwidth,
                                     orientation_bandwidth=kde_orientation_bandwidth,
                                     feature_bandwidth=kde_feature_bandwidth)
        models = _core.learn_contact_models(hand, d.T_world_wrist, d.grasp_joints, surface.frames, surface.curvatures,
                                            make, contact)
        cfg_settings = _config_settings(config or {})
        cfg = _core.ConfigModel(hand.joints_array(d.pregrasp_joints), hand.joints_array(d.grasp_joints),
                                hand.joint_limits, cfg_settings)
        learn_settings = {"n_components": n_components, "kde_position_bandwidth": kde_position_bandwidth,
                          "kde_orientation_bandwidth": kde_orientation_bandwidth,
                          "kde_feature_bandwidth": kde_feature_bandwidth, "max_distance": max_distance,
                          "contact_lambda": contact_lambda, "min_points": min_points, "seed": seed,
                          "config": _config_dict(cfg_settings)}
        return cls(hand, d.hand_path, _core.GraspSynthesizer(hand, models, cfg), feats, learn_settings,
                   str(d.source) if d.source else None)

    # -- persistence
    def save(self, path: str | Path) -> None:
        path = Path(path)
        base = path.resolve().parent
        cfg = self.synthesizer.config_model
        data = {
            "format": MODEL_FORMAT,
            "method": self.method,
            "hand": _relative(self.hand_path, base),
            "demonstration": _relative(Path(self.demo), base) if self.demo else None,
            "features": {"voxel_size": self.features.voxel_size, "radius": self.features.radius},
            "learn_settings": self.learn_settings,
            "config_model": {"pregrasp": cfg.pregrasp.tolist(), "grasp": cfg.grasp.tolist(),
                             "settings": _config_dict(cfg.settings)},
            "contact_models": [{"link": m.link_name, "n_points": m.n_points, "density": _density_to_json(m.density)}
                               for m in self.synthesizer.contact_models],
        }
        path.write_text(json.dumps(data) + "\n")

    @classmethod
    def load(cls, path: str | Path) -> "GraspModel":
        path = Path(path)
        data = _read_json(path, "model")
        if data.get("format") != MODEL_FORMAT:
            raise ValueError(f"{path}: format is {data.get('format')!r}, expected {MODEL_FORMAT!r}")
        _check_method(_field(data, "method", path, str))
        base = path.resolve().parent
        hand_path = _resolve(_field(data, "hand", path, str), base)
        hand = _core.Hand.from_urdf(str(hand_path))
        f = _field(data, "features", path, dict)
        feats = FeatureSettings(voxel_size=float(f.get("voxel_size", 0.003)), radius=float(f.get("radius", 0.01)))
        models = []
        for i, entry in enumerate(_field(data, "contact_models", path, list)):
            where = f"{path}: contact model {i}"
            link_name = entry.get("link")
            if link_name not in hand.link_names:
                raise ValueError(f"{where}: link {link_name!r} is not a link of hand '{hand_path.name}' "
                                 f"(links: {', '.join(hand.link_names)}); was the model learnt for another hand?")
            density = _density_from_json(entry.get("density", {}), where)
            if density.kind != data["method"]:
                raise ValueError(f"{where}: a {density.kind} density in a {data['method']} model")
            models.append(_core.ContactModel(hand.link_index(link_name), link_name, density, int(entry.get("n_points", 0))))
        c = _field(data, "config_model", path, dict)
        try:
            cfg = _core.ConfigModel(np.asarray(c["pregrasp"], float), np.asarray(c["grasp"], float), hand.joint_limits,
                                    _config_settings(c.get("settings", {})))
        except KeyError as e:
            raise ValueError(f"{path}: config_model misses {e}") from None
        except ValueError as e:
            raise ValueError(f"{path}: config_model: {e} (was the model learnt for another hand?)") from None
        demo = data.get("demonstration")
        return cls(hand, hand_path, _core.GraspSynthesizer(hand, models, cfg), feats, data.get("learn_settings", {}),
                   str(_resolve(demo, base)) if demo else None)

    # -- synthesis
    def synthesize(self, cloud, *, n_samples: int = 200, n_optimise: int = 10, optimise: bool = True,
                   seed: int = 0, remove_plane: bool = True, plane=None, viewpoints=None,
                   approach_axis: Sequence[float] | None = None, approach_concentration: float = 20.0,
                   reachable: Callable | None = None,
                   experts: Iterable = (), query_samples: int = 500, kinematic: bool = True,
                   clear_pregrasp: bool = True, collision_beta: float = 2000.0, contact_tolerance: float = 0.001,
                   collision_inside_weight: float = 0.0, annealing: dict | None = None) -> GraspSet:
        """Grasps on a novel object's cloud: a path (PCD/PLY/npy) or an (N, 3) array of points.

        remove_plane: find and remove the support plane (a scene cloud); plane: give it instead
        ([a, b, c, d]); approach_axis: prefer wrists whose approach axis points along it (e.g. (0, 0, -1)
        for top grasps); reachable(wrists, joints) -> bool array: the hard reachability test; experts:
        more experts (graspmix.expert(...) or graspmix._core.Expert objects)."""
        t0 = time.perf_counter()
        name = str(cloud) if isinstance(cloud, (str, Path)) else "<array>"
        if isinstance(cloud, (str, Path)):
            loaded = _core.load_cloud(str(cloud))
            points = loaded.points
            if viewpoints is None and loaded.has_viewpoint:
                viewpoints = loaded.viewpoint[:3]
        else:
            points = _as_points(cloud)
        if plane is not None:
            plane = np.asarray(plane, dtype=float)
            if plane.shape != (4,) or not np.all(np.isfinite(plane)) or not np.linalg.norm(plane[:3]) > 0:
                raise ValueError("plane must be 4 finite numbers [a, b, c, d] with a non-zero normal")
        surface, scene = self.features.surface(points, remove_plane=remove_plane and plane is None, seed=seed,
                                               viewpoints=viewpoints, plane=plane)
        if plane is None and scene.plane_found:
            plane = np.asarray(scene.plane)
        t_features = time.perf_counter() - t0
        hand = self.hand
        # Depths up to contact_tolerance are touching, not penetrating: a cloud is a noisy surface.
        collision = _core.CollisionExpert(hand, surface.points, plane=plane, beta=collision_beta,
                                          contact_tolerance=contact_tolerance, inside_weight=collision_inside_weight)
        all_experts = []
        if kinematic:
            all_experts.append(_core.KinematicFeasibilityExpert(hand, plane=_oriented(plane, surface.points),
                                                                reachable=reachable))
        elif reachable is not None:
            raise ValueError("reachable needs the kinematic expert (kinematic=True)")
        if approach_axis is not None:
            # log E = concentration (cos - 1): 20 makes a 90-degree deviation cost 20 nats, comparable
            # to the contact terms, so the preference decides between otherwise similar grasps.
            all_experts.append(_core.AxisAlignmentExpert(np.asarray(approach_axis, float),
                                                         concentration=approach_concentration))
        all_experts.extend(experts)
        s = _core.SynthesisSettings()
        s.n_samples, s.n_optimise, s.optimise, s.seed = n_samples, n_optimise, optimise, seed
        s.clear_pregrasp = clear_pregrasp
        q = s.query
        q.n_samples = query_samples
        q.kde_bandwidths = (self.learn_settings.get("kde_position_bandwidth", 0.005),
                            self.learn_settings.get("kde_orientation_bandwidth", 0.15))
        s.query = q
        a = s.annealing
        for k, v in (annealing or {}).items():
            if not hasattr(a, k):
                raise ValueError(f"unknown annealing setting {k!r}")
            setattr(a, k, v)
        s.annealing = a
        res = self.synthesizer.synthesize(surface.frames, surface.curvatures, collision, all_experts, s)
        timing = dict(res.timing)
        timing["features"] = t_features
        timing["total"] = time.perf_counter() - t0
        names = hand.joint_names
        grasps = []
        for rank, g in enumerate(res.grasps, start=1):
            experts_table = {"collision": g["log_collision"], "config": g["log_config"],
                             "pregrasp_clear": g["log_pregrasp"]}
            experts_table.update({f"contact/{n}": float(v) for n, v in zip(res.contact_links, g["log_contact"])})
            experts_table.update({n: float(v) for n, v in zip(res.expert_names, g["log_experts"])})
            grasps.append({"rank": rank, "T_world_wrist": [float(x) for x in g["T_world_wrist"]],
                           "pregrasp_joints": hand.joints_dict(g["pregrasp"]),
                           "grasp_joints": hand.joints_dict(g["joints"]),
                           "log_likelihood": float(g["log_likelihood"]), "optimised": bool(g["optimised"]),
                           "experts": {k: float(v) for k, v in experts_table.items()}})
        return GraspSet(grasps, self.hand_path, self.method, name, timing, surface,
                        plane, res.evaluations, res.rejected)


def _as_points(cloud) -> np.ndarray:
    try:
        pts = np.asarray(cloud, dtype=float)
    except (TypeError, ValueError):
        raise ValueError("cloud must be a file path or an (N, 3) array of points") from None
    if pts.ndim != 2 or pts.shape[1] != 3:
        raise ValueError(f"cloud must be an (N, 3) array, got shape {pts.shape}")
    if len(pts) == 0:
        raise ValueError("cloud is empty")
    return pts


def _oriented(plane, points):
    """The plane with its sign chosen so the object's points are on its positive side."""
    if plane is None:
        return None
    n = np.asarray(plane, float)
    if np.mean(points @ n[:3] + n[3]) < 0:
        n = -n
    return n


_CONFIG_KEYS = ("beta", "n_kernels", "alpha", "bandwidth", "min_bandwidth")


def _config_settings(d: dict) -> "_core.ConfigModelSettings":
    s = _core.ConfigModelSettings()
    for k, v in d.items():
        if k not in _CONFIG_KEYS:
            raise ValueError(f"unknown configuration-model setting {k!r} (known: {', '.join(_CONFIG_KEYS)})")
        setattr(s, k, v)
    return s


def _config_dict(s) -> dict:
    return {k: getattr(s, k) for k in _CONFIG_KEYS}


def expert(name: str, fn: Callable, kind: str = "probability") -> "_core.Expert":
    """A user-defined expert from a Python function of a batch: fn(wrists (N, 7), joints (N, D)) returning
    probabilities in [0, 1] (kind="probability"), booleans (kind="hard": False rejects), or log values
    (kind="log")."""
    if kind not in ("probability", "hard", "log"):
        raise ValueError(f"kind must be 'probability', 'hard' or 'log', got {kind!r}")

    def log_value(wrists, joints):
        v = np.asarray(fn(wrists, joints))
        if v.shape != (len(wrists),):
            raise ValueError(f"expert '{name}' returned shape {v.shape} for {len(wrists)} grasps")
        if kind == "log":
            return v.astype(float)
        if kind == "hard":
            return np.where(v.astype(bool), 0.0, -np.inf)
        v = v.astype(float)
        if np.any((v < 0) | (v > 1)) or np.any(np.isnan(v)):
            raise ValueError(f"expert '{name}' returned values outside [0, 1]")
        with np.errstate(divide="ignore"):
            return np.log(v)

    return _core.FunctionExpert(name, log_value)


def learn(demo, method: str = "gmm", **kwargs) -> GraspModel:
    """Learns a GraspModel from one demonstration file (see GraspModel.learn for the settings)."""
    return GraspModel.learn(demo, method, **kwargs)
