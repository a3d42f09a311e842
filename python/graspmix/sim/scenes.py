"""Scenes of several objects on a table (z = 0): their description (SceneSpec, the "graspmix.scene/1"
JSON format), their construction as clutter (make_scene, after Breyer et al. 2020, VGN: "packed" and
"pile"), their observation (acquire_scene, in scene_camera.py) and a grasp executed in them
(execute_in_scene).

Every scene is built, settled and executed in the same Bullet simulation (graspmix._core.sim_settle_scene
and sim_execute_scene), so a scene made by make_scene is at rest when a grasp is executed in it.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .. import _core
from ..io import SCENE_FORMAT, object_reference, read_document, read_objects_file, resolve_object
from ..io.checks import check_int, check_seed, quote
from .execution import SimSettings, closing_overrides, grasp_arrays, load_hand, load_object, make_settings

MODES = ("pile", "packed")
# The table's workspace (VGN's): a 30 x 30 cm square centred on the origin; x_min, y_min, x_max, y_max.
WORKSPACE = (-0.15, -0.15, 0.15, 0.15)
QUATERNION_TOLERANCE = 1e-6  # |1 - |q|| allowed in a scene file
SETTLE_SECONDS = 3.0  # s: at most, per settling
PACKED_ATTEMPTS = 200  # positions tried per object before it is left out (20 left 1-2 of 5 out)
PACKED_GAP = 0.01  # m between packed footprints (about 1 cm, as in the issue; at 5 mm segment_scene joined neighbours)
PACKED_CELL = 0.002  # m: the grid on which footprints are compared
PILE_BOX = 0.6  # the pile's box: this fraction of the workspace's sides, centred in it


@dataclass
class PlacedObject:
    """An object of a scene: a one-link URDF (a path, or relative to pybullet_data), its link pose
    [x, y, z, qx, qy, qz, qw] in the world and its scale (the Bullet simulation supports 1 only)."""

    urdf: str
    pose: np.ndarray
    scale: float = 1.0

    def __post_init__(self):
        self.pose = np.asarray(self.pose, dtype=float)


@dataclass
class SceneSpec:
    """Objects on the table z = 0 (implicit); seed and mode say how make_scene built it (None: by hand)."""

    objects: list[PlacedObject] = field(default_factory=list)
    seed: int | None = None
    mode: str | None = None

    @property
    def poses(self) -> np.ndarray:
        """(N, 7) the objects' link poses."""
        return np.array([o.pose for o in self.objects], dtype=float).reshape(-1, 7)

    def check(self) -> SceneSpec:
        """ValueError naming the object for a missing URDF, a pose that is not 7 finite numbers, a quaternion
        that is not of unit length or a scale that is not positive; returns self."""
        for i, o in enumerate(self.objects):
            what = f"scene object {i} ({quote(o.urdf)})"
            try:
                resolve_object(o.urdf)
            except ValueError as e:
                raise ValueError(f"{what}: {e}") from None
            if o.pose.shape != (7,) or not np.all(np.isfinite(o.pose)):
                raise ValueError(f"{what}: the pose must be 7 finite numbers [x, y, z, qx, qy, qz, qw]")
            norm = float(np.linalg.norm(o.pose[3:]))
            if abs(norm - 1.0) > QUATERNION_TOLERANCE:
                raise ValueError(f"{what}: the quaternion [qx, qy, qz, qw] has length {norm:g}, not 1")
            if not (isinstance(o.scale, (int, float)) and math.isfinite(o.scale) and o.scale > 0):
                raise ValueError(f"{what}: the scale must be a positive number, got {quote(o.scale)}")
        return self

    def without(self, index: int) -> SceneSpec:
        """The scene without object `index`."""
        index = check_int(index, "index", 0, len(self.objects) - 1)
        return SceneSpec([o for i, o in enumerate(self.objects) if i != index], self.seed, self.mode)

    def to_dict(self) -> dict:
        return {
            "format": SCENE_FORMAT,
            "objects": [{"urdf": o.urdf, "pose": [float(v) for v in o.pose], "scale": o.scale} for o in self.objects],
            "seed": self.seed,
            "mode": self.mode,
        }

    def save(self, path) -> None:
        """Writes the scene; object paths as object_reference gives them, so the file loads elsewhere."""
        base = Path(path).resolve().parent
        doc = self.to_dict()
        for o, d in zip(self.objects, doc["objects"]):
            d["urdf"] = object_reference(o.urdf, base)
        Path(path).write_text(json.dumps(doc, indent=1) + "\n")

    @classmethod
    def load(cls, path) -> SceneSpec:
        """A scene file, checked (see check); an object's relative path is looked up next to the file first."""
        doc = read_document(path, SCENE_FORMAT)
        base = Path(path).resolve().parent
        objects = []
        for o in doc["objects"]:
            urdf = o["urdf"]
            if not Path(urdf).is_absolute() and (base / urdf).is_file():
                urdf = str(base / urdf)
            objects.append(PlacedObject(urdf, np.asarray(o["pose"], dtype=float), float(o.get("scale", 1.0))))
        try:
            return cls(objects, doc.get("seed"), doc.get("mode")).check()
        except ValueError as e:
            raise ValueError(f"{path}: {e}") from None


