"""SynthesisOptions: one frozen object of the bound C++ settings structs; its changes, its file form, its checks,
and that each part reaches the synthesis."""

import copy
import dataclasses
import json
import pickle

import graspmix
import numpy as np
import pytest
from graspmix import SynthesisOptions
from graspmix.io.checks import MAX_GRASPS, MAX_SAMPLES
from graspmix.model.options import LATER_FIELDS, LATER_PARTS, PARTS, options_field_names

FAST = {"sampling.n_samples": 30, "sampling.n_optimise": 1, "annealing.iterations": 10}


def test_the_options_are_frozen_and_own_their_parts():
    sampling = graspmix.SamplingSettings(n_samples=77)
    o = SynthesisOptions(sampling=sampling)
    sampling.n_samples = 5  # the caller's struct changes later; the options' copy does not
    assert o.sampling.n_samples == 77
    with pytest.raises(dataclasses.FrozenInstanceError):
        o.sampling = graspmix.SamplingSettings()
    changed = o.updated({"sampling.n_samples": 12})
    assert (o.sampling.n_samples, changed.sampling.n_samples) == (77, 12)
    assert dataclasses.replace(o, approach=None).approach is None and o.approach is not None


def test_updated_reaches_every_field_and_round_trips_through_json():
    names = options_field_names()
    assert len(names) == len(set(names)) > 50 and "seed" in names
    assert {n.split(".")[0] for n in names} == set(PARTS) | {"seed"}
    o = SynthesisOptions().updated(
        {"query.kde.position_bandwidth": 0.02, "approach.hand_axis": [1, 0, 0], "collision.model": "occupancy"}
    )
    assert o.query.kde.position_bandwidth == 0.02 and list(o.approach.hand_axis) == [1, 0, 0]
    for options in (o, SynthesisOptions.paper(), SynthesisOptions(seed=9, contact_quality=None)):
        text = json.dumps(options.to_dict())
        assert SynthesisOptions.from_dict(json.loads(text)) == options
        assert pickle.loads(pickle.dumps(options)) == options == copy.deepcopy(options)
    # A part left out of a file keeps its defaults; null turns an optional expert off.
    partial = SynthesisOptions.from_dict({"sampling": {"n_samples": 9}, "approach": None})
    assert partial == SynthesisOptions().updated({"sampling.n_samples": 9, "approach": None})


def test_a_stored_run_made_before_a_later_part_existed_ran_without_it():
    stored = SynthesisOptions().to_dict()
    assert SynthesisOptions.from_stored(stored) == SynthesisOptions()  # written whole: read as written
    for name in LATER_PARTS:
        old = {k: v for k, v in stored.items() if k != name}
        assert getattr(SynthesisOptions.from_stored(old), name) is None
        assert getattr(SynthesisOptions.from_dict(old), name) is not None  # a hand-written file: its default
    with pytest.raises(ValueError, match="expected an object of parts"):
        SynthesisOptions.from_stored([1])


def test_a_stored_part_without_a_later_field_ran_with_its_value_from_before():
    stored = SynthesisOptions().to_dict()
    for (part, name), before in LATER_FIELDS.items():
        assert getattr(getattr(SynthesisOptions(), part), name) != before  # the default changed the behaviour
        old = {**stored, part: {k: v for k, v in stored[part].items() if k != name}}
        assert getattr(getattr(SynthesisOptions.from_stored(old), part), name) == before
        assert getattr(getattr(SynthesisOptions.from_dict(old), part), name) != before  # a hand-written file


def test_oversampling_is_bounded_and_off_in_the_papers_synthesis():
    assert SynthesisOptions.paper().sampling.oversample == 1
    for bad in (0, graspmix._core.MAX_OVERSAMPLE + 1):
        with pytest.raises(ValueError, match="sampling.oversample"):
            SynthesisOptions().updated({"sampling.oversample": bad})
    with pytest.raises(ValueError, match=r"n_samples \* sampling.oversample"):
        SynthesisOptions().updated({"sampling.n_samples": 60_000, "sampling.oversample": 20})


def test_switching_an_expert_on_keeps_its_settings_and_a_field_turns_it_on():
    o = SynthesisOptions().updated({"approach.stand_off": 0.2})
    assert o.updated({"approach": True}).approach.stand_off == 0.2
    off = o.updated({"approach": False})
    assert off.approach is None
    assert off.updated({"approach.step": 0.01}).approach == graspmix.ClearApproachSettings(step=0.01)
    with pytest.raises(ValueError, match="sampling"):
        SynthesisOptions().updated({"sampling": None})  # not optional


