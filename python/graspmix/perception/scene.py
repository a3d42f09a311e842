"""Scene: a segmented scene cloud (graspmix._core.segment_scene) with numpy arrays, target selection and
a JSON form; camera_to_world for clouds given in a camera's frame."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import _core
from ..io import as_points, quote

# m: a "point:x,y,z" target farther than this from every object's points names no object (a click or a
# typed point lands on the surface the camera saw, within a few voxels of it).
POINT_TARGET_MAX_DISTANCE = _core.POINT_TARGET_MAX_DISTANCE  # m (include/graspmix/perception/targets.hpp)
TARGET_KINDS = ("all", "largest", "nearest")


@dataclass(frozen=True)
class Target:
    """What to grasp: kind "all" | "largest" | "nearest" | "index" (with index) | "point" (with point)."""

    kind: str
    index: int | None = None
    point: tuple[float, float, float] | None = None

    def __str__(self) -> str:
        if self.kind == "index":
            return str(self.index)
        if self.kind == "point":
            return "point:" + ",".join(f"{v:g}" for v in self.point)
        return self.kind


INDEX_MAX = 2**31 - 1  # an object index C++ can hold


def _index_target(index: int) -> Target:
    if not 0 <= index <= INDEX_MAX:
        raise ValueError(f"target: the object index {index} is out of range (the scene's objects count from 0)")
    return Target("index", index=index)


def parse_target(text) -> Target:
    """A Target from "all", "largest", "nearest", an object index ("2") or "point:x,y,z" (metres, the
    cloud's frame); ValueError naming the text otherwise. A Target or an int passes through."""
    if isinstance(text, Target):
        return text
    if isinstance(text, (int, np.integer)) and not isinstance(text, bool):
        return _index_target(int(text))
    if not isinstance(text, str):
        raise ValueError(f"target must be a string or an object index, got {type(text).__name__}")
    t = text.strip()
    if t in TARGET_KINDS:
        return Target(t)
    if t.isdigit():
        return _index_target(int(t))
    if t.startswith("point:"):
        try:
            xyz = tuple(float(v) for v in t[len("point:") :].split(","))
        except ValueError:
            xyz = ()
        if len(xyz) != 3 or not all(math.isfinite(v) for v in xyz):
            raise ValueError(f"target: expected point:x,y,z with three finite numbers (m), got {quote(text)}")
        return Target("point", point=xyz)
    raise ValueError(f"target: expected all, largest, nearest, an object index or point:x,y,z, got {quote(text)}")


@dataclass(frozen=True)
class SceneObject:
    """One object: a Euclidean cluster above the support plane."""

    index: int
    points: np.ndarray  # (n, 3) its points (voxelised), m
    rows: np.ndarray  # (n,) its rows of Scene.points
    centroid: np.ndarray  # (3,)
    obb_center: np.ndarray  # (3,) oriented bounding box
    obb_rotation: np.ndarray  # (3, 3) columns: the box's axes, by decreasing variance
    obb_extents: np.ndarray  # (3,) side lengths along them
    n_points: int

    def to_dict(self) -> dict:
        return {
            "index": self.index,
            "n_points": self.n_points,
            "centroid": self.centroid.tolist(),
            "obb_center": self.obb_center.tolist(),
            "obb_rotation": self.obb_rotation.tolist(),
            "obb_extents": self.obb_extents.tolist(),
        }


def _finite_or_none(v: float):
    return float(v) if math.isfinite(v) else None


class Scene:
    """The support plane and the objects of a scene cloud (made by segment_scene)."""

    def __init__(self, result, viewpoints: np.ndarray | None, *, point_viewpoints: np.ndarray | None = None):
        """result: the C++ Segmentation; viewpoints: the cameras as given to the segmentation (None, (3,) or one per
        input point); point_viewpoints: instead, the camera of each kept point already worked out ((M, 3), or (0, 3)
        for none: _core.SceneSynthesis.viewpoints)."""
        self.result = result  # the C++ Segmentation, for its every count
        self.plane = None if result.plane is None else np.asarray(result.plane, dtype=float)
        self.plane_found = bool(result.plane_found)
        self.plane_given = bool(result.plane_given)
        self.points = np.asarray(result.points)
        self.labels = np.asarray(result.labels)
        self.sources = np.asarray(result.sources)
        self.viewpoints = None  # (M, 3) the camera that saw each kept point, or None without viewpoints
        if point_viewpoints is not None:
            self.viewpoints = np.asarray(point_viewpoints, dtype=float) if len(point_viewpoints) else None
        elif viewpoints is not None:
            vp = np.asarray(viewpoints, dtype=float)
            per_point = vp.ndim == 2 and len(vp) > 1
            self.viewpoints = vp[self.sources] if per_point else np.tile(vp.reshape(3), (len(self.points), 1))
        self.objects = [
            SceneObject(
                index=o.index,
                points=self.points[np.asarray(o.rows)],
                rows=np.asarray(o.rows),
                centroid=np.asarray(o.centroid),
                obb_center=np.asarray(o.obb_center),
                obb_rotation=np.asarray(o.obb_rotation),
                obb_extents=np.asarray(o.obb_extents),
                n_points=int(o.n_points),
            )
            for o in result.objects
        ]
        # per object: its Completion (graspmix.complete_object) once Scene.complete ran, else None
        self.completions: list = [None] * len(self.objects)
        self.notes: list[str] = []  # what a user should know of this scene (e.g. why nothing was completed)
        # the whole segmentation, then each of its steps (Segmentation.step_seconds)
        self.timing = {"segmentation": float(result.seconds)}
        self.timing.update({f"segmentation.{k}": float(v) for k, v in result.step_seconds.items()})

    def __len__(self) -> int:
        return len(self.objects)

    @property
    def visibility(self):
        """The VisibilityModel of what the cameras saw (None without viewpoints)."""
        return self.result.visibility

    def complete(self, settings=None) -> "Scene":
        """Completes every object's unseen side (graspmix.complete_object, by its rule) from what the cameras
        saw; completions[i] holds object i's. Without viewpoints or a support plane nothing is completed, and an
        object complete_object refuses (e.g. seen by a camera in the support plane) stays as seen: `notes` says
        why. Bad settings are a ValueError. Returns the scene."""
        return self.take_completion(_core.complete_scene(self.result, settings=settings))

    def take_completion(self, done) -> "Scene":
        """Keeps a _core.SceneCompletion of this scene (complete_scene's, or synthesize_scene's): completions[i]
        object i's, its notes, its time (when anything could be completed). Returns the scene."""
        self.completions = list(done.completions)
        self.notes.extend(done.notes)
        if self.visibility is not None and self.plane is not None:
            self.timing["completion"] = float(done.seconds)
        return self

    def completed(self, index: int) -> tuple[np.ndarray, np.ndarray]:
        """(points (k, 3), outward normals (k, 3)) completed on object `index`; (0, 3) arrays when none."""
        c = self.completions[index]
        if c is None or len(c.points) == 0:
            return np.zeros((0, 3)), np.zeros((0, 3))
        return np.asarray(c.points), np.asarray(c.normals)

    def solid_points(self, without: int | None = None) -> np.ndarray:
        """The objects' observed points and every completed point, but object `without`'s: what a hand must stay
        out of."""
        kept = [o for o in self.objects if o.index != without]
        observed = self.points if without is None else self.points[self.labels != without]
        return np.vstack([observed, *(self.completed(o.index)[0] for o in kept)])

    def __repr__(self) -> str:
        plane = "given" if self.plane_given else ("found" if self.plane_found else "none")
        return f"<Scene {len(self.objects)} objects, {len(self.points)} points, plane {plane}>"

    def select(self, target="all", camera=None) -> list[int]:
        """Object indices for a target (parse_target's forms): "all" every object; an index; "point:x,y,z"
        the object with a point nearest to it (ValueError beyond POINT_TARGET_MAX_DISTANCE); "largest" the
        object with the most points (what the grasp sampler works on; an OBB volume is inflated by the
        flying pixels at silhouettes and by the hidden side of a one-view object); "nearest" the object with
        the point nearest to a camera: `camera` (3,) if given, else the camera that saw each point (the
        viewpoints given), else the origin."""
        t = parse_target(target)
        if camera is not None:
            camera = np.asarray(camera, dtype=float)
            if camera.shape != (3,):
                raise ValueError(f"camera: expected a finite (3,) position, got shape {camera.shape}")
        return list(
            _core.select_targets(self.result, self.viewpoints, t.kind, index=t.index, point=t.point, camera=camera)
        )

    def to_dict(self) -> dict:
        """A JSON-ready summary: the plane (with the rule's figures), the objects, the counts, the time."""
        r = self.result
        return {
            "plane": None if self.plane is None else self.plane.tolist(),
            "plane_found": self.plane_found,
            "plane_given": self.plane_given,
            "candidates": [
                {
                    "plane": list(map(float, c.plane)),
                    "n_inliers": c.n_inliers,
                    "inlier_fraction": c.inlier_fraction,
                    "camera_height": c.camera_height,
                    "behind_fraction": c.behind_fraction,
                    "margin": _finite_or_none(c.margin),
                    "accepted": c.accepted,
                    "refused_by": c.refused_by,
                    "reason": c.reason,
                }
                for c in r.candidates
            ],
            "objects": [
                {**o.to_dict(), "completion": completion_dict(c)} for o, c in zip(self.objects, self.completions)
            ],
            "notes": list(self.notes),
            "counts": {
                "input": r.n_input,
                "after_voxel": r.n_after_voxel,
                "plane": r.n_plane,
                "outliers": r.n_outliers,
                "small_clusters": r.n_small_clusters,
                "merged": r.n_merged,
                "joined": r.n_joined,
                "split": r.n_split,
                "output": r.n_output,
            },
            "timing_s": dict(self.timing),
        }


def kind_name(kind) -> str:
    """A CompletionKind as a word: "mirror", "rotation", "extrusion", "none"."""
    return kind.name.rstrip("_").lower()


def completion_dict(c) -> dict | None:
    """A Completion's summary: the winning hypothesis, its score, the points it added, every hypothesis scored (its
    time is in the scene's timing, "completion")."""
    if c is None:
        return None
    return {
        "kind": kind_name(c.kind),
        "score": float(c.score),
        "n_points": len(c.points),
        "warning": c.warning,
        "hypotheses": [
            {k: (kind_name(v) if k == "kind" else _json_value(v)) for k, v in h.items()} for h in c.hypotheses
        ],
    }


def _json_value(v):
    if isinstance(v, np.ndarray):
        return v.tolist()
    if isinstance(v, (bool, np.bool_)):
        return bool(v)
    return float(v)


def segment_scene(points, viewpoints=None, plane=None, **settings) -> Scene:
    """The support plane and the objects of a scene cloud (N, 3), seen from viewpoints (None: a camera at
    the origin, the PCD convention; (3,) one camera; (N, 3) one per point); plane [a, b, c, d] gives a known
    support, turned towards the cameras. Keywords: SegmentationSettings' fields (or settings=). ValueError
    on bad input, and when no object stands above the plane."""
    pts = as_points(points)
    vp = None
    if viewpoints is not None:
        vp = np.asarray(viewpoints, dtype=float)
        if vp.shape not in ((3,), (1, 3), (len(pts), 3)):
            raise ValueError(
                f"viewpoints: expected shape (3,) or ({len(pts)}, 3) for {len(pts)} points, got {vp.shape}"
            )
    return Scene(_core.segment_scene(pts, vp, plane, **settings), vp)


def camera_to_world(points, pose) -> tuple[np.ndarray, np.ndarray]:
    """(world points (N, 3), camera position (3,)) of points given in a camera's frame, with the camera's
    pose T_world_camera = [x, y, z, qx, qy, qz, qw]; ValueError when the quaternion is not a unit one (the C++
    check: graspmix._core.camera_pose_matrix)."""
    pts = as_points(points)
    p = np.asarray(pose, dtype=float)
    if p.shape != (7,):
        raise ValueError(f"camera pose: expected 7 numbers x, y, z, qx, qy, qz, qw, got shape {p.shape}")
    T = np.asarray(_core.camera_pose_matrix(p))
    return pts @ T[:3, :3].T + T[:3, 3], T[:3, 3].copy()


def in_world(points, viewpoints, camera_pose):
    """(points, viewpoints) in the world frame: a cloud in a camera's frame (camera_pose, as camera_to_world) is
    mapped to the world and the camera becomes its viewpoint; viewpoints given in the camera's frame are mapped
    with it. No camera_pose: both as they are."""
    if camera_pose is None:
        return points, viewpoints
    world, camera = camera_to_world(points, camera_pose)
    if viewpoints is None:
        return world, camera
    return world, camera_to_world(np.asarray(viewpoints, dtype=float).reshape(-1, 3), camera_pose)[0].squeeze()
