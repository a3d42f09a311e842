"""scene: a scene of several objects on the table, built in the simulation (pile or packed, after VGN)."""

from __future__ import annotations

import argparse
import time

from ..io import data_path
from .common import input_path, int_in, output_file, seed


def cmd_scene(args: argparse.Namespace) -> int:
    from ..sim import scene_camera, scenes

    objects = scenes.choose_objects(args.object_list or data_path("objects", "test60.txt"), args.objects, args.seed)
    t0 = time.perf_counter()
    spec = scenes.make_scene(objects, args.mode, args.seed)
    dt = time.perf_counter() - t0
    spec.save(args.out)
    print(
        f"{args.mode} scene of {len(spec.objects)} of {len(objects)} objects (seed {args.seed}; the others were "
        f"left out or fell off the workspace) built in {dt:.2f} s; wrote {args.out}"
        if len(spec.objects) < len(objects)
        else f"{args.mode} scene of {len(spec.objects)} objects (seed {args.seed}) built in {dt:.2f} s; wrote {args.out}"
    )
    for i, o in enumerate(spec.objects):
        print(f"  {i}: {o.urdf} at {', '.join(f'{v:.3f}' for v in o.pose[:3])}")
    if args.png:
        from ..viz import plot_depth_images

        png = args.out.rsplit(".", 1)[0] + ".png"
        plot_depth_images(scene_camera.acquire_scene(spec), png)
        print(f"wrote {png}")
    return 0


COMMANDS = ("scene",)


def add_parsers(sub) -> None:
    s = sub.add_parser("scene", help="build a scene of several objects on the table (pile or packed) in Bullet")
    s.add_argument("--objects", type=int_in(1, 100), required=True, help="how many objects to draw")
    s.add_argument("--mode", choices=["pile", "packed"], required=True, help="dropped in a pile, or placed upright")
    s.add_argument("--seed", type=seed, default=0, help="seed of the draw and the placement")
    s.add_argument(
        "--object-list", type=input_path, help="object list (one URDF a line; default: data/objects/test60.txt)"
    )
    s.add_argument("--out", type=output_file, required=True, help="output scene file (.json)")
    s.add_argument("--png", action="store_true", help="also draw the scene as the default camera sees it (.png)")
    s.set_defaults(func=cmd_scene)
