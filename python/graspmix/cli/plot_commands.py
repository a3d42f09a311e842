"""graspmix_cli plot: a grasps.json drawn as a picture (--png) and/or an interactive 3D page (--html)."""

from __future__ import annotations

import argparse

from ..model import GraspSet
from .common import CliError, html_file, input_path, int_in, picture_file


def cmd_plot(args: argparse.Namespace) -> int:
    if not args.png and not args.html:
        raise CliError("give --png and/or --html: where to draw the grasps")
    grasps = GraspSet.load(args.grasps)
    top = min(args.top, len(grasps))
    options = {"cloud": args.cloud, "top": top}
    drawn = f"the best {top} of {len(grasps)} grasps"
    if args.png:
        grasps.plot(args.png, **options)
        print(f"wrote {args.png} ({drawn})")
    if args.html:
        grasps.plot(args.html, **options)
        print(f"wrote {args.html} ({drawn}; self-contained: opens in a browser without a network)")
    return 0


COMMANDS = ("plot",)


def add_parsers(sub) -> None:
    s = sub.add_parser("plot", help="draw a grasps file: the cloud, the table and the best grasps' hands")
    s.add_argument("--grasps", type=input_path, required=True, help="grasps file (.json, graspmix.grasps/1)")
    s.add_argument(
        "--cloud",
        type=input_path,
        help="the cloud to draw (.pcd, .ply, .npy); default: the file's cloud or depth image, if it exists",
    )
    s.add_argument("--top", type=int_in(1), default=3, help="how many of the best grasps to draw (3)")
    s.add_argument("--png", type=picture_file, help="write a picture (.png, .pdf, .svg): two views")
    s.add_argument("--html", type=html_file, help="write an interactive 3D view (.html, plotly, self-contained)")
    s.set_defaults(func=cmd_plot)