def test_one_seed_seeds_everything_and_a_nested_mapping_keeps_the_fields_it_does_not_name():
    o = SynthesisOptions().updated({"seed": 5})
    assert o.segmentation.seed == 5 and o.updated({"seed": 6}).segmentation.seed == 6
    assert o.updated({"segmentation.seed": 9}).segmentation.seed == 5  # derived from seed, whatever is set
    kde = SynthesisOptions().updated({"query.kde.orientation_bandwidth": 0.3})
    both = kde.updated({"query.kde": {"position_bandwidth": 0.01}})
    assert (both.query.kde.position_bandwidth, both.query.kde.orientation_bandwidth) == (0.01, 0.3)


def test_repr_names_what_differs_from_the_defaults():
    assert repr(SynthesisOptions()) == "SynthesisOptions()"
    r = repr(SynthesisOptions(seed=3).updated({"contact_quality": None}))
    assert r == "SynthesisOptions(contact_quality=None, seed=3)"


@pytest.mark.parametrize(
    "changes, named",
    [
        ({"bogus": 1}, "bogus"),
        ({"sampling.bogus": 1}, "sampling.bogus"),
        ({"sampling.n_samples": 0}, "sampling.n_samples"),
        ({"sampling.n_samples": "many"}, "sampling.n_samples"),
        ({"sampling.n_samples": 2**40}, "sampling.n_samples"),
        ({"query.n_components": 20, "query.n_samples": 10}, "query.n_components"),
        ({"collision.beta": float("nan")}, "collision.beta"),
        ({"collision.model": "voxels"}, "collision.model"),
        ({"approach.stand_off": -1.0}, "approach.stand_off"),
        ({"approach.hand_axis": [0, 1]}, "approach.hand_axis"),
        ({"contact_quality.friction": 0.0}, "contact_quality.friction"),
        ({"seed": -1}, "seed"),
    ],
)
def test_bad_options_are_value_errors_naming_the_field(changes, named):
    with pytest.raises(ValueError, match=named.replace(".", r"\.")) as e:
        SynthesisOptions().updated(changes)
    assert "\n" not in str(e.value) and "C++" not in str(e.value)


def test_grasp_samples_stop_where_memory_would():
    """Every sampled grasp is returned with its frames (about 7-13 KB each, measured: 20,000 on the mug took 144 MB
    more): a million a target could take ~10 GB, so the bound is 100,000 (MAX_GRASPS), the query's samples keep
    theirs."""
    assert SynthesisOptions().updated({"sampling.n_samples": MAX_GRASPS}).sampling.n_samples == MAX_GRASPS
    with pytest.raises(ValueError, match=r"sampling\.n_samples.*100000"):
        SynthesisOptions().updated({"sampling.n_samples": MAX_GRASPS + 1})
    assert SynthesisOptions().updated({"query.n_samples": MAX_SAMPLES}).query.n_samples == MAX_SAMPLES


def test_bad_parts_and_files_are_value_errors():
    with pytest.raises(ValueError, match="sampling"):
        SynthesisOptions(sampling=graspmix.QuerySettings())
    with pytest.raises(ValueError, match="unknown part"):
        SynthesisOptions.from_dict({"sampler": {}})
    with pytest.raises(ValueError, match="cannot be null"):
        SynthesisOptions.from_dict({"query": None})
    model = graspmix.GraspModel.load(graspmix.default_model_path("gmm"))
    with pytest.raises(ValueError, match="options must be a graspmix.SynthesisOptions"):
        model.synthesize(graspmix.data_path("mug.pcd"), {"n_samples": 5})
    with pytest.raises(ValueError, match="voxel_size"):
        model.synthesize(graspmix.data_path("mug.pcd"), SynthesisOptions().updated({"segmentation.voxel_size": 0.01}))


@pytest.fixture(scope="module")
def gmm():
    return graspmix.GraspModel.load(graspmix.default_model_path("gmm"))


