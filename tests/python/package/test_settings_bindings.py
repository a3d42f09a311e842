"""Settings structs at the Python boundary: each is one class whose defaults are the C++ struct's, and every
keyword API (the old calls) builds the same struct, so its defaults come from there and nowhere else."""

import copy
import pickle

import graspmix
import numpy as np
import pytest
from graspmix import _core

WSG50 = graspmix.data_path("hands", "wsg50.urdf")

SETTINGS = [
    "GmmSettings",
    "KdeSettings",
    "CleanupSettings",
    "SurfaceFeatureSettings",
    "HandLoadSettings",
    "CollisionSettings",
    "ContactSettings",
    "ConfigModelSettings",
    "KinematicFeasibilitySettings",
    "AxisAlignmentSettings",
    "QuerySettings",
    "AnnealingSettings",
    "SamplingSettings",
    "SynthesizerSettings",
    "ClearApproachSettings",
    "ContactQualitySettings",
    "GraspDepthSettings",
    "OccupancySettings",
    "VisibilitySettings",
    "SimSettings",
]


def same(a, b):
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return np.array_equal(a, b)
    return a == b


@pytest.fixture(scope="module")
def wsg():
    return graspmix.Hand.from_urdf(WSG50)


@pytest.fixture(scope="module")
def cube():
    rng = np.random.default_rng(0)
    p = rng.uniform(-0.03, 0.03, size=(3000, 3))
    axis = rng.integers(0, 3, size=len(p))
    p[np.arange(len(p)), axis] = np.sign(rng.normal(size=len(p))) * 0.03  # on the faces
    return p + [0, 0, 0.1]


@pytest.mark.parametrize("name", SETTINGS)
def test_every_settings_class_is_bound_once_with_fields_repr_equality_copy_and_pickle(name):
    cls = getattr(_core, name)
    s = cls()
    assert cls._fields and all(hasattr(s, f) for f in cls._fields)
    # No public name but the fields (graspmix.sim.make_settings lists a class's fields that way).
    public = {n for n in dir(cls) if not n.startswith("_")}
    assert public == set(cls._fields)
    assert repr(s).startswith(f"{name}(") and all(f"{f}=" in repr(s) for f in cls._fields)
    assert s == cls() and not (s != cls())
    for f in (s, copy.copy(s), copy.deepcopy(s), pickle.loads(pickle.dumps(s))):
        assert isinstance(f, cls) and f == s
    # The class documents every field with its default.
    assert all(f in cls.__doc__ for f in cls._fields)


@pytest.mark.parametrize("name", SETTINGS)
def test_keyword_constructor_sets_fields_and_rejects_unknown_names(name):
    cls = getattr(_core, name)
    scalars = [f for f in cls._fields if isinstance(getattr(cls(), f), (bool, int, float))]
    field = next((f for f in scalars if not isinstance(getattr(cls(), f), bool)), scalars[0])
    default = getattr(cls(), field)
    value = (not default) if isinstance(default, bool) else default + 1
    s = cls(**{field: value})
    assert getattr(s, field) == value and s != cls()
    assert pickle.loads(pickle.dumps(s)) == s and copy.copy(s) == s
    with pytest.raises(ValueError, match=r"no_such_setting.*valid: .*" + field):
        cls(no_such_setting=1)


def test_defaults_seen_through_the_keyword_apis_are_the_structs(wsg, cube):
    assert _core.GaussianMixture().settings == _core.GmmSettings()
    assert _core.PoseMixture().settings == _core.PoseMixture.default_settings()
    assert _core.PoseMixture.default_settings().n_components == 2  # the paper's K
    assert _core.PoseKDE().settings == _core.KdeSettings()
    e = _core.CollisionExpert(wsg, cube)
    assert e.settings == _core.CollisionSettings()
    assert e.beta == _core.CollisionSettings().beta and e.plane_margin == _core.CollisionSettings().plane_margin
    cfg = _core.ConfigModel([0.05], [0.02], wsg.joint_limits)
    assert cfg.settings == _core.ConfigModelSettings()
    kde = _core.PoseKDE(position_bandwidth=0.01)
    assert kde.position_bandwidth == 0.01 and kde.orientation_bandwidth == _core.KdeSettings().orientation_bandwidth
    # The values the Python front end and the C++ structs agree on (see the table in the headers).
    assert _core.CollisionSettings().beta == 2000.0
    assert _core.AxisAlignmentSettings().concentration == 20.0


