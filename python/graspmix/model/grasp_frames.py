"""What a robot stack needs of a grasp, computed from the hand's forward kinematics at the grasp joints
(the frames are defined in docs/hands-and-frames.md, "The grasps file and what a robot gets from it"):

- ``T_world_wrist_matrix``: the wrist pose as a 4x4 homogeneous matrix;
- fingertip links: the hand's (``Hand.fingertips``: given by its URDF's ``<graspmix fingertips>`` or inferred, the
  distal link of each finger chain);
- a link's fingertip point: the centre of the box around its collision vertices that lie within
  ``fingertip_tolerance`` of its farthest extent along the approach axis (in the wrist frame);
- ``T_world_tcp``: the tool centre point, the mean of the fingertip points (for two fingers their midpoint),
  oriented like the wrist;
- ``approach``: the hand's approach axis (``Hand.approach_axis``, in the wrist frame) in the world;
- ``closing`` and ``opening_width`` (two fingertip links only, a parallel gripper): the unit vector from the
  first fingertip point to the second (link order of the URDF), and the gap between the two links' collision
  geometry along it (m; the WSG 50's is twice its joint value);
- ``T_world_pregrasp`` / ``T_world_retreat``: the wrist moved back along the approach by
  ``pregrasp_distance`` / ``retreat_distance``, same orientation.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass, replace

import numpy as np

from ..io.checks import check_float

# The frame keys of a grasps.json entry, in their order (after the keys of the first release).
FRAME_KEYS = (
    "T_world_wrist_matrix",
    "T_world_tcp",
    "approach",
    "closing",
    "opening_width",
    "T_world_pregrasp",
    "T_world_retreat",
)


@dataclass(frozen=True)
class GraspFrameSettings:
    """How the exports of a grasp are made (a Python-only tool: the defaults live here once)."""

    # The hand's approach axis in the wrist frame; None: the hand's (Hand.approach_axis, which the experts use).
    approach_axis: tuple | None = None
    pregrasp_distance: float = 0.10  # m: stand-off of the pre-grasp wrist before the grasp, along -approach
    retreat_distance: float = 0.10  # m: how far the wrist backs out after closing, along -approach
    fingertip_tolerance: float = 0.002  # m: vertices this close to a link's far end form its fingertip
    fingertip_links: tuple = ()  # the fingertip links by name; empty: the hand's (Hand.fingertips)

    def checked(self) -> "GraspFrameSettings":
        if self.approach_axis is None:
            return self._checked_distances()
        axis = np.asarray(self.approach_axis, dtype=float)
        if axis.shape != (3,) or not np.all(np.isfinite(axis)) or not np.linalg.norm(axis) > 0:
            raise ValueError(f"approach_axis must be 3 finite numbers, not all zero, got {self.approach_axis!r}")
        return self._checked_distances()

    def _checked_distances(self) -> "GraspFrameSettings":
        check_float(self.pregrasp_distance, "pregrasp_distance", lo=0.0)
        check_float(self.retreat_distance, "retreat_distance", lo=0.0)
        check_float(self.fingertip_tolerance, "fingertip_tolerance", lo=0.0)
        return self

    def for_hand(self, hand) -> "GraspFrameSettings":
        """These settings with the hand's approach axis and fingertips where they leave them to the hand."""
        return replace(
            self,
            approach_axis=tuple(
                float(v) for v in (hand.approach_axis if self.approach_axis is None else self.approach_axis)
            ),
            fingertip_links=tuple(self.fingertip_links) or tuple(hand.fingertips),
        ).checked()

    def to_json(self) -> dict:
        axis = {} if self.approach_axis is None else {"approach_axis": [float(v) for v in self.approach_axis]}
        return {
            **axis,
            "pregrasp_distance": float(self.pregrasp_distance),
            "retreat_distance": float(self.retreat_distance),
            "fingertip_tolerance": float(self.fingertip_tolerance),
        }


def opening_widths(hand, joints) -> list:
    """The opening (``opening_width`` of FrameMaker.frames: the gap between the two fingertip links' collision
    geometry across the fingers, m; None unless the hand has two fingertip links) of `hand` at each configuration
    of `joints` (a list of name -> value, or of arrays in ``hand.joint_names`` order). ValueError for an unknown or
    missing joint. The wrist pose does not change it, so the wrist is placed at the origin."""
    if not len(joints):
        return []
    q = np.array([hand.joints_array(j) for j in joints], dtype=float)
    wrists = np.tile([0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0], (len(q), 1))
    return [f["opening_width"] for f in FrameMaker(hand).frames(wrists, q)]


def rotation_matrices(quats) -> np.ndarray:
    """Unit quaternions [qx, qy, qz, qw] (N, 4) as rotation matrices (N, 3, 3)."""
    q = np.asarray(quats, dtype=float).reshape(-1, 4)
    x, y, z, w = (q / np.linalg.norm(q, axis=1, keepdims=True)).T
    return np.stack(
        [
            np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)], axis=-1),
            np.stack([2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)], axis=-1),
            np.stack([2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)], axis=-1),
        ],
        axis=1,
    )