def test_each_part_reaches_the_synthesis(gmm):
    """Options that must change what the synthesis does, each against the same synthesis without it."""
    cloud = graspmix.data_path("mug.pcd")
    base = SynthesisOptions().updated(FAST)
    ref = gmm.synthesize(cloud, base)
    assert len(ref) == 30 and set(ref.best().experts) >= {"clear_approach", "contact_quality", "kinematic"}
    # sampling: how many grasps come back; max_sampling_rounds bounds the rejection sampling's batches.
    assert len(gmm.synthesize(cloud, base.updated({"sampling.n_samples": 12}))) == 12
    one_round = gmm.synthesize(cloud, base.updated({"sampling.max_sampling_rounds": 1}))
    assert one_round.rejected <= 30 * base.sampling.oversample < ref.rejected
    # oversampling: twice as many drawn by default (once in the paper's preset), as many returned
    assert base.sampling.oversample == 2 and SynthesisOptions.paper().sampling.oversample == 1
    once = gmm.synthesize(cloud, base.updated({"sampling.oversample": 1}))
    assert len(once) == 30 and once.evaluations < ref.evaluations
    # the top-down seeds (on by default, off in the paper's preset): scored with the drawn grasps, so more
    # evaluations, a grasp straight down among those returned, and the count still n_samples.
    assert not SynthesisOptions.paper().sampling.topdown_seeds and base.sampling.topdown_seeds
    unseeded = gmm.synthesize(cloud, base.updated({"sampling.topdown_seeds": False}))
    assert len(unseeded) == 30 and unseeded.evaluations < ref.evaluations
    down = [np.asarray(g.approach) @ [0, 0, -1] for g in ref]
    assert max(down) > 1 - 1e-9 and max(np.asarray(g.approach) @ [0, 0, -1] for g in unseeded) < 1 - 1e-6
    # the floor under each link's contact term (-20 nats by default, none in the paper's preset): no contact term
    # below it, while without it a link's term on the mug falls far lower.
    floor = base.query.link_floor
    assert floor == -20.0 and SynthesisOptions.paper().query.link_floor is None
    terms = [v for g in ref for k, v in g.experts.items() if k.startswith("contact/") and np.isfinite(v)]
    bare_terms = [
        v
        for g in gmm.synthesize(cloud, base.updated({"query.link_floor": None}))
        for k, v in g.experts.items()
        if k.startswith("contact/") and np.isfinite(v)
    ]
    assert min(terms) >= floor and min(bare_terms) < floor - 10
    # experts off: their terms leave the table.
    bare = gmm.synthesize(cloud, base.updated({"approach": None, "contact_quality": None, "kinematic": None}))
    assert not set(bare.best().experts) & {"clear_approach", "contact_quality", "kinematic"}

    # contact quality's friction: the same samples (it is soft and scored last; no annealing; no top-down seeds,
    # whose best are kept in place of the worst drawn grasps by a score that contact quality is part of), and a wider
    # cone forgives more, so no grasp scores worse on it and some score better (NaN: rejected before it was scored).
    def quality(friction):
        changes = {"contact_quality.friction": friction, "sampling.optimise": False, "sampling.topdown_seeds": False}
        g = gmm.synthesize(cloud, base.updated(changes))
        return {tuple(x.T_world_wrist): x.experts["contact_quality"] for x in g}

    loose, tight = quality(5.0), quality(0.05)
    assert loose.keys() == tight.keys()
    scored = [k for k in loose if np.isfinite(loose[k])]
    assert scored and all(loose[k] >= tight[k] for k in scored) and any(loose[k] > tight[k] for k in scored)
    # the seed: the same seed the same grasps, another seed others.
    again = gmm.synthesize(cloud, base)
    assert [g.T_world_wrist for g in again] == [g.T_world_wrist for g in ref]
    assert gmm.synthesize(cloud, base.updated({"seed": 1})).best().T_world_wrist != ref.best().T_world_wrist
    # the approach axis' concentration: the term is concentration * (cos - 1), checked against the pose.
    axis = np.array([1.0, 0.0, 0.0])
    steep = gmm.synthesize(cloud, base.updated({"axis_alignment.concentration": 7.0}), approach_axis=axis)
    from scipy.spatial.transform import Rotation

    best = steep.best()
    cos = Rotation.from_quat(best.T_world_wrist[3:]).apply([0, 0, 1]) @ axis
    assert best.experts["approach_axis"] == pytest.approx(7.0 * (cos - 1.0), abs=1e-9)


def test_a_cloud_in_the_cameras_frame_gives_the_same_grasps_in_the_world(gmm):
    """camera_pose: the points mapped into the world by the pose give the grasps of the world cloud."""
    from scipy.spatial.transform import Rotation

    points = graspmix.io.load_points(graspmix.data_path("mug.pcd"))[0]
    pose = np.r_[0.1, -0.2, 0.6, Rotation.from_euler("xyz", [2.8, 0.1, 0.3]).as_quat()]
    R, t = Rotation.from_quat(pose[3:]), pose[:3]
    in_camera = R.inv().apply(points - t)
    opts = SynthesisOptions().updated(FAST)
    world = gmm.synthesize(points, opts, viewpoints=t)
    framed = gmm.synthesize(in_camera, opts, camera_pose=pose)
    np.testing.assert_allclose(framed.best().T_world_wrist[:3], world.best().T_world_wrist[:3], atol=2e-3)
    with pytest.raises(ValueError, match="unit quaternion"):
        gmm.synthesize(in_camera, opts, camera_pose=[0, 0, 0, 0, 0, 0, 2])
