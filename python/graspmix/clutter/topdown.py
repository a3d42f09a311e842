"""The top-down baseline planner: what a grasp planner without a learnt model does on a segmented scene.

For one object (a segmented cluster: its points): the WSG 50 comes straight down (palm z along -z of the
world, the table being horizontal); the fingers close along the object's narrowest horizontal axis, the
direction across which its points projected on the table are narrowest (the normal of the convex hull
edge of least width: a parallel gripper's minimum-width direction, exact for a box seen from any side);
the hand is centred between the two extremes of the points along that axis and at their centroid along
the other horizontal axis; the fingertips go GRASP_DEPTH below the object's top, but never lower than
TIP_MARGIN above the table clearance; the pre-grasp opening is the hand's maximum and the grasp joints
are fully closed (the simulation's "full" closing stops the fingers on the object).

Which object, in a scene: the highest (the greatest top above the table), as a pile is cleared from the
top, where neighbours are least in the way.

    grasp, index = plan_topdown(scene)            # scene: graspmix.segment_scene(points, viewpoints)
    grasp = topdown_grasp(points, plane=None)      # one object's (n, 3) points
"""

from __future__ import annotations

import math

import numpy as np

from ..io import as_points
from ..model.grasps import Grasp
from ..model.options import TABLE_CLEARANCE
from ..sim.execution import load_hand, top_grasp

GRASP_DEPTH = 0.04  # m: fingertips this far below the object's top (about half the WSG 50's 73 mm fingers)
TIP_MARGIN = 0.005  # m: fingertips at least this far above the table clearance (they must not scrape it)
WSG50_LINKS = ("palm", "finger_left", "finger_right")


def check_hand(hand) -> object:
    """The hand, if the top-down planner can drive it: the WSG 50's links and one prismatic joint (its
    geometry, the fingertips 153.5 mm below the flange, is that of top_grasp); ValueError otherwise."""
    h = load_hand(hand)
    if tuple(h.link_names) != WSG50_LINKS or h.n_dofs != 1:
        raise ValueError(
            f"the top-down planner drives the WSG 50 only (links {', '.join(WSG50_LINKS)}, one joint); "
            f"hand {h.name!r} has links {', '.join(h.link_names)} and {h.n_dofs} joints"
        )
    return h


def _table_height(plane, xy) -> float:
    """z of the table under (x, y): the plane a x + b y + c z + d = 0, or z = 0 without one."""
    if plane is None:
        return 0.0
    a, b, c, d = (float(v) for v in np.asarray(plane, dtype=float).reshape(4))
    if abs(c) < 0.5 * math.sqrt(a * a + b * b + c * c):
        raise ValueError(f"the top-down planner needs a roughly horizontal table, got the plane {[a, b, c, d]}")
    return -(a * xy[0] + b * xy[1] + d) / c


def narrowest_axis(xy: np.ndarray) -> tuple[np.ndarray, float]:
    """(unit direction, width): the horizontal direction across which the 2-D points are narrowest. The
    minimum width of a convex polygon is taken across one of its edges, so the candidates are the hull
    edges' normals; fewer than 3 distinct or collinear points: the minor axis of their covariance."""
    from scipy.spatial import ConvexHull, QhullError

    try:
        hull = xy[ConvexHull(xy).vertices]
    except (QhullError, ValueError):
        hull = None
    if hull is None:
        w, v = np.linalg.eigh(np.cov(xy.T) if len(xy) > 1 else np.eye(2))
        n = v[:, 0]
        return n, float(np.ptp(xy @ n))
    edges = np.roll(hull, -1, axis=0) - hull
    normals = np.stack([-edges[:, 1], edges[:, 0]], axis=1)
    normals /= np.linalg.norm(normals, axis=1, keepdims=True)
    widths = np.ptp(hull @ normals.T, axis=0)
    i = int(np.argmin(widths))
    return normals[i], float(widths[i])


def topdown_grasp(points, plane=None, hand=None, table_clearance: float = TABLE_CLEARANCE) -> Grasp:
    """A top-down grasp of the object whose (n, 3) points are given (world frame, z up). plane: the table
    [a, b, c, d] (default z = 0). The grasp's `object` is left for the caller."""
    h = check_hand(hand)
    p = as_points(points)
    xy = p[:, :2]
    n, _ = narrowest_axis(xy)
    along = xy @ n
    perp = np.array([-n[1], n[0]])
    centre = n * 0.5 * (along.min() + along.max()) + perp * float(np.mean(xy @ perp))
    table = _table_height(plane, centre)
    top = float(p[:, 2].max()) - table
    tip = max(top - GRASP_DEPTH, table_clearance + TIP_MARGIN) + table
    lo, hi = h.joint_limits[0]
    return top_grasp(centre, float(hi), float(lo), yaw=math.atan2(n[1], n[0]), tip_height=tip, hand=h)


def plan_topdown(scene, hand=None, table_clearance: float = TABLE_CLEARANCE) -> tuple[Grasp, int]:
    """(grasp, object index) for the highest object of a segmented scene (graspmix.segment_scene's Scene:
    .objects with .index and .points, .plane). ValueError if the scene has no object."""
    objects = list(scene.objects)
    if not objects:
        raise ValueError("the scene has no object to grasp")
    plane = scene.plane
    tops = [float(o.points[:, 2].max()) - _table_height(plane, o.points[:, :2].mean(0)) for o in objects]
    best = objects[int(np.argmax(tops))]
    grasp = topdown_grasp(best.points, plane, hand, table_clearance)
    grasp.object = int(best.index)
    return grasp, int(best.index)
