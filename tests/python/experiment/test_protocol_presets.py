"""The presets' synthesis: "paper" keeps the paper's (SynthesisOptions.paper()), "defaults" runs the library's
(SynthesisOptions()); each attempt's options; protocol.json's round trip; bad values."""

import pytest
from graspmix import SynthesisOptions, cli
from graspmix import experiment as ex
from graspmix.experiment.protocol import CONDITIONS, protocol_from_json


def test_paper_keeps_the_papers_synthesis_and_defaults_runs_the_librarys():
    paper, smoke, defaults = (ex.Protocol.preset(n) for n in ("paper", "smoke", "defaults"))
    for p in (paper, smoke):
        assert p.synthesis == SynthesisOptions.paper() and p.cloud == "object"
        assert p.synthesis.approach is None and p.synthesis.contact_quality is None
        assert p.synthesis.collision.model == "surface"
    assert defaults.objects == paper.objects and defaults.trials == paper.trials
    assert defaults.synthesis == SynthesisOptions() and defaults.cloud == "scene"
    assert defaults.synthesis.approach is not None and defaults.synthesis.contact_quality is not None
    # An override beats the preset.
    occupancy = SynthesisOptions.paper().updated({"collision.model": "occupancy"})
    assert ex.Protocol.preset("paper", synthesis=occupancy).synthesis.collision.model == "occupancy"


@pytest.mark.parametrize("condition", list(CONDITIONS))
def test_an_attempt_gets_its_conditions_optimisation_its_seed_and_the_known_plane(condition):
    p = ex.Protocol.preset("defaults")
    o = p.attempt_options("objects/mug.urdf", 3, condition)
    assert o.sampling.optimise == CONDITIONS[condition].optimise
    assert o.seed == p.synthesis_seed("objects/mug.urdf", 3, condition) != 0
    assert o.segmentation.find_plane is False
    # Nothing else changes.
    assert o.updated({"sampling.optimise": True, "seed": 0, "segmentation.find_plane": True}) == p.synthesis


def test_protocol_json_round_trips_the_synthesis():
    for name in ("paper", "defaults"):
        p = ex.Protocol.preset(name, synthesis=SynthesisOptions().updated({"approach.stand_off": 0.2}))
        assert protocol_from_json(p.to_json()) == p
    d = ex.Protocol.preset("paper").to_json()
    d["synthesis"]["sampling"]["n_samples"] = 0
    with pytest.raises(ValueError, match="sampling.n_samples"):
        protocol_from_json(d)


def test_bad_values_are_errors(capsys):
    objs = ["cube_small.urdf"]
    with pytest.raises(ValueError, match="synthesis"):
        ex.Protocol(objects=objs, synthesis={"collision": "voxels"})
    with pytest.raises(ValueError, match="collision.model"):
        SynthesisOptions().updated({"collision.model": "voxels"})
    with pytest.raises(ValueError, match="views"):
        ex.Protocol(objects=objs, views=0)
    with pytest.raises(ValueError, match="cloud"):
        ex.Protocol(objects=objs, cloud="depth")
    assert cli.main(["experiment", "--out", "unused", "--stand-off", "-0.1"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--stand-off" in err
    # What each attempt decides itself is refused, not recorded and ignored.
    for changes, name in (({"seed": 3}, "seed"), ({"sampling.optimise": False}, "sampling.optimise")):
        with pytest.raises(ValueError, match=name):
            ex.Protocol(objects=objs, synthesis=SynthesisOptions().updated(changes))
    assert cli.main(["experiment", "--out", "unused", "--no-find-plane"]) == 2
    assert "the known table is given" in capsys.readouterr().err


def test_the_paper_preset_still_gives_the_rows_of_results_paper(tmp_path):
    """Two attempts of the paper preset (the mug, trial 0, condition A, both methods) against the committed full
    run's rows: the same executed grasp (to 1e-6) and the same outcome."""
    import csv
    import gzip
    import json
    from pathlib import Path

    import numpy as np

    objs = tmp_path / "objects.txt"
    objs.write_text("objects/mug.urdf\n")
    out = tmp_path / "run"
    argv = ["experiment", "--preset", "paper", "--objects", str(objs), "--trials", "1", "--conditions", "A"]
    assert cli.main([*argv, "--out", str(out), "--quiet"]) == 0
    with open(out / "attempts.csv", newline="") as f:
        now = {r["method"]: r for r in csv.DictReader(f)}
    repo = Path(__file__).resolve().parents[3]
    with gzip.open(repo / "results" / "paper" / "attempts.csv.gz", "rt", newline="") as f:
        key = ("objects/mug.urdf", "0", "A")
        before = {r["method"]: r for r in csv.DictReader(f) if (r["object"], r["trial"], r["condition"]) == key}
    assert set(now) == set(before) == {"gmm", "kde"}
    for m in now:
        a, b = json.loads(now[m]["grasp"]), json.loads(before[m]["grasp"])
        np.testing.assert_allclose(a["T_world_wrist"], b["T_world_wrist"], rtol=0, atol=1e-6)
        assert now[m]["reason"] == before[m]["reason"]


def test_the_report_says_which_clouds_and_experts_a_run_used():
    from graspmix.experiment.report import _clouds_text, _synthesis_text

    paper = ex.Protocol.preset("paper").to_json()
    assert _synthesis_text(paper["synthesis"]) == "The paper's synthesis. "
    assert _clouds_text(paper) == "4 cameras, the object's pixels"
    one = ex.Protocol.preset(
        "defaults", views=1, synthesis=SynthesisOptions().updated({"collision.model": "occupancy"})
    )
    text = _synthesis_text(one.to_json()["synthesis"])
    assert "occupancy" in text and "stand-off 10 cm, clearance 2 mm" in text and "friction 0.5" in text
    # one camera: the defaults take its depth image as a driver gives it; points on request, and never of 4 cameras
    assert one.cloud == "image"
    assert (
        _clouds_text(one.to_json())
        == "1 camera above the table, the depth image with its intrinsics and pose (image space)"
    )
    points = ex.Protocol.preset("defaults", views=1, cloud="scene")
    assert _clouds_text(points.to_json()) == "1 camera above the table, the whole depth images"
    with pytest.raises(ValueError, match="views must be 1"):
        ex.Protocol.preset("defaults", views=4, cloud="image")
