"""Object lists: one object URDF a line (a path, or relative to pybullet_data), '#' starts a comment."""

from __future__ import annotations

from pathlib import Path

from .checks import check_input_file
from .paths import data_path


def read_object_list(path) -> list[str]:
    """The entries of an object list, as written."""
    p = check_input_file(path, "object list")
    try:
        text = p.read_bytes().decode("utf-8")
    except UnicodeDecodeError as e:
        raise ValueError(f"{p}: not UTF-8 text (byte {e.start})") from None
    return [line.split("#")[0].strip() for line in text.splitlines() if line.split("#")[0].strip()]


def test_objects(path=None) -> list[str]:
    """The paper's 60 test objects (data/objects/test60.txt, paths relative to pybullet_data), or the
    entries of another list."""
    return read_object_list(path if path else data_path("objects", "test60.txt"))


test_objects.__test__ = False  # a library function, not a pytest test


def read_objects_file(path: str | Path) -> list[str]:
    """An objects file for the experiment: entries that exist next to the list are made absolute, the
    others are left for pybullet_data."""
    p = check_input_file(path, "objects")
    objects = read_object_list(p)
    if not objects:
        raise ValueError(f"{path}: lists no objects")
    return [
        str((p.parent / o).resolve()) if not Path(o).is_absolute() and (p.parent / o).is_file() else o for o in objects
    ]
