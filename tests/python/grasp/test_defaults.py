"""Python-side defaults: written once (the settings dataclasses), referred to everywhere else, and
compared with the C++ defaults of the same quantities."""

import inspect

from graspmix import _core
from graspmix.cli import build_parser
from graspmix.experiment import Protocol
from graspmix.model import FeatureSettings, GraspModel, LearnSettings, SynthesisOptions


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
    assert (p.n_samples, p.n_optimise, p.query_samples) == (
        SynthesisOptions.n_samples,
        SynthesisOptions.n_optimise,
        SynthesisOptions.query_samples,
    )
    sub = build_parser()._subparsers._group_actions[0].choices
    syn = sub["synthesize"].parse_args(["--cloud", "x.pcd"])
    assert (syn.samples, syn.optimise_top, syn.query_samples) == (
        SynthesisOptions.n_samples,
        SynthesisOptions.n_optimise,
        SynthesisOptions.query_samples,
    )
    learn = sub["learn"].parse_args(["--out", "m.json"])
    assert (learn.components, learn.max_distance) == (LearnSettings.n_components, LearnSettings.max_distance)


def test_agreements_with_cpp():
    a = _core.SynthesisSettings()
    assert (a.n_samples, a.n_optimise, a.clear_pregrasp) == (
        SynthesisOptions.n_samples,
        SynthesisOptions.n_optimise,
        SynthesisOptions.clear_pregrasp,
    )
    assert a.query.n_samples == SynthesisOptions.query_samples
    assert tuple(a.query.kde_bandwidths) == (
        LearnSettings.kde_position_bandwidth,
        LearnSettings.kde_orientation_bandwidth,
    )
    assert (a.annealing.iterations, a.annealing.initial_temperature) == (
        Protocol.annealing_iterations,
        Protocol.initial_temperature,
    )
    c = _core.ContactSettings()
    assert (c.max_distance, c.lambda_, c.min_points) == (
        LearnSettings.max_distance,
        LearnSettings.contact_lambda,
        LearnSettings.min_points,
    )


def test_python_settings_are_the_cpp_defaults():
    """C++ is the single source: every Python setting that C++ also has is the C++ struct's default."""
    col, axis, kde = _core.CollisionSettings(), _core.AxisAlignmentSettings(), _core.KdeSettings()
    assert (
        SynthesisOptions.collision_beta,
        SynthesisOptions.contact_tolerance,
        SynthesisOptions.collision_inside_weight,
    ) == (col.beta, col.contact_tolerance, col.inside_weight)
    assert SynthesisOptions.approach_concentration == axis.concentration
    assert (LearnSettings.kde_position_bandwidth, LearnSettings.kde_orientation_bandwidth) == (
        kde.position_bandwidth,
        kde.orientation_bandwidth,
    )
    assert list(kde.feature_bandwidth) == [LearnSettings.kde_feature_bandwidth]
    assert LearnSettings.n_components == _core.PoseMixture().settings.n_components
    assert (FeatureSettings.voxel_size, FeatureSettings.radius) == (
        _core.SceneSettings().voxel_size,
        _core.SurfaceFeatureSettings().radius,
    )


def test_the_experiment_drops_the_table_it_reports():
    """The experiment's clean-up and the synthesis cut the table at the same height, the protocol's."""
    assert Protocol(objects=["cube_small.urdf"]).min_height == SynthesisOptions.table_clearance