def pose_matrix(pose) -> np.ndarray:
    """A pose [x, y, z, qx, qy, qz, qw] (unit quaternion) as a 4x4 homogeneous matrix."""
    p = np.asarray(pose, dtype=float)
    T = np.eye(4)
    T[:3, :3] = rotation_matrices(p[3:7])[0]
    T[:3, 3] = p[:3]
    return T


def _distinct_rows(V: np.ndarray) -> np.ndarray:
    """The distinct rows of V (a mesh file repeats a vertex for each triangle it is in; the frames use the
    vertices' extremes, which the copies do not change), by sorting, without np.unique."""
    if len(V) == 0:
        return V
    S = V[np.lexsort(V.T)]
    return S[np.r_[True, np.any(S[1:] != S[:-1], axis=1)]]


# hand -> {link name: its distinct collision vertices}: a hand's geometry does not change, and a mesh link's
# vertices take milliseconds to gather (the xArm's fingertips have 10k mesh vertices, 2,426 distinct)
_VERTICES: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()


def link_vertices(hand, name: str) -> np.ndarray:
    """The distinct collision vertices of link `name` of `hand` (those its triangles use; link frame, read-only),
    gathered once per hand. ValueError for a link without collision geometry."""
    per_hand = _VERTICES.setdefault(hand, {})
    if name not in per_hand:
        V, T = hand.collision_mesh(name)
        if len(T) == 0:
            raise ValueError(f"fingertip link {name!r} of hand '{hand.name}' has no collision geometry")
        used = np.zeros(len(V), dtype=bool)  # not np.unique: its first call imports numpy.ma (~35 ms)
        used[np.asarray(T).ravel()] = True
        V = _distinct_rows(np.asarray(V)[used])
        V.flags.writeable = False
        per_hand[name] = V
    return per_hand[name]


# Fingertip links with more distinct vertices than this keep, for the frames' products, only those that can decide them.
MANY_VERTICES = 256
# m: how far beyond fingertip_tolerance a vertex inside a hull is still kept (against rounding, which is ~1e-15 m)
HULL_MARGIN = 1e-6


def frame_vertices(hand, name: str, tolerance: float) -> np.ndarray:
    """The rows of link_vertices(hand, name) that can decide a frame, in their order: those not deeper than
    `tolerance` + HULL_MARGIN inside the convex hull of one of the link's mesh shapes (the hand's hull_planes, in the
    shape frame; loosened by however far the shape's own vertices stand outside them). The frames use, along a unit
    direction, the vertices' largest (or smallest) value and those within `tolerance` of it; a vertex at depth g
    inside a hull within the link's vertices' hull is at least g short of that largest value along every direction,
    so the frames of these rows are those of all, bit for bit (the same products, a subset of rows). All rows for a
    link of up to MANY_VERTICES. Cached per hand."""
    V = link_vertices(hand, name)
    key = (name, float(tolerance))
    per_hand = _VERTICES[hand]
    if key in per_hand:
        return per_hand[key]
    keep = np.ones(len(V), dtype=bool)
    if len(V) > MANY_VERTICES:
        for shape in hand.collision_shapes(name):
            planes = shape.get("hull_planes")
            if planes is None or len(planes) == 0:
                continue
            planes = np.asarray(planes, dtype=float)
            n, offset = planes[:, :3], planes[:, 3]
            origin = np.asarray(shape["origin"], dtype=float)
            X = (V - origin[:3]) @ rotation_matrices(origin[3:])[0]  # the link's vertices in the shape frame
            loose = max(0.0, float(np.max(np.asarray(shape["vertices"], dtype=float) @ n.T - offset)))
            depth = np.min(offset - X @ n.T, axis=1)
            keep &= depth <= tolerance + HULL_MARGIN + loose
    out = V[keep]
    out.flags.writeable = False
    per_hand[key] = out
    return out


# The multiply-adds of a product that BLAS (OpenBLAS) computes on the calling thread; above it, it wakes its threads.
BLAS_SERIAL_MADDS = 2**18


