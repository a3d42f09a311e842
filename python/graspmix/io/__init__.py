"""File formats and paths: the bundled data folder, JSON documents with their format checks, clouds and
numeric arrays from files, object lists, provenance. The lowest Python layer: it imports nothing of
graspmix but the C++ core.

    graspmix.io.data_path("hands", "wsg50.urdf")
    graspmix.io.read_document(path, graspmix.io.GRASPS_FORMAT)
"""
from .arrays import as_points, load_array, load_points
from .formats import (
    BENCHMARK_FORMAT,
    DEMO_FORMAT,
    FORMATS,
    GMM_FORMAT,
    GRASPS_FORMAT,
    MODEL_FORMAT,
    PROTOCOL_FORMAT,
    SUMMARY_FORMAT,
    check_format,
    read_document,
    read_json,
    require_field,
)
from .objects import read_object_list, read_objects_file, test_objects
from .paths import (
    PACKAGE_PREFIX,
    data_path,
    default_hand_path,
    pybullet_data_path,
    relative_path,
    resolve_object,
    resolve_path,
)
from .provenance import git_commit, package_version, sha256_file

__all__ = [n for n in dir() if not n.startswith("_") and n not in ("arrays", "formats", "objects", "paths",
                                                                    "provenance")]
