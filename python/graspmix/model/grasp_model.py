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
import warnings
from pathlib import Path
from typing import Callable, Iterable, Sequence

import numpy as np

from .. import _core
from ..io import (
    MODEL_FORMAT,
    data_path,
    read_document,
    relative_path,
    require_field,
    resolve_path,
    sha256_file,
)
from ..io.checks import (
    MAX_COMPONENTS,
    check_float,
    check_input_file,
    check_int,
    check_output_path,
    check_path_text,
    check_seed,
)
from ..perception import depth_record, quaternion_order_note, scene_input
from .demonstration import Demonstration
from .grasp_types import (
    GraspType,
    check_names,
    check_same_hand,
    default_type_name,
    log_reference,
    parse_demo_spec,
    select_types,
    type_from_json,
    type_to_json,
)
from .grasps import GraspSet, NoFeasibleGraspWarning
from .options import SynthesisOptions
from .scene_synthesis import synthesize_scene
from .serialization import config_dict, config_settings
from .settings import FeatureScale, LearnSettings, check_method

_L = LearnSettings  # the defaults of learn()


def default_model_path(method: str = "gmm") -> Path:
    """The bundled model learnt from the box demonstration with the WSG 50."""
    check_method(method)
    return data_path("models", f"box_wsg50_{method}.json")


