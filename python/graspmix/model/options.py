"""SynthesisOptions: the one object that configures a synthesis on a cloud.

It is composed of the bound C++ settings structs, each a part of the pipeline, and carried unchanged from
the API (GraspModel.synthesize), the command line (graspmix_cli synthesize, experiment, clutter) and the
experiment's protocol down to the C++ calls; every default is the default-constructed struct's.

    options = graspmix.SynthesisOptions(sampling=graspmix.SamplingSettings(n_samples=400), contact_quality=None)
    options = options.updated({"approach.stand_off": 0.15, "seed": 3})   # or dataclasses.replace(options, ...)
    grasps = model.synthesize("scan.pcd", options, target="largest")

The options are frozen: their parts are copies taken when they are made, and a change makes new options
(`updated`, `dataclasses.replace`). A part that may be None is an expert that may be left out.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from typing import Mapping

import numpy as np

from .. import _core
from ..io.checks import MAX_COMPONENTS, MAX_DRAWN, MAX_GRASPS, MAX_SAMPLES, check_float, check_int, check_seed, quote

# name -> (settings class, whether None is allowed: the expert is left out)
PARTS = {
    "segmentation": (_core.SegmentationSettings, False),
    "sampling": (_core.SamplingSettings, False),
    "query": (_core.QuerySettings, False),
    "annealing": (_core.AnnealingSettings, False),
    "collision": (_core.CollisionSettings, False),
    "occupancy": (_core.OccupancySettings, False),
    "kinematic": (_core.KinematicFeasibilitySettings, True),
    "axis_alignment": (_core.AxisAlignmentSettings, False),
    "approach": (_core.ClearApproachSettings, True),
    "contact_quality": (_core.ContactQualitySettings, True),
    "grasp_depth": (_core.GraspDepthSettings, True),
    "completion": (_core.CompletionSettings, True),
}
# The parts added after runs began to store their options (to_dict writes every part, None when off): a stored
# document without one was made before it existed, so it ran without it (SynthesisOptions.from_stored).
LATER_PARTS = ("grasp_depth",)
# The fields added to a part after runs began to store their options, with the value that gives the behaviour from
# before: a stored part without one ran that way (SynthesisOptions.from_stored).
# (A named segment larger than 1 km: the split of a point target's segment never cuts, as before it existed.)
LATER_FIELDS = {
    ("sampling", "oversample"): 1,
    ("segmentation", "split_named_max_size"): 1000.0,
    ("contact_quality", "target_first"): False,
}
COLLISION_MODELS = ("surface", "occupancy")
# m: the default table clearance, for the tools that crop a table outside a synthesis (plots, the top-down planner)
TABLE_CLEARANCE = _core.SegmentationSettings().table_clearance


def _part(name: str):
    return field(default_factory=PARTS[name][0])


@dataclass(frozen=True)
class SynthesisOptions:
    """Everything that decides a synthesis on a cloud but the cloud, its views, the target and the task's own
    experts (GraspModel.synthesize's other arguments).

    segmentation: the support plane and the objects (graspmix.segment_scene); its voxel_size is the model's
        (the features must match the demonstration's): left at its default it is taken from the model, another
        value must equal the model's. Its seed is always `seed`.
    sampling: how many grasps are drawn, kept and annealed.
    query: the contact query densities Q_i.
    annealing: the simulated annealing of the best grasps.
    collision: the collision expert W (model "surface": the cloud's points; "occupancy": also what the cameras
        did not see free, on an OccupancyMap made with `occupancy`).
    kinematic: joint limits and the support plane, hard (None: off).
    axis_alignment: the preference for an approach axis, used when synthesize(approach_axis=...) is given.
    approach: the hard clear approach of the open hand from the stand-off (None: off).
    contact_quality: the soft antipodal contact test of the closing hand (None: off).
    grasp_depth: the soft charge of a grasp whose fingertips reach less than grasp_depth.min_depth back into the object
        (the object's points between the fingers, along the approach: grasp_depth.hpp; None: off).
    completion: the unseen side of every object completed from what the cameras saw (graspmix.complete_object;
        None: off). The completed points join the target's surface, weighing query.completed_weight in the query
        densities, and the points the hand keeps out of (collision, clear approach, contact quality). Without a
        viewpoint or a support plane nothing is completed, and the grasp set's notes say so.
    seed: seeds everything random (RANSAC, sampling, annealing).
    """

    segmentation: _core.SegmentationSettings = _part("segmentation")
    sampling: _core.SamplingSettings = _part("sampling")
    query: _core.QuerySettings = _part("query")
    annealing: _core.AnnealingSettings = _part("annealing")
    collision: _core.CollisionSettings = _part("collision")
    occupancy: _core.OccupancySettings = _part("occupancy")
    kinematic: _core.KinematicFeasibilitySettings | None = _part("kinematic")
    axis_alignment: _core.AxisAlignmentSettings = _part("axis_alignment")
    approach: _core.ClearApproachSettings | None = _part("approach")
    contact_quality: _core.ContactQualitySettings | None = _part("contact_quality")
    grasp_depth: _core.GraspDepthSettings | None = _part("grasp_depth")
    completion: _core.CompletionSettings | None = _part("completion")
    seed: int = 0

    def __post_init__(self):
        for name, (cls, optional) in PARTS.items():
            value = getattr(self, name)
            if value is None and optional:
                continue
            if not isinstance(value, cls):
                allowed = f"a {cls.__name__}" + (" or None" if optional else "")
                raise ValueError(f"SynthesisOptions.{name}: expected {allowed}, got {type(value).__name__}")
            object.__setattr__(self, name, copy.copy(value))  # the options own their parts
        object.__setattr__(self, "seed", check_seed(self.seed, "SynthesisOptions.seed"))
        self.segmentation.seed = self.seed  # derived: one seed seeds everything (RANSAC too)
        self._check_numbers()

    def _check_numbers(self) -> None:
        """The numbers bounded before they reach a C++ cast or a long run (ValueError naming the field)."""
        s, q = self.sampling, self.query
        check_int(s.n_samples, "sampling.n_samples", 1, MAX_GRASPS)
        check_int(s.n_optimise, "sampling.n_optimise", 0, MAX_GRASPS)
        check_int(s.max_sampling_rounds, "sampling.max_sampling_rounds", 1, 1000)
        check_int(s.oversample, "sampling.oversample", 1, _core.MAX_OVERSAMPLE)
        if s.n_samples * s.oversample > MAX_DRAWN:
            raise ValueError(
                f"sampling.n_samples * sampling.oversample (the grasps drawn) must be at most {MAX_DRAWN}, got "
                f"{s.n_samples} * {s.oversample}"
            )
        check_int(q.n_samples, "query.n_samples", 1, MAX_SAMPLES)
        check_int(q.n_components, "query.n_components", 1, MAX_COMPONENTS)
        if q.n_components > q.n_samples:
            raise ValueError(f"query.n_components ({q.n_components}) must not exceed query.n_samples ({q.n_samples})")
        check_int(self.annealing.iterations, "annealing.iterations", 0, MAX_SAMPLES)
        check_float(self.annealing.initial_temperature, "annealing.initial_temperature", gt=0.0)
        c = self.collision
        for name in ("beta", "contact_tolerance", "inside_weight", "point_radius"):
            check_float(getattr(c, name), f"collision.{name}", 0.0)
        check_float(self.occupancy.resolution, "occupancy.resolution", gt=0.0)
        check_float(self.axis_alignment.concentration, "axis_alignment.concentration", 0.0)
        check_float(self.segmentation.table_clearance, "segmentation.table_clearance", 0.0)
        if self.approach is not None:
            check_float(self.approach.stand_off, "approach.stand_off", 0.0)
            check_float(self.approach.step, "approach.step", gt=0.0)
            check_float(self.approach.clearance, "approach.clearance", 0.0)
        if self.contact_quality is not None:
            check_float(self.contact_quality.friction, "contact_quality.friction", gt=0.0)
        if self.grasp_depth is not None:
            for name in ("min_depth", "penalty", "min_radius"):
                check_float(getattr(self.grasp_depth, name), f"grasp_depth.{name}", 0.0)
        check_float(q.completed_weight, "query.completed_weight", gt=0.0)
        if q.completed_weight > 1.0:
            raise ValueError(
                f"query.completed_weight must be in (0, 1] (an observed point weighs 1), got {q.completed_weight}"
            )

    def __repr__(self) -> str:
        """The parts that differ from the defaults (all of them: repr(options.part))."""
        default = SynthesisOptions(seed=self.seed)  # the segmentation's seed is the options' own
        changed = [f"{n}={getattr(self, n)!r}" for n in PARTS if getattr(self, n) != getattr(default, n)]
        if self.seed:
            changed.append(f"seed={self.seed}")
        return f"SynthesisOptions({', '.join(changed)})"

    # -- presets and changes
    @classmethod
    def paper(cls, **parts) -> "SynthesisOptions":
        """The paper's synthesis: the collision expert on the cloud's points and the plane alone (no solid volume,
        no charge of unseen space), each link's contact term its query density as it is (no floor), grasps drawn
        from the query densities alone (no top-down seeds, n_samples drawn, not twice as many), no clear
        approach, no contact quality, no grasp depth, no completion, no split of a cluster
        larger than one object (the experiment's "paper" preset: its single objects, some longer than 15 cm, stay
        whole); `parts` as the constructor's."""
        return cls(
            **{
                "segmentation": _core.SegmentationSettings(split_touching=False),
                "query": _core.QuerySettings(link_floor=None),
                "sampling": _core.SamplingSettings(topdown_seeds=False, oversample=1),
                "collision": _core.CollisionSettings(
                    model="surface", volume=False, unseen_weight=0.0, unseen_margin=0.0
                ),
                "approach": None,
                "contact_quality": None,
                "grasp_depth": None,
                "completion": None,
                **parts,
            }
        )

    def updated(self, changes: Mapping[str, object]) -> "SynthesisOptions":
        """New options with `changes` applied: "part.field" -> value (e.g. "sampling.n_samples": 400), "part" ->
        a settings object, None (an optional expert off) or True (on, with its defaults), "seed" -> int.
        ValueError naming an unknown part or field, or a value of the wrong kind."""
        parts = {name: getattr(self, name) for name in PARTS}
        seed = self.seed
        for key, value in changes.items():
            name, _, fld = str(key).partition(".")
            if name == "seed" and not fld:
                seed = value
                continue
            if name not in PARTS:
                raise ValueError(f"unknown synthesis option {quote(key)} (parts: {', '.join(PARTS)}, seed)")
            cls, optional = PARTS[name]
            if not fld:
                if value is True:  # on: as it is, or with its defaults when it was off
                    value = parts[name] if parts[name] is not None else cls()
                elif value is False and optional:
                    value = None
                parts[name] = value
                continue
            if parts[name] is None:
                parts[name] = cls()  # a field of a part that was off turns it on
            parts[name] = _with_field(parts[name], name, fld, value)
        return SynthesisOptions(**parts, seed=seed)

    # -- the file form (protocol.json, the CLI's records)
    def to_dict(self) -> dict:
        """JSON-ready: {part: {field: value} or None, "seed": int}."""
        out = {name: _fields_dict(getattr(self, name)) for name in PARTS}
        out["seed"] = self.seed
        return out

    @classmethod
    def from_dict(cls, d: Mapping) -> "SynthesisOptions":
        """The options of to_dict's form; a part or field left out keeps its default. ValueError naming an unknown
        part or field, or a bad value."""
        if not isinstance(d, Mapping):
            raise ValueError(f"synthesis options: expected an object of parts, got {type(d).__name__}")
        parts = {}
        for name, value in d.items():
            if name == "seed":
                continue
            if name not in PARTS:
                raise ValueError(f"synthesis options: unknown part {quote(name)} (parts: {', '.join(PARTS)}, seed)")
            cls_, optional = PARTS[name]
            if value is None:
                if not optional:
                    raise ValueError(f"synthesis options: {name} cannot be null")
                parts[name] = None
            elif isinstance(value, Mapping):
                parts[name] = _settings_of(cls_, name, value)
            else:
                raise ValueError(f"synthesis options: {name} must be an object of fields, got {quote(value)}")
        return cls(**parts, seed=d.get("seed", 0))

    @classmethod
    def from_stored(cls, d: Mapping) -> "SynthesisOptions":
        """The options a run stored (to_dict's form, written whole): as from_dict, but a part of LATER_PARTS that the
        document leaves out is off, and a field of LATER_FIELDS its part leaves out has its value from before, since
        the run was made before they existed (from_dict would give their defaults)."""
        if not isinstance(d, Mapping):
            return cls.from_dict(d)  # its error
        d = {**{name: None for name in LATER_PARTS}, **d}
        for (part, name), before in LATER_FIELDS.items():
            if isinstance(d.get(part), Mapping) and name not in d[part]:
                d[part] = {**d[part], name: before}
        return cls.from_dict(d)

    # -- what the C++ calls take
    def synthesizer_settings(
        self, position_bandwidth: float, orientation_bandwidth: float
    ) -> "_core.SynthesizerSettings":
        """The GraspSynthesizer's settings for a model learnt with these KDE kernels: sampling, annealing, the seed,
        and the query densities of query_for."""
        query = self.query_for(position_bandwidth, orientation_bandwidth)
        return _core.SynthesizerSettings(sampling=self.sampling, query=query, annealing=self.annealing, seed=self.seed)

    def query_for(self, position_bandwidth: float, orientation_bandwidth: float) -> "_core.QuerySettings":
        """The query densities' settings for a model learnt with these KDE kernels: query.kde left at its defaults
        takes the model's (a KDE model's query densities use its contact kernels), a value set is kept."""
        q = copy.copy(self.query)
        default = _core.KdeSettings()
        if q.kde.position_bandwidth == default.position_bandwidth:
            q.kde.position_bandwidth = position_bandwidth
        if q.kde.orientation_bandwidth == default.orientation_bandwidth:
            q.kde.orientation_bandwidth = orientation_bandwidth
        return q

    def segmentation_for(self, voxel_size: float) -> "_core.SegmentationSettings":
        """The segmentation's settings for a model whose features were learnt at voxel_size (see the class doc)."""
        s = copy.copy(self.segmentation)
        default = _core.SegmentationSettings().voxel_size
        if s.voxel_size not in (default, voxel_size):
            raise ValueError(
                f"segmentation.voxel_size ({s.voxel_size:g} m) differs from the model's ({voxel_size:g} m): the query "
                "cloud's features must be computed at the demonstration's density"
            )
        s.voxel_size, s.seed = voxel_size, self.seed
        return s


def _value(v):
    if isinstance(v, np.ndarray):
        return v.tolist()
    return v


def _fields_dict(settings) -> dict | None:
    if settings is None:
        return None
    return {
        f: (_fields_dict(v) if hasattr(v, "_fields") else _value(v))
        for f in settings._fields
        for v in [getattr(settings, f)]
    }


def _settings_of(cls, where: str, values: Mapping):
    """A settings object of `cls` from a {field: value} mapping (nested settings from nested mappings)."""
    return _with_fields(cls(), where, values)


def _with_fields(settings, where: str, values: Mapping):
    for k, v in values.items():
        settings = _with_field(settings, where, k, v)
    return settings


def _with_field(settings, where: str, fld: str, value):
    """A copy of `settings` with one field (nested "a.b" too; a mapping for a nested settings object changes the
    fields it names) set; ValueError naming it when unknown or bad."""
    head, _, rest = fld.partition(".")
    if head not in settings._fields:
        raise ValueError(
            f"unknown synthesis option {quote(where + '.' + fld)} ({where}'s fields: {', '.join(settings._fields)})"
        )
    current = getattr(settings, head)
    nested = hasattr(current, "_fields")
    if rest and not nested:
        raise ValueError(f"synthesis option {quote(where + '.' + fld)}: {head} has no fields")
    if rest:
        value = _with_field(current, f"{where}.{head}", rest, value)
    elif nested and isinstance(value, Mapping):
        value = _with_fields(current, f"{where}.{head}", value)
    # Through the class's keyword constructor: the C++ settings_from converts and words a bad value's error.
    fields = {f: getattr(settings, f) for f in settings._fields}
    try:
        return type(settings)(**{**fields, head: value})
    except ValueError as e:
        raise ValueError(f"synthesis option {where}.{head}: {e}") from None


def options_field_names() -> list[str]:
    """Every "part.field" name `updated` takes (nested settings as "part.field.sub"), and "seed"."""
    out = []

    def walk(prefix, settings):
        for f in settings._fields:
            v = getattr(settings, f)
            if hasattr(v, "_fields"):
                walk(f"{prefix}.{f}", v)
            else:
                out.append(f"{prefix}.{f}")

    for name, (cls, _) in PARTS.items():
        walk(name, cls())
    return out + ["seed"]


__all__ = ["COLLISION_MODELS", "PARTS", "TABLE_CLEARANCE", "SynthesisOptions", "options_field_names"]