def test_settings_and_keywords_combine_and_keywords_win(wsg, cube):
    base = _core.CollisionSettings(beta=10.0, point_radius=0.001)
    e = _core.CollisionExpert(wsg, cube, settings=base, beta=30.0)
    assert e.beta == 30.0 and e.point_radius == 0.001
    assert base.beta == 10.0  # the caller's settings are not modified
    g = _core.GaussianMixture(settings=_core.GmmSettings(n_components=3, tol=1e-5), n_components=2)
    assert g.settings.n_components == 2 and g.settings.tol == 1e-5
    with pytest.raises(ValueError, match="settings must be a CollisionSettings"):
        _core.CollisionExpert(wsg, cube, settings=_core.GmmSettings())


@pytest.mark.parametrize(
    "call",
    [
        lambda w, c: _core.CollisionExpert(w, c, betta=1.0),
        lambda w, c: _core.GaussianMixture(n_component=2),
        lambda w, c: _core.PoseMixture(seeds=1),
        lambda w, c: _core.PoseKDE(bandwidth=0.1),
        lambda w, c: _core.prepare_cloud(c, voxel=0.01),
        lambda w, c: _core.compute_surface_features(c, radious=0.01),
        lambda w, c: _core.KinematicFeasibilityExpert(w, margin=0.01),
        lambda w, c: _core.AxisAlignmentExpert([0, 0, -1], kappa=3.0),
        lambda w, c: _core.Hand.from_urdf(WSG50, meshes=False),
        lambda w, c: _core.ConfigModel([0.05], [0.02], w.joint_limits, alfa=1.0),
    ],
)
def test_unknown_keyword_is_a_value_error_naming_it(wsg, cube, call):
    with pytest.raises(ValueError, match="unknown setting '.*' \\(valid: "):
        call(wsg, cube)


def test_bad_values_are_value_errors_naming_the_setting():
    with pytest.raises(ValueError, match="seed"):
        _core.GaussianMixture(seed=-1)
    with pytest.raises(ValueError, match="crop_min"):
        _core.CleanupSettings(crop_min=[0, 0])
    with pytest.raises(ValueError, match="orientation"):
        _core.SurfaceFeatureSettings(orientation="inward")


WRONG = {
    bool: ["yes", 2, None, 0.5],
    int: [2**70, -(2**70), "3", 1.5, True, None],
    float: ["0.1", True, [1.0], None],
    str: [5, None, ["surface"]],
}
OPTIONAL_NUMBERS = {("QuerySettings", "link_floor")}


def test_an_optional_number_takes_none_and_finite_numbers_only():
    s = _core.QuerySettings()
    s.link_floor = None
    assert s.link_floor is None and _core.QuerySettings(link_floor=None).link_floor is None
    s.link_floor = np.float64(-7.5)
    assert s.link_floor == -7.5 and type(s.link_floor) is float
    for bad in (float("inf"), float("nan")):
        with pytest.raises(ValueError, match="setting 'link_floor': .* is not valid: expected a finite number or None"):
            s.link_floor = bad
    assert s.link_floor == -7.5


@pytest.mark.parametrize("name", [*SETTINGS, "SegmentationSettings"])
def test_a_field_given_a_value_of_another_kind_is_a_value_error_naming_it(name):
    """By attribute and by keyword: an integer beyond C++'s, text for a number, a bool for a number, a number for
    a flag are ValueErrors naming the field and saying what it takes, never pybind11's TypeError listing C++
    signatures; numpy scalars of the right kind are taken."""
    cls = getattr(_core, name)
    checked = 0
    for field in cls._fields:
        default = getattr(cls(), field)
        kind = type(default) if type(default) in WRONG else None
        if kind is None or field == "seed":  # arrays and seeds have converters of their own (tested elsewhere)
            continue
        # A number that may be unset takes None (QuerySettings.link_floor: None is the paper's product).
        optional = (name, field) in OPTIONAL_NUMBERS
        for value in [v for v in WRONG[kind] if not (optional and v is None)]:
            s = cls()
            with pytest.raises(ValueError, match=f"setting '{field}': .* is not valid: expected ") as e:
                setattr(s, field, value)
            assert "\n" not in str(e.value) and "Supports" not in str(e.value)
            assert getattr(s, field) == default  # unchanged
            with pytest.raises(ValueError, match=f"{name}: setting '{field}'"):
                cls(**{field: value})
        numpy_value = {bool: np.bool_, int: np.int64, float: np.float64}.get(kind, str)(default)
        s = cls()
        setattr(s, field, numpy_value)
        assert getattr(s, field) == default and type(getattr(s, field)) is kind
        checked += 1
    assert checked > 0 or name == "SynthesizerSettings"  # its fields are its parts (below) and its seed


