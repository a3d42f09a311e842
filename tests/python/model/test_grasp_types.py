"""Grasp types: a model of several demonstrations (the bundled box top grasp and mug side grasp).

Independent answers: the type each demonstration was recorded as (on its own cloud the best grasp must
be of that type), invariance of the ranking to the order the demonstrations are given in, and the grasps
the code before grasp types synthesised with the bundled box model (commit 8199385; the file was then in
format graspmix.model/1 and has since been re-saved as graspmix.model/2 with the same numbers).
"""

import json

import graspmix
import numpy as np
import pytest
from graspmix.cli.main import main
from graspmix.model.grasp_types import REFERENCE_EXPERT

BOX, MUG = graspmix.data_path("demos", "box_wsg50.json"), graspmix.data_path("demos", "mug_side_wsg50.json")
CLOUDS = {
    "box_wsg50": graspmix.data_path("demos", "box.pcd"),
    "mug_side_wsg50": graspmix.data_path("demos", "mug_side.pcd"),
}
# The demonstrations' clouds have no table.
FAST = graspmix.SynthesisOptions().updated(
    {"sampling.n_samples": 100, "sampling.n_optimise": 3, "segmentation.find_plane": False}
)


def test_a_model_of_one_type_synthesises_as_that_type_of_a_model_of_two():
    """The bundled box model and the box type of the bundled two-type model are learnt from the same
    demonstration with the same seed: restricted to that type, the two-type model gives the same grasps, each
    log L lower by exactly the type's reference."""
    one = graspmix.GraspModel.load(graspmix.default_model_path("gmm"))
    assert one.type_names == ["box_wsg50"] and one.types[0].log_reference == 0.0
    two = graspmix.GraspModel.load(graspmix.data_path("models", "box_mug_side_wsg50_gmm.json"))
    opts = graspmix.SynthesisOptions().updated({"sampling.n_samples": 50, "sampling.n_optimise": 3, "seed": 3})
    a = one.synthesize(graspmix.data_path("mug.pcd"), opts)
    b = two.synthesize(graspmix.data_path("mug.pcd"), opts, types="box_wsg50")
    ref = two.types[two.type_names.index("box_wsg50")].log_reference
    assert len(a) == len(b) == 50 and ref > 0
    for g, h in zip(a.grasps, b.grasps):
        np.testing.assert_allclose(g.T_world_wrist, h.T_world_wrist, rtol=0, atol=1e-12)
        assert h.log_likelihood == pytest.approx(g.log_likelihood - ref, abs=1e-9) or g.log_likelihood == -np.inf
        assert REFERENCE_EXPERT not in g.experts and g.type == h.type == "box_wsg50"


def test_a_model_is_built_from_a_list_of_grasp_types():
    m = graspmix.GraspModel.load(graspmix.default_model_path("gmm"))
    same = graspmix.GraspModel(m.hand, m.hand_path, list(m.types), m.features, m.learn_settings)
    assert same.type_names == ["box_wsg50"] and same.synthesizer is m.synthesizer
    with pytest.raises(ValueError, match="types must be a list of GraspType, got GraspSynthesizer"):
        graspmix.GraspModel(m.hand, m.hand_path, m.synthesizer, m.features, m.learn_settings)


def test_demonstrations_of_different_hands_are_refused(tmp_path, capsys):
    urdf = graspmix.data_path("hands", "wsg50.urdf").read_text().replace('<robot name="wsg50">', '<robot name="other">')
    (tmp_path / "other.urdf").write_text(urdf)
    demo = json.loads(MUG.read_text())
    demo["hand"], demo["cloud"] = str(tmp_path / "other.urdf"), str(CLOUDS["mug_side_wsg50"])
    (tmp_path / "other_demo.json").write_text(json.dumps(demo))
    with pytest.raises(ValueError, match="different hands: 'wsg50'.*'other'"):
        graspmix.learn([str(BOX), str(tmp_path / "other_demo.json")])
    rc = main(
        ["learn", "--demo", str(BOX), "--demo", str(tmp_path / "other_demo.json"), "--out", str(tmp_path / "m.json")]
    )
    err = capsys.readouterr().err.strip()
    assert rc == 2 and len(err.splitlines()) == 1 and "different hands" in err
    assert not (tmp_path / "m.json").exists()


def test_type_names_must_be_unique_and_well_formed(tmp_path):
    with pytest.raises(ValueError, match="two demonstrations are named 'box_wsg50'"):
        graspmix.learn([str(BOX), str(BOX)])
    named = graspmix.learn([str(BOX), f"top={BOX}"])
    assert named.type_names == ["box_wsg50", "top"]
    with pytest.raises(ValueError, match="bad grasp type name"):
        graspmix.learn([f"a b={BOX}"])
