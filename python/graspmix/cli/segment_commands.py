"""graspmix_cli segment: the support plane and the objects of a scene cloud (graspmix.segment_scene) or of one
camera's depth image (graspmix.segment_view)."""

from __future__ import annotations

import argparse
import json
import sys

import numpy as np

from .. import _core
from ..perception import CameraView, kind_name, quaternion_order_note, scene_input, segment_scene, segment_view
from .common import box, float_in, given, input_path, int_in, picture_file, seed
from .views import add_view_arguments, input_keywords, known_plane


def _plane_lines(scene) -> list[str]:
    d = scene.to_dict()
    if scene.plane_given:
        head = "plane: given"
    elif scene.plane_found:
        head = "plane: found"
    else:
        head = "plane: none (no candidate passed the support rule: every point is an object point)"
    lines = [
        head + ("" if scene.plane is None else f" [{', '.join(f'{v:.4f}' for v in scene.plane)}] (towards the cameras)")
    ]
    for c in d["candidates"]:
        margin = "-" if c["margin"] is None or np.isnan(c["margin"]) else f"{c['margin']:.3f} m"
        verdict = "support" if c["accepted"] else c["reason"]
        lines.append(
            f"  candidate [{', '.join(f'{v:.3f}' for v in c['plane'])}]: {c['inlier_fraction']:.1%} of the points, "
            f"cameras {c['camera_height']:.3f} m above, {c['behind_fraction']:.1%} behind, reach {margin}: {verdict}"
        )
    return lines


def cmd_segment(args) -> int:
    keywords = input_keywords(args, "the scene cloud")
    source, _, notes = scene_input(**keywords)
    settings = given(
        args, "cluster_tolerance", "min_cluster_size", "table_clearance", "voxel_size", "seed", "workspace"
    )
    if isinstance(source, CameraView):
        scene = segment_view(source, known_plane(args), _core.SegmentationSettings(**settings))
        points = source.world_points()
    else:
        points, viewpoints = source
        scene = segment_scene(points, viewpoints, known_plane(args), **settings)
    order = quaternion_order_note(keywords.get("camera_pose"), scene.plane if scene.plane_found else None)
    scene.notes[:0] = notes + ([order] if order else [])
    if args.completion:
        scene.complete()
    for note in scene.notes:
        print(f"graspmix_cli segment: note: {note}", file=sys.stderr)
    if args.png:
        from ..viz import plot_scene

        plot_scene(scene, args.png, cloud=points)
    if args.json:
        print(json.dumps(scene.to_dict(), allow_nan=False))
        return 0
    for line in _plane_lines(scene):
        print(line)
    print(f"objects: {len(scene.objects)}")
    for o in scene.objects:
        c, e = o.centroid, o.obb_extents
        print(
            f"  {o.index}: {o.n_points} points, centroid [{c[0]:.3f}, {c[1]:.3f}, {c[2]:.3f}] m, "
            f"box {e[0] * 100:.1f} x {e[1] * 100:.1f} x {e[2] * 100:.1f} cm" + completion_text(scene, o.index)
        )
    r = scene.result
    print(
        f"points: {r.n_input} in, {r.n_after_voxel} after the voxel grid, {r.n_plane} table, {r.n_outliers} outliers, "
        f"{r.n_small_clusters} in clusters too small (noise), {r.n_merged} clusters joined to a larger one seen through it, "
        f"{r.n_joined} joined to another across a gap the camera did not see (a shadow), {r.n_output} on objects"
    )
    steps = ", ".join(f"{k} {v * 1e3:.1f}" for k, v in scene.result.step_seconds.items())
    print(f"time: {scene.timing['segmentation'] * 1e3:.1f} ms ({steps})")
    if args.png:
        print(f"picture: {args.png}")
    return 0


def completion_text(scene, index: int) -> str:
    """ ", completed: <kind> (score s) +k points[; warning]" for an object Scene.complete completed, else ""."""
    c = scene.completions[index]
    if c is None:
        return ""
    text = f"; completed: {kind_name(c.kind)} (score {c.score:.2f}) +{len(c.points)} points"
    return text + (f"; {c.warning}" if c.warning else "")


COMMANDS = ("segment",)


def add_parsers(sub) -> None:
    s = sub.add_parser("segment", help="the support plane and the objects of a scene cloud (.pcd/.ply/.npy)")
    s.add_argument(
        "--cloud", type=input_path, help="the scene cloud (.pcd, .ply, or .npy (N, 3)); required unless --depth"
    )
    add_view_arguments(s)
    s.add_argument("--png", type=picture_file, help="write a picture of the objects over the plane")
    s.add_argument("--json", action="store_true", help="print the segmentation as JSON instead")
    s.add_argument(
        "--completion",
        action=argparse.BooleanOptionalAction,
        default=True,
        help="complete each object's unseen side from what the camera saw (graspmix.complete_object; default on)",
    )
    tuning = s.add_argument_group("settings (default: SegmentationSettings')")
    tuning.add_argument("--cluster-tolerance", type=float_in(gt=0.0), help="m: points closer are one object")
    tuning.add_argument("--min-cluster-size", type=int_in(1), help="smaller clusters are noise")
    tuning.add_argument("--table-clearance", type=float_in(0.0), help="m above the plane that is still the table")
    tuning.add_argument("--voxel-size", type=float_in(0.0), help="m: voxel-grid leaf (0 = off)")
    tuning.add_argument("--seed", type=seed, help="seed of the RANSAC plane search")
    tuning.add_argument(
        "--workspace",
        type=box,
        metavar="X0,Y0,Z0,X1,Y1,Z1",
        help="m: the box in the world frame the cloud or image is cropped to first (default: none)",
    )
    s.set_defaults(func=cmd_segment)
