"""Grasp types: one demonstration each, with its own contact models M_i and configuration model C, all
for the same hand; a GraspModel holds one or more.

Scores of different types are made comparable by each type's reference: the log-likelihood log L_ref
that the type's own demonstrated grasp scores on its own demonstration cloud, through the same experts
a synthesis uses (query densities fitted on that cloud, contacts, configuration, collision with the
cloud, pre-grasp clearance). A grasp of a model of several types is ranked by
log L - log L_ref of its type: how close it comes to what its type's demonstration scores on the object
it was taught on. (Raw log L is not comparable: a type whose links touched more points or whose
contact mixtures are sharper scores higher on any object.) The term is one more entry of the grasp's
experts, "type_reference" = -log L_ref, so log_likelihood stays the sum of its experts. A model of one
type adds no term: its grasps and their scores are those of a single-demonstration model.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .. import _core
from ..io import relative_path, resolve_path
from .demonstration import Demonstration
from .experts import collision_expert
from .options import SynthesisOptions
from .serialization import config_dict, config_settings, density_from_json, density_to_json

REFERENCE_EXPERT = _core.TYPE_REFERENCE_TERM  # the experts' key of -log L_ref in a model of several types


@dataclass
class GraspType:
    """One grasp type: its name, synthesiser (contact models and configuration model), the demonstration
    it was learnt from (a path, or None) and log L_ref (see the module's docstring)."""

    name: str
    synthesizer: "_core.GraspSynthesizer"
    demo: str | None = None
    log_reference: float = 0.0

    @property
    def contact_links(self) -> list[str]:
        return [m.link_name for m in self.synthesizer.contact_models]


def parse_demo_spec(spec) -> tuple[str | None, object]:
    """(name or None, demonstration) of a learn() input: a Demonstration, a path, or "name=path" text."""
    if isinstance(spec, Demonstration):
        return None, spec
    if isinstance(spec, str) and "=" in spec:
        name, path = spec.split("=", 1)
        if not name or not _valid_name(name):
            raise ValueError(f"bad grasp type name {name!r} in {spec!r}: letters, digits, '_', '-' and '.' only")
        return name, path
    return None, spec


def _valid_name(name: str) -> bool:
    return all(c.isalnum() or c in "_-." for c in name)


def default_type_name(demo: Demonstration, index: int) -> str:
    """A demonstration's grasp type name: its file's stem, or "type<index>" for one not read from a file."""
    return Path(demo.source).stem if demo.source else f"type{index}"


def check_names(names: list[str]) -> None:
    """Type names are unique (ValueError naming the duplicate otherwise)."""
    seen = set()
    for n in names:
        if n in seen:
            raise ValueError(f"two demonstrations are named {n!r}: give one another name (name=path)")
        seen.add(n)


def check_same_hand(hands: list, demos: list[Demonstration]) -> None:
    """Every demonstration is of the same hand (name, links and joints); ValueError naming the two otherwise."""
    first = hands[0]
    for hand, demo in zip(hands[1:], demos[1:]):
        if (hand.name, hand.link_names, hand.joint_names) != (first.name, first.link_names, first.joint_names):
            raise ValueError(
                f"the demonstrations are of different hands: '{first.name}' ({demos[0].hand_path}) and "
                f"'{hand.name}' ({demo.hand_path}); a model's grasp types must share one hand"
            )


def log_reference(hand, synthesizer, demo: Demonstration, surface, seed: int) -> float:
    """log L_ref: the demonstrated grasp's log-likelihood on its own demonstration cloud (its surface
    features), through the query densities, contacts, configuration, collision and pre-grasp experts of
    a synthesis with the default SynthesisOptions."""
    opts = SynthesisOptions()
    query = synthesizer.query_densities(surface.frames, surface.curvatures, settings=opts.query, seed=seed)
    collision = collision_expert(hand, np.asarray(surface.points), None, opts)
    joints = hand.joints_array(demo.grasp_joints)[None, :]
    ev = synthesizer.evaluate(query, collision, [], demo.T_world_wrist[None, :], joints, opts.sampling.clear_pregrasp)
    value = float(np.asarray(ev.total).ravel()[0])
    if not np.isfinite(value):
        raise ValueError(
            f"the demonstrated grasp of {demo.source or 'the demonstration'} scores log L = {value} on its own "
            "cloud (a hard expert rejects it): its type has no reference score"
        )
    return value


def select_types(types: list[GraspType], names) -> list[GraspType]:
    """The types named (a list, or "a,b" text), in the model's order; None: all. ValueError listing the
    known names for an unknown one."""
    if names is None:
        return list(types)
    if isinstance(names, str):
        names = [n.strip() for n in names.split(",")]
    names = list(names)
    known = [t.name for t in types]
    unknown = [n for n in names if n not in known]
    if unknown or not names:
        what = f"unknown grasp type(s) {', '.join(map(repr, unknown))}" if unknown else "no grasp type given"
        raise ValueError(f"{what}; the model's types: {', '.join(known)}")
    return [t for t in types if t.name in names]


def type_to_json(t: GraspType, base: Path) -> dict:
    """One entry of a model file's "types" (format graspmix.model/2)."""
    cfg = t.synthesizer.config_model
    return {
        "name": t.name,
        "demonstration": relative_path(Path(t.demo), base) if t.demo else None,
        "log_reference": t.log_reference,
        "config_model": {
            "pregrasp": cfg.pregrasp.tolist(),
            "grasp": cfg.grasp.tolist(),
            "settings": config_dict(cfg.settings),
        },
        "contact_models": [
            {"link": m.link_name, "n_points": m.n_points, "density": density_to_json(m.density)}
            for m in t.synthesizer.contact_models
        ],
    }


def type_from_json(entry: dict, hand, hand_path: Path, method: str, path: Path, name: str) -> GraspType:
    """A GraspType from an entry of a model file's "types"."""
    models = _contact_models(entry["contact_models"], hand, hand_path, method, f"{path}: type {name!r}")
    cfg = _config_model(entry["config_model"], hand, path)
    demo = entry.get("demonstration")
    base = path.resolve().parent
    return GraspType(
        name,
        _core.GraspSynthesizer(hand, models, cfg),
        str(resolve_path(demo, base)) if demo else None,
        float(entry.get("log_reference", 0.0)),
    )


def _contact_models(entries: list, hand, hand_path: Path, method: str, where: str) -> list:
    models = []
    for i, entry in enumerate(entries):
        at = f"{where}: contact model {i}"
        link_name = entry.get("link")
        if link_name not in hand.link_names:
            raise ValueError(
                f"{at}: link {link_name!r} is not a link of hand '{hand_path.name}' "
                f"(links: {', '.join(hand.link_names)}); was the model learnt for another hand?"
            )
        density = density_from_json(entry.get("density", {}), at)
        if density.kind != method:
            raise ValueError(f"{at}: a {density.kind} density in a {method} model")
        models.append(_core.ContactModel(hand.link_index(link_name), link_name, density, int(entry.get("n_points", 0))))
    return models


def _config_model(c: dict, hand, path: Path) -> "_core.ConfigModel":
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
