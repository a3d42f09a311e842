"""graspmix.io: the bundled data found from the package, one format check per document kind, paths
written into files, object lists, arrays."""

import json
from pathlib import Path

import graspmix
import numpy as np
import pytest
from graspmix import io


def test_data_path_finds_the_bundled_data():
    for parts in (("hands", "wsg50.urdf"), ("models", "box_wsg50_gmm.json"), ("objects", "test60.txt"), ("mug.pcd",)):
        assert io.data_path(*parts).is_file(), parts
    assert graspmix.data_path is io.data_path and io.default_hand_path() == io.data_path("hands", "wsg50.urdf")


def test_format_checks(tmp_path):
    p = tmp_path / "doc.json"
    for fmt in io.FORMATS:
        p.write_text(json.dumps({"format": fmt, "x": 1}))
        doc = io.read_json(p, "test")
        io.check_format(doc, fmt, p)
        assert doc["x"] == 1
        p.write_text(json.dumps({"format": "other/9"}))
        with pytest.raises(ValueError, match=f"format is 'other/9', expected format '{fmt}'"):
            io.read_document(p, fmt)
        # read_document also checks the content against the format's schema: here, required fields miss.
        p.write_text(json.dumps({"format": fmt, "x": 1}))
        with pytest.raises(io.SchemaError, match=r"doc\.json: field '\w+' is missing"):
            io.read_document(p, fmt)
    # Only demonstrations may leave the field out.
    p.write_text(json.dumps({"hand": "x"}))
    assert io.check_format(io.read_json(p, "test"), io.DEMO_FORMAT, p) is None
    with pytest.raises(ValueError, match="format is None"):
        io.read_document(p, io.MODEL_FORMAT)
    p.write_text("[1, 2]")
    with pytest.raises(ValueError, match="JSON object"):
        io.read_document(p, io.MODEL_FORMAT)
    p.write_text("{nope")
    with pytest.raises(ValueError, match="not valid JSON"):
        io.read_json(p, "model")
    with pytest.raises(ValueError, match="no such grasps file"):
        io.read_document(tmp_path / "missing.json", io.GRASPS_FORMAT)
    with pytest.raises(ValueError, match="missing field 'hand'"):
        io.require_field({}, "hand", p)
    with pytest.raises(ValueError, match="wrong type"):
        io.require_field({"hand": 1}, "hand", p, str)


def test_paths_in_files(tmp_path):
    urdf = io.data_path("hands", "wsg50.urdf")
    assert io.relative_path(urdf, tmp_path) == "package://graspmix/hands/wsg50.urdf"
    assert io.resolve_path("package://graspmix/hands/wsg50.urdf", tmp_path) == urdf
    mine = tmp_path / "sub" / "a.pcd"
    mine.parent.mkdir()
    mine.write_text("")
    assert io.relative_path(mine, tmp_path) == str(Path("sub") / "a.pcd")
    assert io.resolve_path("sub/a.pcd", tmp_path) == mine.resolve()
    assert io.resolve_path("hands/wsg50.urdf", tmp_path) == urdf.resolve()  # falls back to the bundled data


def test_object_lists(tmp_path):
    objects = io.test_objects()
    assert len(objects) == 60 and objects[0].endswith(".urdf")
    (tmp_path / "here.urdf").write_text("<robot/>")
    lst = tmp_path / "list.txt"
    lst.write_text("# a comment\nhere.urdf  # next to the list\ncube_small.urdf\n\n")
    assert io.read_objects_file(lst) == [str((tmp_path / "here.urdf").resolve()), "cube_small.urdf"]
    lst.write_text("# nothing\n")
    with pytest.raises(ValueError, match="lists no objects"):
        io.read_objects_file(lst)
    with pytest.raises(ValueError, match="no such objects file"):
        io.read_objects_file(tmp_path / "none.txt")
    with pytest.raises(ValueError, match="no such object file"):
        io.resolve_object("no/such.urdf")


def test_arrays(tmp_path):
    np.save(tmp_path / "a.npy", np.ones((4, 3)))
    (tmp_path / "b.csv").write_text("1,2\n3,4\n")
    assert io.load_array(tmp_path / "a.npy").shape == (4, 3)
    assert io.load_array(tmp_path / "b.csv").tolist() == [[1, 2], [3, 4]]
    with pytest.raises(ValueError, match="no such file"):
        io.load_array(tmp_path / "c.npy")
    points, name, viewpoint = io.load_points(np.zeros((5, 3)))
    assert points.shape == (5, 3) and name == "<array>" and viewpoint is None
    with pytest.raises(ValueError, match=r"\(N, 3\)"):
        io.load_points(np.zeros((5, 2)))
    points, name, viewpoint = io.load_points(str(io.data_path("mug.pcd")))
    assert len(points) > 100 and name.endswith("mug.pcd")
