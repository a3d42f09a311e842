"""Objects found vs placed: segment_scene's clusters judged against the simulation's per-point object ids.

A scene of the clutter protocol (make_scene, pile or packed) is observed as a round observes it
(acquire_scene: one 640x480 camera, the labels of the renderer's segmentation mask follow every point) and
segmented; each cluster's points carry the id of the object they were rendered on (Segmentation.sources).

A cluster *holds* an object when at least HOLD_FRACTION of its points (and MIN_HOLD_POINTS) lie on it.
Each cluster is then
  - "one": it holds one object, and no other cluster holds that object (correct);
  - "piece": it holds one object that another cluster holds too (a split);
  - "merged": it holds several objects;
  - "other": it holds none (the table's points above the clearance, flying pixels).
An object is "visible" when at least MIN_VISIBLE_POINTS of the cloud's points lie on it (a fully hidden one
cannot be found from one view), "found whole" when a "one" cluster holds it, "missed" when no cluster does.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

HOLD_FRACTION = 0.2  # of a cluster's points: a smaller share is a neighbour's flying pixels at its edge
MIN_HOLD_POINTS = 10  # voxelised points
MIN_VISIBLE_POINTS = 50  # raw points of the cloud (a 640x480 view; min_cluster_size is 20 voxels)
KINDS = ("one", "piece", "merged", "other")


@dataclass
class SceneConfusion:
    """One scene's counts."""

    placed: int
    visible: int
    found: int
    clusters: dict = field(default_factory=dict)  # kind -> number of clusters
    whole: int = 0  # visible objects found as one cluster
    missed: int = 0  # visible objects no cluster holds

    def to_dict(self) -> dict:
        return {
            "placed": self.placed,
            "visible": self.visible,
            "found": self.found,
            "clusters": dict(self.clusters),
            "whole": self.whole,
            "missed": self.missed,
        }


def cluster_kinds(cluster_labels: list[np.ndarray]) -> tuple[list[str], list[list[int]]]:
    """Per cluster (the object ids of its points, -1 for the table), its kind and the objects it holds."""
    held = []
    for ids in cluster_labels:
        ids = np.asarray(ids)
        objs, counts = np.unique(ids[ids >= 0], return_counts=True)
        keep = (counts >= MIN_HOLD_POINTS) & (counts >= HOLD_FRACTION * max(len(ids), 1))
        held.append([int(o) for o in objs[keep]])
    holders: dict[int, int] = {}
    for h in held:
        for o in h:
            holders[o] = holders.get(o, 0) + 1
    kinds = []
    for h in held:
        if not h:
            kinds.append("other")
        elif len(h) > 1:
            kinds.append("merged")
        else:
            kinds.append("piece" if holders[h[0]] > 1 else "one")
    return kinds, held


def scene_confusion(point_ids: np.ndarray, object_rows: list[np.ndarray], cloud_ids: np.ndarray, placed: int):
    """The counts of one segmented scene: point_ids (M,) the object id of each segmented point, object_rows
    each cluster's rows of them, cloud_ids (N,) the ids of the whole cloud (for what was visible)."""
    kinds, held = cluster_kinds([point_ids[np.asarray(r)] for r in object_rows])
    ids, counts = np.unique(np.asarray(cloud_ids)[np.asarray(cloud_ids) >= 0], return_counts=True)
    visible = {int(o) for o, c in zip(ids, counts) if c >= MIN_VISIBLE_POINTS}
    whole = {h[0] for k, h in zip(kinds, held) if k == "one"}
    anywhere = {o for h in held for o in h}
    return SceneConfusion(
        placed=placed,
        visible=len(visible),
        found=len(object_rows),
        clusters={k: kinds.count(k) for k in KINDS},
        whole=len(whole & visible),
        missed=len(visible - anywhere),
    )


def confusion_of(acq, placed: int, **settings) -> tuple[SceneConfusion, object]:
    """segment_scene on an acquisition (acquire_scene's, with labels) and its counts; the Scene too."""
    from ..perception import segment_scene

    scene = segment_scene(acq.points, acq.viewpoints, **settings)
    point_ids = np.asarray(acq.labels)[scene.sources]
    return scene_confusion(point_ids, [o.rows for o in scene.objects], acq.labels, placed), scene


def total(rows: list[SceneConfusion]) -> dict:
    """The counts summed over scenes, and the scenes whose every visible object was found whole."""
    out = {k: sum(getattr(r, k) for r in rows) for k in ("placed", "visible", "found", "whole", "missed")}
    out.update({k: sum(r.clusters.get(k, 0) for r in rows) for k in KINDS})
    out["scenes"] = len(rows)
    out["scenes_exact"] = sum(r.whole == r.visible and r.found == r.visible for r in rows)
    return out
