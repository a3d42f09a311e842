"""Grasp: the one definition of a grasps.json entry, read by its attributes; it round-trips the file's
entries exactly."""

import json

import graspmix
import numpy as np
import pytest
from graspmix.model import Grasp, GraspSet, grasp_by_rank, load_grasps
from graspmix.model.grasp_frames import FRAME_KEYS

# An entry as GraspSet wrote it before Grasp existed (and as grasps.json holds it).
OLD_ENTRY = {
    "rank": 1,
    "T_world_wrist": [0.01, -0.02, 0.2, 1.0, 0.0, 0.0, 0.0],
    "pregrasp_joints": {"finger_left_joint": 0.05},
    "grasp_joints": {"finger_left_joint": 0.03},
    "log_likelihood": -12.5,
    "optimised": True,
    "experts": {"collision": 0.0, "config": -1.5, "pregrasp_clear": 0.0, "contact/palm": -3.0, "kinematic": 0.0},
}


def test_round_trip_is_the_old_layout():
    g = Grasp.from_dict(OLD_ENTRY)
    assert g.to_dict() == OLD_ENTRY
    assert list(g.to_dict()) == list(OLD_ENTRY)  # same key order as before
    assert json.dumps(g.to_dict()) == json.dumps(OLD_ENTRY)
    assert Grasp.from_dict(g.to_dict()) == g
    # Fields a newer writer adds survive, after the known ones.
    newer = dict(OLD_ENTRY, object="mug", tcp=[0, 0, 0.1])
    assert Grasp.from_dict(newer).to_dict() == newer
    # Only what execution needs, in the layout of the experiment's CSV column.
    assert g.to_dict(execution_only=True) == {
        k: OLD_ENTRY[k] for k in ("T_world_wrist", "pregrasp_joints", "grasp_joints")
    }


def test_fields_and_what_a_bare_grasp_writes():
    g = Grasp.from_dict(OLD_ENTRY)
    assert g.T_world_wrist == OLD_ENTRY["T_world_wrist"] and g.experts["config"] == -1.5 and g.rank == 1
    assert g.extra == {} and g.object is None
    bare = Grasp([0, 0, 0, 0, 0, 0, 1], {"j": 0.0}, {"j": 0.0})
    assert bare.rank is None and bare.log_likelihood is None
    assert list(bare.to_dict()) == ["T_world_wrist", "pregrasp_joints", "grasp_joints"]
    with pytest.raises(ValueError, match="no 'grasp_joints'"):
        Grasp.from_dict({"T_world_wrist": [0] * 7, "pregrasp_joints": {}})


def test_synthesised_grasps_are_grasps_in_the_files_layout(tmp_path):
    model = graspmix.GraspModel.load(graspmix.default_model_path("gmm"))
    grasps = model.synthesize(
        graspmix.data_path("mug.pcd"),
        graspmix.SynthesisOptions().updated({"sampling.n_samples": 30, "sampling.optimise": False}),
    )
    best = grasps.best()
    assert isinstance(best, Grasp) and best.rank == 1
    # The old layout, then the object it is on, its grasp type and what a robot stack needs.
    assert list(best.to_dict()) == [*OLD_ENTRY, "object", "type", *FRAME_KEYS]
    assert len(best.T_world_wrist) == 7 and all(type(x) is float for x in best.T_world_wrist)
    assert set(best.experts) >= {"collision", "config", "pregrasp_clear", "kinematic"}
    # grasps.json: the same entries, read back as Grasps sorted by rank (non-finite log values as floats again).
    grasps.save(tmp_path / "g.json")
    doc = load_grasps(tmp_path / "g.json")
    assert all(isinstance(g, Grasp) for g in doc["grasps"])
    finite = [g for g in grasps if np.isfinite(g.log_likelihood)]
    assert doc["grasps"][: len(finite)] == finite
    assert [g.log_likelihood for g in doc["grasps"][len(finite) :]] == [-np.inf] * (len(grasps) - len(finite))
    assert grasp_by_rank(doc, 2) == grasps[1] and grasp_by_rank(grasps, 2) is grasps[1]
    # A GraspSet holds Grasps; a grasps.json entry becomes one through Grasp.from_dict.
    GraspSet([Grasp.from_dict(OLD_ENTRY)], model.hand_path, "gmm", "", {}).save(tmp_path / "d.json")
    (back,) = [g.to_dict() for g in load_grasps(tmp_path / "d.json")["grasps"]]
    assert list(back)[: len(OLD_ENTRY)] == list(OLD_ENTRY) and {k: back[k] for k in OLD_ENTRY} == OLD_ENTRY
    assert "T_world_wrist_matrix" in back  # the set added the frames
    with pytest.raises(ValueError, match=r"grasps\[0\]: expected a Grasp .* got dict"):
        GraspSet([dict(OLD_ENTRY)], model.hand_path, "gmm", "", {})
