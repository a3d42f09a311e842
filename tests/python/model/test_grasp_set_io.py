"""GraspSet.load: a saved grasps.json comes back equal, field by field; a loaded set plots; bad files are
clear errors."""

import dataclasses
import json
import shutil
from pathlib import Path

import graspmix
import numpy as np
import pytest
from graspmix.model import Grasp, GraspSet


def _options(n_samples: int, n_optimise: int, seed: int) -> graspmix.SynthesisOptions:
    return graspmix.SynthesisOptions().updated(
        {"sampling.n_samples": n_samples, "sampling.n_optimise": n_optimise, "seed": seed}
    )


@pytest.fixture(scope="module")
def synthesised():
    model = graspmix.GraspModel.load(graspmix.default_model_path("gmm"))
    return model.synthesize(graspmix.data_path("mug.pcd"), _options(40, 3, 1))


@pytest.fixture(scope="module")
def in_a_scene():
    """Grasps on one object of the bundled scene: some rejected by a hard expert (log values -inf, NaN)."""
    model = graspmix.GraspModel.load(graspmix.default_model_path("gmm"))
    cloud = graspmix.data_path("scenes", "packed4.pcd")
    # (no top-down seeds: they would take the places of the rejected grasps, whose -inf the file must carry)
    return model.synthesize(
        cloud, _options(60, 2, 0).updated({"sampling.topdown_seeds": False}), target="point:-0.05,-0.1,0.06"
    )


def _same(a, b):
    """Equality of JSON-like values, NaN equal to NaN and -inf to -inf."""
    if isinstance(a, dict):
        return isinstance(b, dict) and list(a) == list(b) and all(_same(a[k], b[k]) for k in a)
    if isinstance(a, (list, tuple)):
        return isinstance(b, (list, tuple)) and len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, float) or isinstance(b, float):
        return a == b or (np.isnan(a) and np.isnan(b))
    return a == b


@pytest.mark.parametrize("which", ["synthesised", "in_a_scene"])
def test_saved_and_loaded_set_is_equal(which, request, tmp_path):
    synthesised = request.getfixturevalue(which)
    if which == "in_a_scene":  # the file holds "-inf" and null; they come back as numbers
        values = [g.log_likelihood for g in synthesised] + [v for g in synthesised for v in g.experts.values()]
        assert not np.all(np.isfinite(values))
    path = tmp_path / "out" / "grasps.json"
    path.parent.mkdir()
    synthesised.save(path)
    loaded = GraspSet.load(path)
    assert len(loaded) == len(synthesised)
    for a, b in zip(synthesised, loaded):
        assert isinstance(b, Grasp)
        for f in dataclasses.fields(Grasp):
            assert _same(getattr(a, f.name), getattr(b, f.name)), f.name
    assert loaded.hand_path.resolve() == synthesised.hand_path.resolve()
    assert loaded.cloud == str(Path(synthesised.cloud).resolve())
    assert loaded.method == synthesised.method and loaded.timing == synthesised.timing
    np.testing.assert_array_equal(loaded.plane, synthesised.plane)
    assert (loaded.evaluations, loaded.rejected, loaded.targets) == (
        synthesised.evaluations,
        synthesised.rejected,
        synthesised.targets,
    )
    assert loaded.frame_settings == synthesised.frame_settings and loaded.fingertips == synthesised.fingertips
    for prop in ("wrist_matrices", "tcp_poses", "approaches", "closings", "opening_widths", "pregrasp_poses"):
        np.testing.assert_array_equal(getattr(loaded, prop), getattr(synthesised, prop))
    # Saved again, the file is the same: nothing is lost or changed by a round trip.
    loaded.save(tmp_path / "again.json")
    first, second = json.loads(path.read_text()), json.loads((tmp_path / "again.json").read_text())
    assert second["cloud"] == first["cloud"] and _same(first["grasps"], second["grasps"])
    # A file moved together with a cloud it names relatively still finds the cloud.
    shutil.copy(synthesised.cloud, tmp_path / "cloud.pcd")
    doc = dict(first, cloud="../cloud.pcd")
    path.write_text(json.dumps(doc))
    assert GraspSet.load(path).cloud == str((tmp_path / "cloud.pcd").resolve())