class GraspModel:
    """One or more grasp types (GraspType: a demonstration's contact models M_i for every link that touched
    the object and its configuration model C), all for one hand, and how they were learnt; synthesises
    grasps of every type on new clouds and ranks them together (graspmix.model.grasp_types says how)."""

    def __init__(
        self,
        hand: "_core.Hand",
        hand_path: Path,
        types: "list[GraspType]",
        features: FeatureScale,
        learn_settings: dict,
    ):
        self._hand = hand
        self.hand_path = Path(hand_path)
        if not isinstance(types, list) or not all(isinstance(t, GraspType) for t in types):
            raise ValueError(f"types must be a list of GraspType, got {type(types).__name__}")
        if not types:
            raise ValueError("a GraspModel needs at least one grasp type")
        check_names([t.name for t in types])
        self.types = types
        self.features = features
        self.learn_settings = learn_settings

    # -- properties
    @property
    def synthesizer(self) -> "_core.GraspSynthesizer":
        """The first grasp type's synthesiser (the only one of a single-demonstration model)."""
        return self.types[0].synthesizer

    @property
    def demo(self) -> str | None:
        """The first grasp type's demonstration file."""
        return self.types[0].demo

    @property
    def type_names(self) -> list[str]:
        return [t.name for t in self.types]

    @property
    def method(self) -> str:
        return self.synthesizer.method

    @property
    def hand(self) -> "_core.Hand":
        return self._hand

    @property
    def contact_links(self) -> list[str]:
        """The links with a contact model, in any type (in order of first appearance)."""
        return list(dict.fromkeys(n for t in self.types for n in t.contact_links))

    def __repr__(self):
        return (
            f"GraspModel(method={self.method!r}, hand={self.hand_path.name!r}, types={self.type_names}, "
            f"contact links={self.contact_links})"
        )

    # -- learning
    @classmethod
    def learn(
        cls,
        demo,
        method: str = "gmm",
        *,
        n_components: int = _L.n_components,
        kde_position_bandwidth: float = _L.kde_position_bandwidth,
        kde_orientation_bandwidth: float = _L.kde_orientation_bandwidth,
        kde_feature_bandwidth: float = _L.kde_feature_bandwidth,
        gmm_reg_covar: float = _L.gmm_reg_covar,
        max_distance: float = _L.max_distance,
        contact_lambda: float = _L.contact_lambda,
        min_points: int = _L.min_points,
        voxel_size: float = FeatureScale.voxel_size,
        radius: float = FeatureScale.radius,
        seed: int = _L.seed,
        config: dict | None = None,
    ) -> "GraspModel":
        """Learns from one demonstration (a file, "name=file" or a Demonstration) or a list of them: each
        demonstration is one grasp type, named by the name given or else its file's stem, with its own
        contact and configuration models. All demonstrations must be of the same hand (ValueError
        otherwise). A model of several types also stores each type's log L_ref, what its demonstrated
        grasp scores on its own demonstration cloud (see graspmix.model.grasp_types)."""
        check_method(method)
        check_learn_numbers(
            n_components=n_components,
            kde_position_bandwidth=kde_position_bandwidth,
            kde_orientation_bandwidth=kde_orientation_bandwidth,
            kde_feature_bandwidth=kde_feature_bandwidth,
            gmm_reg_covar=gmm_reg_covar,
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
            n_components=n_components,
            kde_position_bandwidth=kde_position_bandwidth,
            kde_orientation_bandwidth=kde_orientation_bandwidth,
            kde_feature_bandwidth=kde_feature_bandwidth,
            max_distance=max_distance,
            contact_lambda=contact_lambda,
            min_points=min_points,
            seed=seed,
            gmm_reg_covar=gmm_reg_covar,
        )
        feats = FeatureScale(voxel_size=voxel_size, radius=radius)
        cfg_settings = config_settings(config or {})
        types, hand, hand_path = _learn_types(demo, method, s, feats, cfg_settings)
        learn_settings = dict(dataclasses.asdict(s), config=config_dict(cfg_settings))
        return cls(hand, hand_path, types, feats, learn_settings)

    # -- persistence
    def save(self, path: str | Path) -> None:
        """Writes the model file (format graspmix.model/2: the shared hand, features and settings, and a
        "types" list, each with its name, demonstration, log_reference, config_model and contact_models)."""
        path = check_output_path(path, "model file")
        base = path.resolve().parent
        data = {
            "format": MODEL_FORMAT,
            "method": self.method,
            "hand": relative_path(self.hand_path, base),
            "features": {"voxel_size": self.features.voxel_size, "radius": self.features.radius},
            "learn_settings": self.learn_settings,
            "types": [type_to_json(t, base) for t in self.types],
        }
        path.write_text(json.dumps(data) + "\n")

    @classmethod
    def load(cls, path: str | Path) -> "GraspModel":
        """Reads a model file (format graspmix.model/2)."""
        path = check_path_text(path, "model")
        data = read_document(path, MODEL_FORMAT)
        method = require_field(data, "method", path, str)
        check_method(method)
        base = path.resolve().parent
        hand_path = resolve_path(require_field(data, "hand", path, str), base)
        hand = _core.Hand.from_urdf(str(check_input_file(hand_path, "hand")))
        f = require_field(data, "features", path, dict)
        feats = FeatureScale(
            voxel_size=float(f.get("voxel_size", FeatureScale.voxel_size)),
            radius=float(f.get("radius", FeatureScale.radius)),
        )
        entries = require_field(data, "types", path, list)
        types = [type_from_json(e, hand, hand_path, method, path, e["name"]) for e in entries]
        return cls(hand, hand_path, types, feats, data.get("learn_settings", {}))

    # -- synthesis
    def synthesize(
        self,
        cloud=None,
        options: SynthesisOptions | None = None,
        *,
        depth=None,
        intrinsics=None,
        depth_scale: float | None = None,
        camera_pose=None,
        target="all",
        viewpoints=None,
        plane=None,
        approach_axis: Sequence[float] | None = None,
        reachable: Callable | None = None,
        experts: Iterable = (),
        types=None,
    ) -> GraspSet:
        """Grasps on one camera's view or on a cloud, configured by `options` (SynthesisOptions; None: the library's
        defaults). The input, as cameras give it: an organized cloud `cloud` (H, W, 3) in the sensor frame (x right,
        y down, z forward; NaN where nothing was hit), or a depth image `depth` ((H, W) array, or a 16-bit PNG in
        millimetres or a .npy) with its `intrinsics` (K (3, 3), (fx, fy, cx, cy) or a PinholeCamera) and
        `depth_scale` (metres per unit; None: 0.001 for integers, 1 for floats), each with the camera's pose
        camera_pose = T_world_camera [x, y, z, qx, qy, qz, qw] (None: the world is the camera's frame); such a view
        is segmented in image space (as perception.segment_view does), and so is an organized PCD (its VIEWPOINT the
        camera's pose, perception.organized_file_view). Or any cloud: a path (PCD/PLY/npy) or an (N, 3) array of
        points (with camera_pose: in that camera's frame). Grasps come back in the world frame. Everything after
        reading the input is one C++ call (graspmix._core.synthesize_scene: include/graspmix/grasp/scene_synthesis.hpp).

        The cloud is segmented (as graspmix.segment_scene does) into its support plane and the objects on it;
        grasps are sampled on the target objects and checked for collision against all of them and the
        plane. target: "all" (every object, best grasps first), an object index, "point:x,y,z" (the object
        nearest the point), "largest", "nearest" (to the camera); every grasp records its object.
        viewpoints (an unorganized cloud's): the camera position (3,) or one per point (N, 3) (default: the file's);
        they orient the plane and the normals.
        plane: a known support [a, b, c, d] instead of the one searched for (points within
        options.segmentation.table_clearance of it are dropped). approach_axis: prefer wrists whose approach axis
        points along it (e.g. (0, 0, -1) for top grasps; options.axis_alignment says how much);
        reachable(wrists, joints) -> bool array: the hard reachability test; experts: more experts
        (graspmix.expert(...) or graspmix._core.Expert objects); types: the grasp types to sample (names, a list
        or "a,b"; default all), each sampling and optimising as many grasps as one would, all ranked together by
        log L - log L_ref of their type (graspmix.model.grasp_types), each grasp recording its "type"."""
        opts = checked_options(options)
        chosen = select_types(self.types, types)
        t0 = time.perf_counter()
        source, name, notes = scene_input(cloud, depth, intrinsics, depth_scale, camera_pose, viewpoints)
        view = None if depth is None else depth_record(depth, source, depth_scale)
        name = "" if view is not None else name  # the depth image is the view, not a cloud file
        t_input = time.perf_counter() - t0
        # The scene (support plane, objects, completion), the targets and every target's synthesis: one C++ call.
        out = synthesize_scene(
            self,
            source,
            checked_plane(plane),
            target,
            opts,
            self.synthesizer_settings(opts),
            approach_axis=approach_axis,
            reachable=reachable,
            experts=experts,
            types=chosen,
        )
        order = quaternion_order_note(camera_pose, out.scene.plane if out.scene.plane_found else None)
        out.scene.notes[:0] = notes + ([order] if order else [])
        timing = dict(out.timing)
        segmentation = t_input + timing.pop("segmentation")  # reading the input counts as the segmentation's
        timing = _stage_times(timing, segmentation, time.perf_counter() - t0)
        grasps = GraspSet(
            out.grasps, self.hand_path, self.method, name, timing, out.surface, out.scene.plane, out.evaluations,
            out.rejected, scene=out.scene, targets=out.targets, hand=self._hand, view=view,
            cloud_sha256=sha256_file(name) if isinstance(cloud, (str, Path)) else "",
        )  # fmt: skip
        if len(grasps) and grasps.n_feasible == 0:
            warnings.warn(grasps.no_feasible_message(), NoFeasibleGraspWarning, stacklevel=2)
        return grasps

    def synthesizer_settings(self, opts: SynthesisOptions) -> "_core.SynthesizerSettings":
        """The GraspSynthesizer's settings of `opts` for this model (its KDE kernels where the options leave the
        query's at their defaults: SynthesisOptions.query_for)."""
        ls = self.learn_settings
        return opts.synthesizer_settings(
            ls.get("kde_position_bandwidth", _L.kde_position_bandwidth),
            ls.get("kde_orientation_bandwidth", _L.kde_orientation_bandwidth),
        )


