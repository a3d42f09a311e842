"""clutter: the clutter-removal protocol (VGN, GIGA) in the simulation, GSR and DR with 95% intervals; or,
with --task named, one object per scene named by a point on it and lifted (or not)."""

from __future__ import annotations

import argparse
from pathlib import Path

from .common import input_path, int_in, output_folder, seed, split_list
from .experiment_commands import run_options
from .synthesis_flags import add_synthesis_arguments, synthesis_options


def _protocol(args):
    from ..clutter import MODES, PLANNERS
    from ..clutter.protocol import ClutterProtocol

    return ClutterProtocol(
        object_list=args.object_list or "",
        objects=args.objects,
        scenes=args.scenes,
        modes=split_list(args.mode, "--mode", MODES),
        methods=split_list(args.method, "--method", PLANNERS),
        views=args.views,
        noise=args.noise,
        closing=args.closing,
        max_attempts=ClutterProtocol.max_attempts if args.max_attempts is None else args.max_attempts,
        seed=args.seed,
        synthesis=synthesis_options(args),
        task=args.task,
        targets=1 if args.targets is None else args.targets,
        cloud=args.cloud or "",
    )


def _print_results(res: dict, out: Path) -> None:
    from ..clutter import CLUTTER_CSV_NAME, results_table
    from ..clutter.named import NAMED_CSV_NAME
    from ..io import CLUTTER_SUMMARY_FORMAT, read_document

    units, csv = ("attempts", NAMED_CSV_NAME) if res.get("task") == "named" else ("rounds", CLUTTER_CSV_NAME)
    done = f"{res['rounds']}/{res['total']} {units} in {out / csv}"
    print(f"ran {res['ran']} attempts in {res['seconds']:.1f} s ({res['skipped']} {units} already done); {done}")
    if res["rounds"] == 0:
        return
    for row in results_table(read_document(out / "summary.json", CLUTTER_SUMMARY_FORMAT)):
        print("  " + " | ".join(row))
    plot = "" if res.get("task") == "named" else f", {out / 'clutter.png'}"
    print(f"wrote {out / 'summary.json'}, {out / 'report.md'}{plot}")


def cmd_clutter(args: argparse.Namespace) -> int:
    from ..clutter import run_clutter

    p = _protocol(args)
    what = f"{p.scenes} scenes x modes {','.join(p.modes)} x methods {','.join(p.methods)}, {p.objects} objects each"
    seen = f"{p.views} view(s){' as a depth image' if p.cloud == 'image' else ''}, {'noise' if p.noise else 'no noise'}"
    task = f"; {p.targets} named object(s) per scene" if p.task == "named" else ""
    print(f"clutter: {what} from {p.object_list}; {seen}{task}; {args.jobs} job(s); into {args.out}", flush=True)
    res = run_clutter(p, args.out, **run_options(args))
    _print_results({**res, "task": p.task}, Path(args.out))
    return 0


COMMANDS = ("clutter",)


def add_parsers(sub) -> None:
    from ..clutter.protocol import CLOUDS, ROUNDS

    s = sub.add_parser(
        "clutter",
        help="clutter removal (VGN/GIGA protocol): scenes of N objects, grasp until clear; GSR and DR with 95%% CIs",
    )
    s.add_argument("--out", type=output_folder, required=True, help="run folder; running again into it resumes")
    s.add_argument("--mode", default="pile", help="pile, packed, or both comma-separated (default pile)")
    s.add_argument("--method", default="gmm", help="gmm, kde, topdown, or several comma-separated (default gmm)")
    s.add_argument("--objects", type=int_in(1, 50), default=5, help="objects per scene (default 5)")
    s.add_argument("--scenes", type=int_in(1, 1_000_000), default=ROUNDS, help=f"scenes per mode (default {ROUNDS})")
    s.add_argument("--views", type=int_in(1, 64), default=1, help="cameras per observation (default 1)")
    s.add_argument("--noise", action="store_true", help="the depth noise model")
    s.add_argument(
        "--cloud",
        choices=CLOUDS,
        help="what the planners get of the camera: its depth image with intrinsics and pose, as a robot's camera "
        "gives it (image; the default with one camera), or every pixel as points with its position (scene; "
        "the default with several, and every run before this option existed)",
    )
    s.add_argument(
        "--object-list",
        type=input_path,
        help="objects to draw scenes from, one URDF a line (default: data/objects/clutter_test.txt)",
    )
    s.add_argument(
        "--task",
        choices=["clear", "named"],
        default="clear",
        help="clear the scenes (default), or lift one object per scene named by a point on it (point:x,y,z)",
    )
    s.add_argument(
        "--targets",
        type=int_in(1, 50),
        help="--task named: objects named per scene, each on the untouched scene (default 1)",
    )
    s.add_argument("--closing", choices=["full", "learnt"], default="full", help="how grasps close (default full)")
    s.add_argument(
        "--max-attempts",
        type=int_in(-1, 10_000),
        help="attempts per scene at most (default: the protocol's, -1: objects + 2; 0: no cap, VGN's rules alone)",
    )
    s.add_argument("--seed", type=seed, default=0, help="base of every derived seed (default 0)")
    add_synthesis_arguments(s, seed=False)
    s.add_argument("--jobs", type=int_in(1, 1024), default=1, help="parallel worker processes (or Ray tasks)")
    s.add_argument("--executor", choices=["local", "ray"], default="local", help="local processes or Ray")
    s.add_argument("--ray-address", help="address of a running Ray cluster (default: start a local one)")
    s.add_argument("--quiet", action="store_true", help="no progress bar")
    s.set_defaults(func=cmd_clutter)