def _sim_objects(spec: SceneSpec) -> list:
    spec.check()
    for i, o in enumerate(spec.objects):
        if o.scale != 1.0:
            raise ValueError(f"scene object {i} ({quote(o.urdf)}): the Bullet simulation supports scale 1 only")
    return [load_object(o.urdf) for o in spec.objects]


def settle(spec: SceneSpec, settings: SimSettings | None = None, seconds: float = SETTLE_SECONDS, walls=None):
    """The scene simulated without a hand until its objects rest (at most `seconds`), as a new SceneSpec.
    walls: [x_min, y_min, x_max, y_max, height] of a box standing around the objects meanwhile, or None."""
    if not spec.objects:
        return SceneSpec([], spec.seed, spec.mode)
    objs = _sim_objects(spec)
    r = _core.sim_settle_scene(objs, spec.poses, make_settings(settings), seconds, walls)
    poses = _canonical(np.asarray(r.object_poses))
    return SceneSpec([PlacedObject(o.urdf, p, o.scale) for o, p in zip(spec.objects, poses)], spec.seed, spec.mode)


def _canonical(poses: np.ndarray) -> np.ndarray:
    """Unit quaternions with w >= 0 (the convention of a single representative)."""
    poses = poses.copy()
    poses[:, 3:] /= np.linalg.norm(poses[:, 3:], axis=1, keepdims=True)
    poses[poses[:, 6] < 0, 3:] *= -1
    return poses


def choose_objects(object_list, n: int, seed: int) -> list[str]:
    """n objects drawn from an object list file (without replacement when it has n or more)."""
    n = check_int(n, "n", 1)
    check_seed(seed)
    objects = read_objects_file(object_list)
    rng = np.random.default_rng(seed)
    return [objects[i] for i in rng.choice(len(objects), n, replace=n > len(objects))]


def _yaw_quaternion(yaw: float) -> np.ndarray:
    return np.array([0.0, 0.0, math.sin(yaw / 2), math.cos(yaw / 2)])


def _rotate(q: np.ndarray, v: np.ndarray) -> np.ndarray:
    pose = np.zeros((len(v), 7))
    pose[:, 6] = 1.0
    pose[:, :3] = v
    return _core.pose_multiply(np.r_[0.0, 0.0, 0.0, q][None].repeat(len(v), 0), pose)[:, :3]


def _vertices(obj) -> np.ndarray:
    model = obj.model
    return np.asarray(model.collision_mesh(model.link_names[0])[0], dtype=float)


def _place_packed(objs, rng, workspace) -> list[tuple[int, np.ndarray]]:
    """Upright objects at random positions and yaws in the workspace; an object whose footprint (the convex
    hull of its vertices seen from above, on a PACKED_CELL grid, grown by PACKED_GAP) would overlap one
    already placed is tried elsewhere, and left out after PACKED_ATTEMPTS tries."""
    from scipy.ndimage import binary_dilation
    from scipy.spatial import ConvexHull, Delaunay

    x0, y0, x1, y1 = workspace
    gx, gy = np.meshgrid(np.arange(x0, x1, PACKED_CELL), np.arange(y0, y1, PACKED_CELL), indexing="ij")
    cells = np.stack([gx.ravel(), gy.ravel()], axis=1)
    occupied = np.zeros(gx.shape, dtype=bool)
    grow = np.ones((2 * math.ceil(PACKED_GAP / PACKED_CELL) + 1,) * 2, dtype=bool)
    placed = []
    for i, obj in enumerate(objs):
        verts = _vertices(obj)
        verts = verts[ConvexHull(verts).vertices]
        for _ in range(PACKED_ATTEMPTS):
            q = _yaw_quaternion(rng.uniform(0.0, 2 * math.pi))
            xy = _rotate(q, verts)[:, :2]
            lo, hi = xy.min(0), xy.max(0)
            if np.any(hi - lo >= [x1 - x0, y1 - y0]):
                break
            origin = np.array([rng.uniform(x0 - lo[0], x1 - hi[0]), rng.uniform(y0 - lo[1], y1 - hi[1])])
            footprint = (Delaunay(xy + origin).find_simplex(cells) >= 0).reshape(gx.shape)
            if not np.any(binary_dilation(footprint, grow) & occupied):
                occupied |= footprint
                placed.append((i, np.asarray(obj.rest_pose(origin[0], origin[1], q))))
                break
    return placed