def test_a_file_without_frames_gets_them_from_its_hand(synthesised, tmp_path):
    synthesised.save(tmp_path / "g.json")
    doc = json.loads((tmp_path / "g.json").read_text())
    for g in doc["grasps"]:
        for k in graspmix.model.grasp_frames.FRAME_KEYS:
            g.pop(k)
    del doc["frames"], doc["plane"]
    (tmp_path / "old.json").write_text(json.dumps(doc))
    old = GraspSet.load(tmp_path / "old.json")
    np.testing.assert_allclose(old.tcp_poses, synthesised.tcp_poses, atol=1e-12)
    assert old.plane is None


def test_loaded_sets_plot(synthesised, tmp_path):
    synthesised.save(tmp_path / "g.json")
    loaded = GraspSet.load(tmp_path / "g.json")
    drawing = graspmix.viz.grasp_drawing(loaded, top=2)
    # The file's cloud, its table points dropped (the mug's cloud is the mug on a table): every point drawn is
    # off the plane, and the table patch lies in the plane.
    plane = loaded.plane
    assert len(drawing.points) > 1000
    assert np.all(np.abs(drawing.points @ plane[:3] + plane[3]) > graspmix.SegmentationSettings().table_clearance)
    np.testing.assert_allclose(drawing.plane_patch @ plane[:3] + plane[3], 0, atol=1e-9)
    assert len(drawing.hands) == 2 and len(drawing.hands[0]) == 3  # palm and two fingers
    np.testing.assert_allclose(drawing.tcps[0], loaded.best().T_world_tcp[:3])
    assert loaded.plot(tmp_path / "g.png", top=2) == tmp_path / "g.png"
    assert (tmp_path / "g.png").stat().st_size > 20_000
    # A file without a cloud: the hands and the table alone.
    doc = json.loads((tmp_path / "g.json").read_text())
    (tmp_path / "bare.json").write_text(json.dumps(dict(doc, cloud="")))
    bare = GraspSet.load(tmp_path / "bare.json")
    assert len(graspmix.viz.grasp_drawing(bare).points) == 0
    assert bare.plot(tmp_path / "bare.png").stat().st_size > 10_000
    fig = loaded.plot(cloud=graspmix.data_path("mug.pcd"))
    assert len(fig.axes) == 2
    with pytest.raises(ValueError, match="no grasps to draw"):
        loaded.plot(tmp_path / "x.png", top=0)


def test_bad_grasps_files_are_clear_errors(tmp_path, synthesised):
    synthesised.save(tmp_path / "g.json")
    doc = json.loads((tmp_path / "g.json").read_text())
    cases = {
        "tcp": (lambda d: d["grasps"][0].__setitem__("T_world_tcp", [0, 0]), r"grasps\[0\].T_world_tcp"),
        "matrix": (lambda d: d["grasps"][0].__setitem__("T_world_wrist_matrix", [[1, 0]]), "T_world_wrist_matrix"),
        "plane": (lambda d: d.__setitem__("plane", [0, 0, 1]), "plane"),
        "distance": (lambda d: d["frames"].__setitem__("pregrasp_distance", -1), "pregrasp_distance"),
        "hand": (lambda d: d.pop("hand"), "names no hand"),
    }
    for name, (spoil, message) in cases.items():
        bad = json.loads(json.dumps(doc))
        spoil(bad)
        (tmp_path / f"{name}.json").write_text(json.dumps(bad))
        with pytest.raises(ValueError, match=message):
            GraspSet.load(tmp_path / f"{name}.json")