def checked_options(options) -> SynthesisOptions:
    """The options of a synthesis: None is the defaults; anything but SynthesisOptions is a ValueError."""
    if options is None:
        return SynthesisOptions()
    if not isinstance(options, SynthesisOptions):
        raise ValueError(
            f"options must be a graspmix.SynthesisOptions (or None for the defaults), got {type(options).__name__}"
        )
    return options


def _stage_times(synthesis: dict, segmentation: float, total: float) -> dict:
    """A synthesis' stage times: the segmentation (the clean-up, plane and objects), the features (surface
    features of the targets: what the synthesiser's own stages and the segmentation leave of the total), the
    synthesiser's stages and the total."""
    timing = dict(synthesis)
    timing["segmentation"] = segmentation
    timing["total"] = total
    timing["features"] = total - segmentation - sum(synthesis.values())
    return timing


def checked_plane(plane):
    """None, or a plane [a, b, c, d] of 4 finite numbers with a non-zero normal (ValueError otherwise)."""
    if plane is None:
        return None
    plane = np.asarray(plane, dtype=float)
    if plane.shape != (4,) or not np.all(np.isfinite(plane)) or not np.linalg.norm(plane[:3]) > 0:
        raise ValueError("plane must be 4 finite numbers [a, b, c, d] with a non-zero normal")
    return plane


