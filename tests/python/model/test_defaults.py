"""Defaults are written once: the synthesis' in the C++ settings structs (SynthesisOptions is composed of them),
learning's in LearnSettings; the API, the command line, the experiment's and the clutter protocol's defaults are
those, and the Python settings that C++ also has agree with it."""

import inspect

from graspmix import _core
from graspmix.cli import build_parser
from graspmix.cli.synthesis_flags import synthesis_options
from graspmix.clutter.protocol import ClutterProtocol
from graspmix.experiment import Protocol
from graspmix.model import FeatureScale, GraspModel, LearnSettings, SynthesisOptions
from graspmix.model.options import PARTS


def _defaults(fn):
    return {k: p.default for k, p in inspect.signature(fn).parameters.items() if p.default is not p.empty}


def test_synthesis_options_are_the_cpp_structs_defaults():
    o = SynthesisOptions()
    for name, (cls, _) in PARTS.items():
        assert getattr(o, name) == cls(), name
    assert o.seed == 0
    # synthesize() restates no setting: everything but the input, the views, the target and the task is the options'.
    syn = _defaults(GraspModel.synthesize)
    assert syn["options"] is None
    inputs = {"cloud", "depth", "intrinsics", "depth_scale", "camera_pose", "viewpoints"}
    assert set(syn) == inputs | {"options", "target", "plane", "approach_axis", "reachable", "experts", "types"}


def test_learn_keyword_defaults_are_the_settings_defaults():
    learn = _defaults(GraspModel.learn)
    for k, v in vars(LearnSettings()).items():
        assert learn[k] == v, k
    assert (learn["voxel_size"], learn["radius"]) == (FeatureScale.voxel_size, FeatureScale.radius)


def test_cli_and_protocols_default_to_the_same_options():
    sub = build_parser()._subparsers._group_actions[0].choices
    assert synthesis_options(sub["synthesize"].parse_args(["--cloud", "x.pcd"])) == SynthesisOptions()
    assert Protocol.preset("defaults").synthesis == SynthesisOptions()
    assert Protocol(objects=["cube_small.urdf"]).synthesis == SynthesisOptions()
    assert ClutterProtocol().synthesis == SynthesisOptions()
    learn = sub["learn"].parse_args(["--out", "m.json"])
    assert (learn.components, learn.max_distance) == (LearnSettings.n_components, LearnSettings.max_distance)


def test_python_settings_that_cpp_also_has_are_its_defaults():
    c = _core.ContactSettings()
    assert (c.max_distance, c.lambda_, c.min_points) == (
        LearnSettings.max_distance,
        LearnSettings.contact_lambda,
        LearnSettings.min_points,
    )
    kde = _core.KdeSettings()
    assert (LearnSettings.kde_position_bandwidth, LearnSettings.kde_orientation_bandwidth) == (
        kde.position_bandwidth,
        kde.orientation_bandwidth,
    )
    assert SynthesisOptions().query.kde == kde  # KDE query kernels default to the contact kernels' defaults
    assert list(kde.feature_bandwidth) == [LearnSettings.kde_feature_bandwidth]
    assert LearnSettings.n_components == _core.PoseMixture().settings.n_components
    assert (FeatureScale.voxel_size, FeatureScale.radius) == (
        _core.CleanupSettings().voxel_size,
        _core.SurfaceFeatureSettings().radius,
    )
    assert SynthesisOptions().segmentation.voxel_size == FeatureScale.voxel_size
