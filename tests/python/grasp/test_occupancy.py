"""The occupancy map and the occupancy collision model on a box rendered by pybullet from one camera (the
renderer's ground truth: the box's pose and size), synthesis with collision="occupancy", and bad input."""

import graspmix
import numpy as np
import pytest
from graspmix import SynthesisOptions, _core
from graspmix.perception import segment_scene
from graspmix.sim.acquisition import AcquisitionSettings, Camera, acquire

EYE = (0.5, 0.1, 0.45)  # sees the box's +x face (and its top)
SIZE = (0.06, 0.06, 0.10)  # m
# A finger: a free box link 2 x 4 x 6 cm centred on its frame (2 cm along x, the approach).
FINGER = """<robot name="finger"><link name="finger"><collision><geometry><box size="0.02 0.04 0.06"/></geometry>
</collision></link><link name="tip"/><joint name="slide" type="prismatic"><parent link="finger"/><child link="tip"/>
<axis xyz="0 0 1"/><limit lower="0" upper="0.1" effort="1" velocity="1"/></joint></robot>"""


@pytest.fixture(scope="module")
def seen(box_urdf):
    path = box_urdf(SIZE)
    acq = acquire(path, seed=0, settings=AcquisitionSettings(cameras=[Camera(eye=EYE)], keep="scene"))
    scene = segment_scene(acq.points, acq.viewpoints)
    occ = _core.OccupancyMap(acq.points, acq.viewpoints, scene.points, scene.plane)
    return acq, scene, occ, np.asarray(acq.object_pose[:3]), path


def test_one_camera_sees_free_in_front_and_leaves_the_back_unknown(seen):
    _, _, occ, c, _ = seen
    free, occupied, unknown = 0, 1, 2
    assert occ.state([c])[0] == unknown  # the box's inside: no ray reached it
    assert occ.state([c + [0.06, 0, 0]])[0] == free  # 3 cm in front of the seen face
    assert occ.state([c + [0.03 + 0.001, 0, 0]])[0] == occupied  # the seen face
    assert occ.state([c - [0.06, 0, 0]])[0] == unknown  # 3 cm behind the hidden face: the shadow
    assert occ.state([c + [0.5, 0, 0]])[0] == free  # outside the mapped region
    assert occ.plane is not None and occ.plane[2] > 0.999  # towards the camera
    s = occ.stats
    assert s["n_free"] + s["n_occupied"] + s["n_unknown"] == np.prod(occ.dims)


def _charges(expert, xs, c, zs=None):
    zs = np.full(len(xs), c[2]) if zs is None else zs
    wrists = np.array([[x, c[1], z, 0, 0, 0, 1] for x, z in zip(xs, zs)])
    return expert.evaluate_batch(wrists, np.zeros((len(xs), 1))).cloud_depth[:, 0]


def test_a_finger_inside_costs_more_than_one_grazing_and_the_charge_grows_with_depth(seen):
    _, scene, occ, c, _ = seen
    finger = _core.Hand.from_urdf_string(FINGER, ".")
    occupancy = _core.CollisionExpert(finger, scene.points, scene.plane, occupancy=occ)
    surface = _core.CollisionExpert(finger, scene.points, scene.plane, settings=_core.CollisionSettings(volume=False))
    assert occupancy.model == "occupancy" and surface.model == "surface"
    # Down into the seen top face (the finger is 6 cm tall): 0 is touching.
    top = c[2] + SIZE[2] / 2
    depths = np.array([0.0, 0.01, 0.02, 0.04])
    charge = _charges(occupancy, np.full(4, c[0]), c, top + 0.03 - depths)
    assert charge[0] == 0.0
    assert np.all(np.diff(charge) > 0)
    face = c[0] + SIZE[0] / 2  # the seen side face
    inside = _charges(occupancy, [c[0]], c)[0]  # the finger wholly inside the box
    assert inside >= charge[-1] and inside > 10 * 0.003
    assert _charges(surface, [c[0]], c)[0] == 0.0  # the surface model sees no point inside it
    # Behind the box from this camera: charged by the occupancy model, invisible to the surface model.
    behind = c[0] - SIZE[0] / 2 - 0.02
    assert _charges(occupancy, [behind], c)[0] > 0.0
    assert _charges(surface, [behind], c)[0] == 0.0
    # The same finger in the space the camera saw free is not.
    assert _charges(occupancy, [face + 0.03], c)[0] == 0.0


def test_synthesis_with_the_occupancy_model(seen):
    acq, *_ = seen
    model = graspmix.GraspModel.load(graspmix.default_model_path())
    opts = SynthesisOptions().updated(
        {"collision.model": "occupancy", "sampling.n_samples": 40, "sampling.n_optimise": 1}
    )
    grasps = model.synthesize(acq.points, opts, viewpoints=acq.viewpoints)
    assert len(grasps) > 0 and grasps.timing["occupancy"] > 0
    # The grasps the hard experts passed rank first; rejected samples fill up the rest (log L = -inf).
    finite = [bool(np.isfinite(g.log_likelihood)) for g in grasps]
    assert finite[0] and finite == sorted(finite, reverse=True)
    assert SynthesisOptions().collision.model == _core.CollisionSettings().model == "surface"


