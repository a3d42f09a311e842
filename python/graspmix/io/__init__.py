"""File formats and paths: the bundled data folder, JSON documents with their format checks, clouds and
numeric arrays from files, object lists, provenance. The lowest Python layer: it imports nothing of
graspmix but the C++ core.

    graspmix.io.data_path("hands", "wsg50.urdf")
    graspmix.io.read_document(path, graspmix.io.GRASPS_FORMAT)   # checked against its format's schema
    graspmix.io.check_output_path(path, "--out")                   # before the work whose result it holds
"""

from .arrays import as_points, load_array, load_points
from .checks import (
    MAX_SIM_TIME,
    QUOTE_LIMIT,
    SEED_MAX,
    check_float,
    check_input_file,
    check_int,
    check_output_folder,
    check_output_path,
    check_path_text,
    check_seed,
    check_sim_time,
    quote,
)
from .formats import (
    BENCHMARK_FORMAT,
    CLUTTER_FORMAT,
    CLUTTER_SUMMARY_FORMAT,
    DEMO_FORMAT,
    FORMATS,
    GMM_FORMAT,
    GRASPS_FORMAT,
    MODEL_FORMAT,
    PROTOCOL_FORMAT,
    SCENE_FORMAT,
    SCHEMAS,
    SUMMARY_FORMAT,
    check_format,
    read_document,
    read_json,
    require_field,
)
from .objects import read_object_list, read_objects_file, test_objects
from .paths import (
    PACKAGE_PREFIX,
    PYBULLET_DATA_PREFIX,
    check_digest,
    data_path,
    default_hand_path,
    object_reference,
    pybullet_data_path,
    relative_path,
    resolve_object,
    resolve_path,
)
from .provenance import git_commit, package_version, sha256_file
from .schema import SchemaError

__all__ = [
    n
    for n in dir()
    if not n.startswith("_") and n not in ("arrays", "checks", "formats", "objects", "paths", "provenance", "schema")
]
