"""Where files are: the bundled data folder (found here and nowhere else), paths written into graspmix
files, and object URDFs (a path, or relative to pybullet_data).

Every path a graspmix file stores (a demonstration's hand and cloud, a model's hand and demonstration, a
grasps file's hand and cloud, a scene's objects) is written by relative_path or object_reference and read
by resolve_path or resolve_object, so the files load on another machine: the bundled data as
package://graspmix/..., pybullet_data's files as pybullet_data://... (resolved against the installed
pybullet_data), anything else relative to the file's folder (absolute only across drives)."""

from __future__ import annotations

import os
from pathlib import Path

from .checks import check_path_text
from .provenance import sha256_file

PACKAGE_PREFIX = "package://graspmix/"
PYBULLET_DATA_PREFIX = "pybullet_data://"  # a file of the installed pybullet_data package (e.g. its hands)

# This file is graspmix/io/paths.py: the package folder is one level up, the source tree's data/ three.
_PACKAGE = Path(__file__).resolve().parent.parent


def data_path(*parts: str) -> Path:
    """A file of the bundled data (hands, demonstrations, default models, example clouds, object lists)."""
    for root in (_PACKAGE / "data", _PACKAGE.parent.parent / "data"):  # installed package, then source tree
        if root.is_dir():
            return root.joinpath(*parts)
    raise FileNotFoundError("graspmix's bundled data folder is missing from this installation")


def default_hand_path() -> Path:
    """The bundled WSG 50 URDF."""
    return data_path("hands", "wsg50.urdf")


def resolve_path(path_text: str, base: Path) -> Path:
    """A path from a file: package://graspmix/... (the bundled data), pybullet_data://... (the installed
    pybullet_data), absolute, or relative to the file's folder `base` (then to the bundled data).
    ValueError for a path that is not UTF-8 or too long."""
    check_path_text(path_text, "path")
    if path_text.startswith(PACKAGE_PREFIX):
        return data_path(path_text[len(PACKAGE_PREFIX) :])
    if path_text.startswith(PYBULLET_DATA_PREFIX):
        return pybullet_data_path() / path_text[len(PYBULLET_DATA_PREFIX) :]
    p = Path(path_text)
    if p.is_absolute():
        return p
    for candidate in (base / p, data_path(path_text)):
        if candidate.exists():
            return candidate.resolve()
    return (base / p).resolve()


def relative_path(target: Path, base: Path) -> str:
    """How a file in folder `base` refers to target: package://graspmix/... for the bundled data,
    pybullet_data://... for pybullet_data's files, else relative to base when it can be (keeps files
    movable with their data), else absolute."""
    for prefix, root in ((PACKAGE_PREFIX, data_path()), (PYBULLET_DATA_PREFIX, _pybullet_data_or_none())):
        if root is None:
            continue
        try:
            return prefix + Path(target).resolve().relative_to(root.resolve()).as_posix()
        except ValueError:
            pass
    try:
        return os.path.relpath(Path(target).resolve(), Path(base).resolve())
    except ValueError:
        return str(Path(target).resolve())


def pybullet_data_path() -> Path:
    """pybullet_data's folder (the WSG 50 meshes, the test objects)."""
    import pybullet_data

    return Path(pybullet_data.getDataPath())


def _pybullet_data_or_none() -> Path | None:
    try:
        return pybullet_data_path()
    except ImportError:  # pybullet is optional for reading and writing files
        return None


def object_reference(path: str | Path, base: Path) -> str:
    """How a scene file in folder `base` names an object URDF: relative to pybullet_data for its objects
    (the scene format's own form, e.g. random_urdfs/012/012.urdf), else as relative_path writes it."""
    root = _pybullet_data_or_none()
    target = resolve_object(path)
    if root is not None:
        try:
            return target.resolve().relative_to(root.resolve()).as_posix()
        except ValueError:
            pass
    return relative_path(target, base)


def resolve_object(path: str | Path) -> Path:
    """An object URDF: an existing path, package://graspmix/..., pybullet_data://..., or a path relative to
    pybullet_data (e.g. random_urdfs/012/012.urdf)."""
    p = check_path_text(path, "object")
    if str(path).startswith((PACKAGE_PREFIX, PYBULLET_DATA_PREFIX)):
        p = resolve_path(str(path), Path.cwd())
    if p.is_file():
        return p.resolve()
    q = pybullet_data_path() / p
    if q.is_file():
        return q
    raise ValueError(f"{path}: no such object file (looked in the working directory and in pybullet_data)")


def check_digest(path: str | Path, digest: str | None, what: str) -> None:
    """ValueError when `path` no longer holds the bytes whose SHA-256 `digest` a grasps file recorded of the cloud
    or depth image it was made on (drawing it over a file replaced since, e.g. a camera driver writing depth.png
    again, would put the grasps on another scene); nothing recorded: nothing to check."""
    if digest and sha256_file(path) != digest:
        raise ValueError(
            f"{path}: not the {what} the grasps were synthesised on (its content changed since: its SHA-256 differs "
            "from the one the grasps file records); synthesise again on it, or give the picture's cloud yourself"
        )