def check_learn_numbers(**v) -> None:
    """learn()'s numbers given (any of its keywords), bounded before they reach a C++ cast (ValueError naming the
    keyword)."""
    ints = {"n_components": MAX_COMPONENTS, "min_points": 2**31 - 1}
    positive = (
        "kde_position_bandwidth",
        "kde_orientation_bandwidth",
        "kde_feature_bandwidth",
        "gmm_reg_covar",
        "max_distance",
        "contact_lambda",
        "radius",
    )
    for name, value in v.items():
        if name in ints:
            check_int(value, name, 1, ints[name])
        elif name == "seed":
            check_seed(value)
        elif name in positive:
            check_float(value, name, gt=0.0)
        elif name == "voxel_size":
            check_float(value, name, 0.0)
        else:
            raise ValueError(f"unknown learning setting {name!r}")


def _learn_types(demos, method: str, s: LearnSettings, feats: FeatureScale, cfg_settings) -> tuple:
    """(types, hand, hand path) learnt from one demonstration or a list of them (see GraspModel.learn)."""
    specs = list(demos) if isinstance(demos, (list, tuple)) else [demos]
    if not specs:
        raise ValueError("no demonstration to learn from")
    named = [parse_demo_spec(x) for x in specs]
    loaded = [d if isinstance(d, Demonstration) else Demonstration.load(d) for _, d in named]
    names = [n or default_type_name(d, i) for i, ((n, _), d) in enumerate(zip(named, loaded))]
    check_names(names)
    hands = [_core.Hand.from_urdf(str(check_input_file(d.hand_path, "hand"))) for d in loaded]
    check_same_hand(hands, loaded)
    hand = hands[0]
    types = []
    for name, d in zip(names, loaded):
        surface, _ = feats.surface(d.cloud, remove_plane=False, seed=s.seed)
        models = _core.learn_contact_models(
            hand,
            d.T_world_wrist,
            d.grasp_joints,
            surface.frames,
            surface.curvatures,
            _density_factory(method, s),
            _contact_settings(s),
        )
        cfg = _core.ConfigModel(
            hand.joints_array(d.pregrasp_joints), hand.joints_array(d.grasp_joints), hand.joint_limits, cfg_settings
        )
        synthesizer = _core.GraspSynthesizer(hand, models, cfg)
        # One type needs no reference: its ranking and scores stay those of a single-demonstration model.
        ref = log_reference(hand, synthesizer, d, surface, s.seed) if len(loaded) > 1 else 0.0
        types.append(GraspType(name, synthesizer, str(d.source) if d.source else None, ref))
    return types, hand, loaded[0].hand_path


def _density_factory(method: str, s: LearnSettings) -> Callable:
    if method == "gmm":
        return lambda: _core.PoseMixture(n_components=s.n_components, seed=s.seed, reg_covar=s.gmm_reg_covar)
    return lambda: _core.PoseKDE(
        position_bandwidth=s.kde_position_bandwidth,
        orientation_bandwidth=s.kde_orientation_bandwidth,
        feature_bandwidth=s.kde_feature_bandwidth,
    )


def _contact_settings(s: LearnSettings) -> "_core.ContactSettings":
    contact = _core.ContactSettings()
    contact.max_distance, contact.lambda_, contact.min_points = s.max_distance, s.contact_lambda, s.min_points
    return contact


def learn(demo, method: str = "gmm", **kwargs) -> GraspModel:
    """Learns a GraspModel from one demonstration file or a list of them, one grasp type each (see
    GraspModel.learn for the names and settings)."""
    return GraspModel.learn(demo, method, **kwargs)