def vertex_products(V: np.ndarray, b: np.ndarray) -> np.ndarray:
    """V @ b.T (V (m, 3), b (n, 3)) in blocks of b's rows small enough for BLAS to compute each on this thread: waking
    its threads costs more than such a product (milliseconds on a busy machine: the xArm's fingertips have 2,426
    vertices) and leaves them spinning for a while, taking the cores from what runs next. Every block has two rows
    or more (with one it would be a matrix-vector product, which rounds differently), so each value is the one
    product's, bit for bit (tests/python/model/test_grasp_frames.py)."""
    n = len(b)
    blocks = min(-(-len(V) * n * 3 // BLAS_SERIAL_MADDS), n // 2)
    if blocks <= 1:
        return V @ b.T
    return np.hstack([V @ part.T for part in np.array_split(b, blocks)])


class FrameMaker:
    """Computes the frames of grasps of one hand (batched over the grasps)."""

    def __init__(self, hand, settings: GraspFrameSettings | None = None):
        """settings: how (default GraspFrameSettings(): the hand's approach axis and fingertips)."""
        self.settings = (settings or GraspFrameSettings()).for_hand(hand)
        self.hand, self.tips = hand, list(self.settings.fingertip_links)
        for n in self.tips:
            if n not in hand.link_names:
                raise ValueError(f"fingertip link {n!r} is not a link of hand '{hand.name}'")
        axis = np.asarray(self.settings.approach_axis, dtype=float)
        self.axis = axis / np.linalg.norm(axis)
        self.rows = [hand.link_index(n) for n in self.tips]
        # each fingertip link's collision vertices (those its triangles use), link frame, and those of them that
        # decide the frames along a unit direction
        self.vertices = [link_vertices(hand, n) for n in self.tips]
        self.deciding = [frame_vertices(hand, n, self.settings.fingertip_tolerance) for n in self.tips]

    def frames(self, wrists: np.ndarray, joints: np.ndarray) -> list[dict]:
        """The frame keys (FRAME_KEYS) of grasps with wrists (N, 7) and grasp joints (N, n_dofs)."""
        wrists = np.atleast_2d(np.asarray(wrists, dtype=float))
        links = np.asarray(self.hand.fk_batch(wrists, np.atleast_2d(np.asarray(joints, dtype=float))))
        R = rotation_matrices(wrists[:, 3:])
        n, s = len(wrists), self.settings
        M = np.zeros((n, 4, 4))
        M[:, :3, :3], M[:, :3, 3], M[:, 3, 3] = R, wrists[:, :3], 1.0
        approach = R @ self.axis
        tips = self._tips(links, wrists, R)
        cols = {
            "T_world_wrist_matrix": M.tolist(),
            "T_world_tcp": [None] * n,
            "approach": approach.tolist(),
            "closing": [None] * n,
            "opening_width": [None] * n,
            "T_world_pregrasp": np.hstack([wrists[:, :3] - s.pregrasp_distance * approach, wrists[:, 3:]]).tolist(),
            "T_world_retreat": np.hstack([wrists[:, :3] - s.retreat_distance * approach, wrists[:, 3:]]).tolist(),
        }
        if tips:
            cols["T_world_tcp"] = np.hstack([np.mean(tips, axis=0), wrists[:, 3:]]).tolist()
        if len(tips) == 2:
            c = tips[1] - tips[0]
            norm = np.linalg.norm(c, axis=1, keepdims=True)
            c /= np.maximum(norm, 1e-12)
            cols["closing"] = c.tolist()
            # The deciding vertices decide along unit directions: all of them where the fingertips coincide.
            vs = self.deciding if np.all(norm >= 1e-12) else self.vertices
            cols["opening_width"] = (
                self._along(links, 1, c, V=vs[1]).min(axis=0) - self._along(links, 0, c, V=vs[0]).max(axis=0)
            ).tolist()
        return [{k: cols[k][i] for k in FRAME_KEYS} for i in range(n)]

    def _along(self, links, k, d, origin=None, *, V):
        """(V, N): each vertex V (of fingertip link k) measured along the world directions d (N, 3) from origin (N, 3;
        default the world's), for every grasp: one matrix product, without the vertices' world positions."""
        row = self.rows[k]
        b = np.einsum("nji,nj->ni", rotation_matrices(links[:, row, 3:]), d)  # d in the link frame
        t = links[:, row, :3] if origin is None else links[:, row, :3] - origin
        return vertex_products(V, b) + np.einsum("ni,ni->n", t, d)[None, :]

    def _tips(self, links, wrists, R):
        """The fingertip point per tip link (N, 3): the box, in the wrist frame, of the link's vertices within
        fingertip_tolerance of its farthest extent along the approach."""
        tips = []
        approach = R @ self.axis
        for k, (row, V) in enumerate(zip(self.rows, self.deciding)):
            along = self._along(links, k, approach, wrists[:, :3], V=V)
            near = along >= along.max(axis=0, keepdims=True) - self.settings.fingertip_tolerance
            g, v = np.nonzero(near.T)  # (grasp, vertex) pairs, grasp-major: few vertices per grasp, one at least
            # The near vertices in the wrist frame: R^T (R_link v + t_link - t_wrist).
            M = np.einsum("nji,njk->nik", R, rotation_matrices(links[:, row, 3:]))
            off = np.einsum("nji,nj->ni", R, links[:, row, :3] - wrists[:, :3])
            local = np.einsum("kij,kj->ki", M[g], V[v]) + off[g]
            starts = np.searchsorted(g, np.arange(len(wrists)))
            lo, hi = np.minimum.reduceat(local, starts, axis=0), np.maximum.reduceat(local, starts, axis=0)
            tips.append(np.einsum("nij,nj->ni", R, (lo + hi) / 2) + wrists[:, :3])
        return tips