def _place_pile(objs, rng, workspace) -> tuple[list[tuple[int, np.ndarray]], list[float]]:
    """Random orientations above the pile's box, stacked in height so that none starts inside another;
    returns the poses and the box's walls."""
    x0, y0, x1, y1 = workspace
    cx, cy, hx, hy = (x0 + x1) / 2, (y0 + y1) / 2, PILE_BOX * (x1 - x0) / 2, PILE_BOX * (y1 - y0) / 2
    placed, z = [], 0.0
    for i, obj in enumerate(objs):
        q = rng.normal(size=4)
        q /= np.linalg.norm(q)
        pose = np.asarray(obj.rest_pose(0.0, 0.0, q))
        rotated = _rotate(pose[3:], _vertices(obj))
        lo, hi = rotated.min(0), rotated.max(0)
        x = rng.uniform(cx - hx - lo[0], cx + hx - hi[0]) if hi[0] - lo[0] < 2 * hx else cx - (lo[0] + hi[0]) / 2
        y = rng.uniform(cy - hy - lo[1], cy + hy - hi[1]) if hi[1] - lo[1] < 2 * hy else cy - (lo[1] + hi[1]) / 2
        pose[:3] = [x, y, pose[2] + z + 0.01]
        z += hi[2] - lo[2] + 0.01
        placed.append((i, pose))
    return placed, [cx - hx, cy - hy, cx + hx, cy + hy, max(0.1, z + 0.05)]


def make_scene(objects: list[str], mode: str, seed: int, workspace=WORKSPACE, settings=None) -> SceneSpec:
    """A scene of the given objects (URDFs) on the table, deterministic for a seed (VGN's construction):
    packed: upright at random positions and yaws in the workspace, rejected when they would overlap, then
    settled; pile: dropped with random orientations into a box in the middle of the workspace, settled, the
    box removed, settled again. Objects that end outside the workspace are removed (and the rest settled)."""
    if mode not in MODES:
        raise ValueError(f"mode must be one of {', '.join(MODES)}, got {quote(mode)}")
    check_seed(seed)
    if not objects:
        raise ValueError("make_scene: no objects given")
    x0, y0, x1, y1 = (float(v) for v in workspace)
    if not (x1 > x0 and y1 > y0):
        raise ValueError(f"workspace must be [x_min, y_min, x_max, y_max] with max > min, got {quote(workspace)}")
    objs = [load_object(o) for o in objects]
    rng = np.random.default_rng(seed)
    if mode == "packed":
        placed, walls = _place_packed(objs, rng, (x0, y0, x1, y1)), None
    else:
        placed, walls = _place_pile(objs, rng, (x0, y0, x1, y1))
    spec = SceneSpec([PlacedObject(str(objects[i]), pose) for i, pose in placed], seed, mode)
    if walls is not None:
        spec = settle(spec, settings, walls=walls)
    spec = settle(spec, settings)
    inside = [o for o in spec.objects if x0 <= o.pose[0] <= x1 and y0 <= o.pose[1] <= y1 and o.pose[2] > -0.01]
    if len(inside) < len(spec.objects):
        spec = settle(SceneSpec(inside, seed, mode), settings)
    return spec


@dataclass
class SceneExecution:
    """A grasp executed in a scene: result (SimResult: success, reason, lift_height, contact_count, ...),
    lifted (indices into the scene's objects), moved (m each object's position changed, lifted ones
    included), remaining (the objects left on the table, settled at their final poses)."""

    result: object
    lifted: list[int]
    moved: np.ndarray
    remaining: SceneSpec
    object_poses: np.ndarray  # (N, 7) every object's pose at the end of the execution

    @property
    def outcome(self) -> str:
        """'success', 'start in collision', 'no contact', 'not held' or 'two objects lifted'."""
        return self.result.reason


def execute_in_scene(
    spec: SceneSpec, grasp, hand=None, closing: str = "full", settings: SimSettings | None = None
) -> SceneExecution:
    """Executes a Grasp among the scene's objects in Bullet. closing:
    "full" (the fingers close until they stop, force-limited: the experiment's rule) or "learnt" (just past
    the synthesised grasp joints); see graspmix.sim.execution.CLOSING."""
    s = make_settings(settings, **closing_overrides(closing))
    objs = _sim_objects(spec)
    if not objs:
        raise ValueError("execute_in_scene: the scene has no object")
    h = load_hand(hand)
    wrist, pre, fin = grasp_arrays(h, grasp)
    r = _core.sim_execute_scene(h, objs, spec.poses, wrist, pre, fin, s)
    poses = _canonical(np.asarray(r.object_poses))
    lifted = [int(i) for i in r.lifted]
    left = SceneSpec(
        [PlacedObject(o.urdf, p, o.scale) for i, (o, p) in enumerate(zip(spec.objects, poses)) if i not in lifted],
        spec.seed,
        spec.mode,
    )
    return SceneExecution(r.result, lifted, np.asarray(r.moved), settle(left, settings), poses)
