"""The presets' synthesis settings: "paper" keeps the paper's (and a protocol.json written before the new experts
existed reads as the paper's), "defaults" runs the library's; the new fields' bad values."""

import dataclasses

import pytest
from graspmix import cli
from graspmix import experiment as ex
from graspmix.experiment.attempt import synthesis_keywords
from graspmix.experiment.protocol import protocol_from_json
from graspmix.model.settings import SynthesisOptions


def test_paper_keeps_the_papers_synthesis_and_defaults_runs_the_librarys():
    paper, smoke, defaults = (ex.Protocol.preset(n) for n in ("paper", "smoke", "defaults"))
    for p in (paper, smoke):
        assert (p.collision, p.clear_approach, p.contact_quality, p.cloud) == ("surface", False, False, "object")
    assert defaults.objects == paper.objects and defaults.trials == paper.trials
    assert defaults.collision == SynthesisOptions.collision
    assert defaults.clear_approach == SynthesisOptions.clear_approach
    assert defaults.stand_off == SynthesisOptions.stand_off
    assert defaults.contact_quality == SynthesisOptions.contact_quality
    assert defaults.friction == SynthesisOptions.friction
    assert defaults.cloud == "scene"
    # An override beats the preset.
    assert ex.Protocol.preset("paper", collision="occupancy").collision == "occupancy"
    # What reaches the synthesis.
    kw = synthesis_keywords(paper, 0, True)
    assert (kw["collision"], kw["clear_approach"]) == ("surface", False)
    kw = synthesis_keywords(defaults, 0, True)
    assert (kw["collision"], kw["clear_approach"], kw["stand_off"]) == (
        SynthesisOptions.collision,
        SynthesisOptions.clear_approach,
        SynthesisOptions.stand_off,
    )


def test_a_protocol_json_without_the_new_fields_is_the_papers():
    d = dataclasses.asdict(ex.Protocol.preset("paper"))
    for k in ("collision", "clear_approach", "stand_off", "contact_quality", "friction", "cloud", "views"):
        d.pop(k)
    p = protocol_from_json(d)
    assert (p.collision, p.clear_approach, p.contact_quality, p.cloud, p.views) == (
        "surface",
        False,
        False,
        "object",
        4,
    )


def test_bad_values_are_errors(capsys):
    objs = ["cube_small.urdf"]
    with pytest.raises(ValueError, match="collision"):
        ex.Protocol(objects=objs, collision="voxels")
    with pytest.raises(ValueError, match="clear_approach"):
        ex.Protocol(objects=objs, clear_approach="yes")
    with pytest.raises(ValueError, match="stand_off"):
        ex.Protocol(objects=objs, stand_off=-0.01)
    with pytest.raises(ValueError, match="contact_quality"):
        ex.Protocol(objects=objs, contact_quality=1)
    with pytest.raises(ValueError, match="friction"):
        ex.Protocol(objects=objs, friction=0.0)
    with pytest.raises(ValueError, match="views"):
        ex.Protocol(objects=objs, views=0)
    with pytest.raises(ValueError, match="cloud"):
        ex.Protocol(objects=objs, cloud="depth")
    assert cli.main(["experiment", "--out", "unused", "--stand-off", "-0.1"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--stand-off" in err


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
    import dataclasses as dc

    from graspmix.experiment.report import _clouds_text, _synthesis_text

    paper = dc.asdict(ex.Protocol.preset("paper"))
    assert (
        _synthesis_text(paper) == "The paper's synthesis. " and _clouds_text(paper) == "4 cameras, the object's pixels"
    )
    one = dc.asdict(ex.Protocol.preset("defaults", views=1, collision="occupancy"))
    text = _synthesis_text(one)
    assert "occupancy" in text and "stand-off 10 cm, clearance 2 mm" in text and "friction 0.5" in text
    assert _clouds_text(one) == "1 camera above the table, the whole depth images"
    assert _synthesis_text({}) == "The paper's synthesis. "  # a protocol.json from before the fields
