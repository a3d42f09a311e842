"""Python-side defaults: written once (the settings dataclasses), referred to everywhere else, and
compared with the C++ defaults of the same quantities."""
import inspect
import re

import pytest

import graspmix
from graspmix import _core
from graspmix.cli import build_parser
from graspmix.experiment import Protocol
from graspmix.model import DEFAULT_DISAGREEMENTS, FeatureSettings, GraspModel, LearnSettings, SynthesisOptions


def _defaults(fn):
    return {k: p.default for k, p in inspect.signature(fn).parameters.items() if p.default is not p.empty}


def test_keyword_defaults_are_the_settings_defaults():
    syn = _defaults(GraspModel.synthesize)
    for k, v in vars(SynthesisOptions()).items():
        assert syn[k] == v, k
    learn = _defaults(GraspModel.learn)
    for k, v in vars(LearnSettings()).items():
        assert learn[k] == v, k
    assert (learn["voxel_size"], learn["radius"]) == (FeatureSettings.voxel_size, FeatureSettings.radius)


def test_cli_and_protocol_defaults_are_the_settings_defaults():
    p = Protocol(objects=["cube_small.urdf"])
    assert (p.n_samples, p.n_optimise, p.query_samples) == (SynthesisOptions.n_samples, SynthesisOptions.n_optimise,
                                                             SynthesisOptions.query_samples)
    sub = build_parser()._subparsers._group_actions[0].choices
    syn = sub["synthesize"].parse_args(["--cloud", "x.pcd"])
    assert (syn.samples, syn.optimise_top, syn.query_samples) == (SynthesisOptions.n_samples,
                                                                   SynthesisOptions.n_optimise,
                                                                   SynthesisOptions.query_samples)
    learn = sub["learn"].parse_args(["--out", "m.json"])
    assert (learn.components, learn.max_distance) == (LearnSettings.n_components, LearnSettings.max_distance)


def test_agreements_with_cpp():
    a = _core.SynthesisSettings()
    assert (a.n_samples, a.n_optimise, a.clear_pregrasp) == (SynthesisOptions.n_samples, SynthesisOptions.n_optimise,
                                                             SynthesisOptions.clear_pregrasp)
    assert a.query.n_samples == SynthesisOptions.query_samples
    assert tuple(a.query.kde_bandwidths) == (LearnSettings.kde_position_bandwidth, LearnSettings.kde_orientation_bandwidth)
    assert (a.annealing.iterations, a.annealing.initial_temperature) == (Protocol.annealing_iterations,
                                                                         Protocol.initial_temperature)
    c = _core.ContactSettings()
    assert (c.max_distance, c.lambda_, c.min_points) == (LearnSettings.max_distance, LearnSettings.contact_lambda,
                                                         LearnSettings.min_points)


def _binding_default(cls, arg: str) -> float:
    """The default of a keyword argument of a bound constructor, from pybind11's signature text."""
    m = re.search(rf"\b{arg}: [^=,)]+ = ([^,)]+)", cls.__init__.__doc__)
    assert m, f"{cls.__name__} has no default for {arg}"
    return float(m.group(1))


def test_the_listed_disagreements_are_the_real_ones():
    """The C++ values of DEFAULT_DISAGREEMENTS, read from the bindings: if either side changes, this list
    must be updated (C++ is to become the single source)."""
    cpp = {"SynthesisOptions.collision_beta": _binding_default(_core.CollisionExpert, "beta"),
           "SynthesisOptions.contact_tolerance": _binding_default(_core.CollisionExpert, "contact_tolerance"),
           "SynthesisOptions.approach_concentration": _binding_default(_core.AxisAlignmentExpert, "concentration"),
           "LearnSettings.n_components": _binding_default(_core.GaussianMixture, "n_components")}
    assert sorted(cpp) == sorted(name for name, *_ in DEFAULT_DISAGREEMENTS)
    for name, py, cxx, _ in DEFAULT_DISAGREEMENTS:
        owner, field = name.split(".")
        assert getattr(getattr(graspmix.model, owner), field) == py, name
        assert cpp[name] == pytest.approx(cxx) and py != cxx, name
    # PoseMixture, which learning uses, has the Python default.
    assert _binding_default(_core.PoseMixture, "n_components") == LearnSettings.n_components
