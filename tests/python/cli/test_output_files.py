"""What a command writes is checked before the work: never the file it reads (by any path, a NAME=FILE demonstration
included), never two outputs on one file, a picture by a picture's suffix and a page by .html; each a one-line error
and exit status 2, with the input left as it was."""

import shutil

import pytest
from graspmix import data_path
from graspmix.cli.main import main


@pytest.fixture()
def cloud(tmp_path):
    path = tmp_path / "scene.pcd"
    shutil.copy(data_path("scenes", "packed4.pcd"), path)
    return path


def _refused(argv, capsys, words):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and all(w in err[0] for w in words), err


def test_an_output_on_the_input_is_refused_and_the_input_kept(cloud, capsys):
    before = cloud.read_bytes()
    _refused(["synthesize", "--cloud", str(cloud), "--out", str(cloud)], capsys, ["--out", "--cloud", "same file"])
    # the same file by another path
    other = cloud.parent / "." / ".." / cloud.parent.name / cloud.name
    _refused(["synthesize", "--cloud", str(cloud), "--out", str(other)], capsys, ["same file"])
    assert cloud.read_bytes() == before


def test_two_outputs_on_one_file_are_refused(cloud, capsys):
    out = cloud.parent / "g.png"
    _refused(["synthesize", "--cloud", str(cloud), "--out", str(out), "--png", str(out)], capsys, ["same file"])
    assert not out.exists()


def test_a_named_demonstration_is_an_input_too(tmp_path, capsys):
    demo = tmp_path / "box.json"
    shutil.copy(data_path("demos", "box_wsg50.json"), demo)
    before = demo.read_bytes()
    _refused(["learn", "--demo", f"box={demo}", "--out", str(demo)], capsys, ["--demo", "same file"])
    assert demo.read_bytes() == before


@pytest.mark.parametrize(
    "argv, words",
    [
        (["--png", "pic.txt"], ["--png", ".png", "'pic.txt'"]),
        (["--png", "pic"], ["--png", "'pic'"]),
    ],
)
def test_a_picture_needs_a_pictures_suffix(cloud, capsys, argv, words):
    _refused(["synthesize", "--cloud", str(cloud), "--out", str(cloud.parent / "g.json"), *argv], capsys, words)
    assert not (cloud.parent / "g.json").exists()  # refused before the work


def test_a_page_needs_html(tmp_path, capsys):
    _refused(["plot", "--grasps", str(tmp_path / "g.json"), "--html", str(tmp_path / "view")], capsys, ["--html"])


def test_reading_one_file_twice_is_allowed(tmp_path):
    demo = str(data_path("demos", "box_wsg50.json"))
    out = tmp_path / "model.json"
    assert main(["learn", "--demo", f"a={demo}", "--demo", f"b={demo}", "--out", str(out)]) == 0
    assert out.exists()