def test_bad_input_is_a_value_error(seen):
    acq, scene, _, c, _ = seen
    model = graspmix.GraspModel.load(graspmix.default_model_path())
    occupancy = SynthesisOptions().updated({"collision.model": "occupancy"})
    with pytest.raises(ValueError, match="collision.model"):
        SynthesisOptions().updated({"collision.model": "voxels"})
    with pytest.raises(ValueError, match="occupancy.resolution"):
        occupancy.updated({"occupancy.resolution": 0.0})
    with pytest.raises(ValueError, match="viewpoints"):
        model.synthesize(acq.points, occupancy)  # an array has no VIEWPOINT
    with pytest.raises(ValueError, match="resolution"):
        _core.OccupancyMap(acq.points, acq.viewpoints, scene.points, resolution=-0.005)
    with pytest.raises(ValueError, match="NaN"):
        _core.OccupancyMap(acq.points, [np.nan, 0, 1], scene.points)
    with pytest.raises(ValueError, match="inside the objects' bounding box"):
        _core.OccupancyMap(acq.points, c, scene.points)  # a camera inside the box
    with pytest.raises(ValueError, match="OccupancyMap"):
        _core.CollisionExpert(model.hand, scene.points, model="occupancy")


def _approach_values(collision, config, wrists, stand_off):
    e = _core.ClearApproachExpert(collision, config, stand_off=stand_off, hand_axis=(1, 0, 0))
    return e.log_value(np.asarray(wrists, float), np.zeros((len(wrists), 1)))


def test_a_clear_approach_must_keep_out_of_the_unseen_shadow(seen):
    """The finger's approach axis is its x: it approaches a side face of the box along the face's inward normal.
    From the seen side it backs off into space the camera saw free; from the hidden side into the shadow."""
    _, scene, occ, c, _ = seen
    finger = _core.Hand.from_urdf_string(FINGER, ".")
    config = _core.ConfigModel([0.0], [0.0], finger.joint_limits)
    occupancy = _core.CollisionExpert(finger, scene.points, scene.plane, occupancy=occ)
    surface = _core.CollisionExpert(finger, scene.points, scene.plane)
    half = SIZE[0] / 2
    # 5 mm off the seen +x face, approaching along -x (rotation pi about z): the path runs to the camera.
    front = [c[0] + half + 0.015, c[1], c[2], 0, 0, 1, 0]
    # 5 mm off the hidden -x face, approaching along +x: the path runs through the shadow behind the box.
    back = [c[0] - half - 0.015, c[1], c[2], 0, 0, 0, 1]
    assert list(_approach_values(occupancy, config, [front], 0.10)) == [0.0]
    assert list(_approach_values(occupancy, config, [back], 0.10)) == [-np.inf]
    # The surface model sees no point behind the box: the path from behind is clear to it.
    assert list(_approach_values(surface, config, [front, back], 0.10)) == [0.0, 0.0]
    # Approaching the seen face from inside the box: the pre-grasp is clear, a path of 2 cm or more is not.
    inside = [c[0] + half + 0.015, c[1], c[2], 0, 0, 0, 1]
    for collision in (occupancy, surface):
        assert list(_approach_values(collision, config, [inside], 0.0)) == [0.0]
        assert list(_approach_values(collision, config, [inside], 0.02)) == [-np.inf]


def test_clear_approach_bad_settings_are_value_errors(seen):
    _, scene, _, _, _ = seen
    model = graspmix.GraspModel.load(graspmix.default_model_path())
    collision = _core.CollisionExpert(model.hand, scene.points, scene.plane)
    config = model.synthesizer.config_model
    with pytest.raises(ValueError, match="stand_off"):
        _core.ClearApproachExpert(collision, config, stand_off=-0.01)
    with pytest.raises(ValueError, match="step"):
        _core.ClearApproachExpert(collision, config, step=0.0)
    with pytest.raises(ValueError, match="stand_off"):
        model.synthesize(scene.points, SynthesisOptions().updated({"approach.stand_off": -0.05}))


def test_an_object_only_cloud_under_the_occupancy_model_rejects_every_grasp_and_says_why(box_urdf, tmp_path, capsys):
    """Without the table's rays the space beside the object is unseen (solid): no open hand fits. The CLI still
    writes the least bad grasps and says on stderr why none passed."""
    from graspmix import cli

    acq = acquire(box_urdf(SIZE), seed=0, settings=AcquisitionSettings(cameras=[Camera(eye=EYE)], keep="object"))
    np.save(tmp_path / "box.npy", acq.points)
    # (no completion: its back face would draw a few samples away from the object, into space the map calls free)
    argv = ["synthesize", "--cloud", str(tmp_path / "box.npy"), "--collision", "occupancy", "--plane", "0,0,1,0"]
    argv += ["--no-completion"]
    argv += [f"--viewpoint={','.join(str(x) for x in EYE)}", "--samples", "40", "--out", str(tmp_path / "g.json")]
    assert cli.main(argv) == 0
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "no sampled grasp passed the hard experts" in err and "clear_approach" in err
    grasps = graspmix.GraspSet.load(tmp_path / "g.json")
    assert len(grasps) == 40 and not any(np.isfinite(g.log_likelihood) for g in grasps)


def test_an_expert_without_a_map_is_the_surface_model_under_the_occupancy_option(seen):
    """A scene's neighbours' expert is built from points alone, also when the synthesis runs the occupancy model:
    collision_expert without a map gives the surface model (it raised before, failing every scene of two objects)."""
    from graspmix.model.experts import collision_expert

    _, scene, occ, _, _ = seen
    opts = SynthesisOptions(collision=_core.CollisionSettings(model="occupancy"))
    hand = graspmix.Hand.from_urdf(graspmix.data_path("hands", "wsg50.urdf"))
    assert collision_expert(hand, scene.points, None, opts).model == "surface"
    assert collision_expert(hand, scene.points, scene.plane, opts, occ).model == "occupancy"