def test_a_nested_settings_field_takes_only_its_class():
    s = _core.SynthesizerSettings()
    with pytest.raises(ValueError, match="setting 'sampling': 5 is not valid: expected a SamplingSettings"):
        s.sampling = 5
    s.sampling = _core.SamplingSettings(n_samples=9)
    assert s.sampling.n_samples == 9
    s.sampling.n_samples = 11  # a part is still returned by reference: its attributes write through
    assert s.sampling.n_samples == 11


def test_old_keyword_calls_give_the_numbers_of_settings_calls(wsg, cube):
    scene_kw = _core.prepare_cloud(cube, voxel_size=0.004, remove_plane=False, seed=3)
    scene_s = _core.prepare_cloud(cube, settings=_core.CleanupSettings(voxel_size=0.004, remove_plane=False, seed=3))
    np.testing.assert_array_equal(scene_kw.points, scene_s.points)
    cropped = _core.prepare_cloud(cube, crop_min=[-1, -1, 0.1], voxel_size=0, remove_outliers=False, remove_plane=False)
    assert np.all(cropped.points[:, 2] >= 0.1) and len(cropped.points) < len(cube)
    f_kw = _core.compute_surface_features(scene_kw.points, 0.012, orientation="centroid", n_threads=1)
    f_s = _core.compute_surface_features(
        scene_kw.points, settings=_core.SurfaceFeatureSettings(radius=0.012, orientation="centroid")
    )
    np.testing.assert_array_equal(f_kw.frames, f_s.frames)
    np.testing.assert_array_equal(f_kw.curvatures, f_s.curvatures)

    X = np.random.default_rng(1).normal(size=(300, 2))
    a = _core.GaussianMixture(n_components=3, seed=0).fit(X)
    b = _core.GaussianMixture(settings=_core.GmmSettings(n_components=3, seed=0)).fit(X)
    np.testing.assert_array_equal(a.means_, b.means_)

    wrists = np.tile([0, 0, 0, 0, 0, 0, 1.0], (5, 1))
    wrists[:, 2] = np.linspace(-0.1, 0.1, 5)
    e_kw = _core.CollisionExpert(wsg, cube, plane=[0, 0, 1, 0], beta=500.0, plane_margin=0.01)
    e_s = _core.CollisionExpert(
        wsg, cube, plane=[0, 0, 1, 0], settings=_core.CollisionSettings(beta=500.0, plane_margin=0.01)
    )
    np.testing.assert_array_equal(e_kw.log_w(wrists, [0.03]), e_s.log_w(wrists, [0.03]))

    ax_kw = _core.AxisAlignmentExpert([0, 0, -1], concentration=3.0)
    ax_s = _core.AxisAlignmentExpert([0, 0, -1], settings=_core.AxisAlignmentSettings(concentration=3.0))
    q = np.zeros((5, 1))
    np.testing.assert_array_equal(ax_kw.log_value(wrists, q), ax_s.log_value(wrists, q))
    assert ax_kw.name == _core.AxisAlignmentSettings().name


def test_nested_settings_write_through():
    s = _core.SynthesizerSettings(sampling=_core.SamplingSettings(n_samples=50), seed=None)
    assert s.seed == 0 and s.query == _core.QuerySettings() and s.sampling.n_samples == 50
    s.query.n_samples = 7  # attributes of a nested settings object write through
    assert s.query.n_samples == 7
    with pytest.raises(ValueError, match="n_samples"):
        _core.SynthesizerSettings(n_samples=50)  # the sampling's fields are in its part


def test_results_are_attribute_classes():
    model = graspmix.GraspModel.load(graspmix.default_model_path("gmm"))
    cloud = _core.load_cloud(str(graspmix.data_path("mug.pcd"))).points
    surface, _ = model.features.surface(cloud, remove_plane=True)
    collision = _core.CollisionExpert(model.hand, surface.points)
    settings = _core.SynthesizerSettings(sampling=_core.SamplingSettings(n_samples=20, n_optimise=1))
    res = model.synthesizer.synthesize(surface.frames, surface.curvatures, collision, None, settings, seed=4)
    g = res.grasps[0]
    assert isinstance(g, _core.Grasp) and len(g.T_world_wrist) == 7
    assert res.timing.total >= res.timing.query + res.timing.sampling + res.timing.optimisation - 1e-9
    for r in (g, res.timing):
        with pytest.raises(TypeError):
            r["log_likelihood"]  # no dict-style reading
    d = _core.contact_data(model.hand, 1, np.r_[0, 0, 0.3, 0, 0, 0, 1.0], [0.0], surface.frames, surface.curvatures)
    assert isinstance(d, _core.ContactData) and len(d.weights) == len(d)
