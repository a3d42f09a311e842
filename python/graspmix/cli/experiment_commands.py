"""experiment, report, benchmark: the paper's experiment and its runtime figure."""

from __future__ import annotations

import argparse
import dataclasses
import shlex
from pathlib import Path

from ..io import SUMMARY_FORMAT, read_document, read_objects_file, test_objects
from ..model.settings import METHODS
from .common import CliError, float_in, input_path, int_in, output_folder, seed, split_list
from .synthesis_flags import add_synthesis_arguments, synthesis_options


def _protocol(args):
    from ..experiment import CONDITIONS, Protocol

    conditions = split_list(args.conditions, "--conditions", list(CONDITIONS)) if args.conditions else None
    methods = split_list(args.methods, "--methods", list(METHODS)) if args.methods else None
    objects = read_objects_file(args.objects) if args.objects else None
    if args.jobs < 1:
        raise CliError(f"--jobs must be at least 1, got {args.jobs}")
    protocol = Protocol.preset(
        args.preset,
        objects=objects,
        trials=args.trials,
        conditions=conditions,
        methods=methods,
        seed=args.seed,
        closing=args.closing,
        models=_models(args.model or [], methods),
        pixel_noise_std=args.pixel_noise,
        depth_noise_std=args.depth_noise,
        views=args.views,
        cloud=args.cloud,
    )
    # replace() validates the protocol again with its synthesis options.
    return dataclasses.replace(protocol, synthesis=synthesis_options(args, protocol.synthesis))


def _models(paths: list, methods) -> dict | None:
    """--model files (repeatable, one per method) as method -> absolute path."""
    from ..model import GraspModel

    models = {}
    for path in paths:
        method = GraspModel.load(path).method
        if method in models:
            raise CliError(f"--model: two {method} models given ({models[method]} and {path})")
        if methods is not None and method not in methods:
            raise CliError(f"--model {path} is a {method} model, not one of --methods {','.join(methods)}")
        models[method] = str(Path(path).resolve())
    return models or None


def run_options(args: argparse.Namespace) -> dict:
    """The keyword arguments of a run (the experiment's or the clutter protocol's) from the shared options
    --jobs, --executor, --ray-address, --quiet, and the command line to record."""
    command = "graspmix_cli " + " ".join(shlex.quote(a) for a in (args.argv or []))
    return {
        "jobs": args.jobs,
        "executor": args.executor,
        "progress": not args.quiet,
        "ray_address": args.ray_address,
        "command": command,
    }


def cmd_experiment(args: argparse.Namespace) -> int:
    from ..experiment import CSV_NAME, run

    protocol = _protocol(args)
    n = len(protocol.all_attempts())
    print(
        f"experiment: {len(protocol.objects)} objects x {protocol.trials} trials x conditions "
        f"{','.join(protocol.conditions)} x methods {','.join(protocol.methods)} = {n} attempts; "
        f"{args.jobs} job(s), executor {args.executor}; into {args.out}",
        flush=True,
    )
    res = run(protocol, args.out, **run_options(args))
    print(
        f"ran {res['ran']} attempts in {res['seconds']:.1f} s ({res['skipped']} already done); "
        f"{res['rows']}/{res['total']} in {Path(args.out) / CSV_NAME}"
    )
    if res["rows"] > 0:
        print_findings(Path(args.out))
    return 0


def print_findings(run_dir: Path) -> None:
    from ..experiment.report import findings_table

    summary = read_document(run_dir / "summary.json", SUMMARY_FORMAT)
    for row in findings_table(summary):
        print("  " + " | ".join(row))
    print(f"wrote {run_dir / 'summary.json'}, {run_dir / 'report.md'}, {run_dir / 'report.html'}")


def cmd_report(args: argparse.Namespace) -> int:
    from ..experiment.report import build_report

    build_report(args.run)
    print_findings(Path(args.run))
    return 0


def cmd_benchmark(args: argparse.Namespace) -> int:
    from ..experiment import benchmark, format_benchmark

    objects = read_objects_file(args.objects) if args.objects else test_objects()
    if args.limit is not None:
        if args.limit < 1:
            raise CliError(f"--limit must be at least 1, got {args.limit}")
        objects = objects[: args.limit]
    from ..experiment import Protocol

    res = benchmark(
        objects,
        args.out,
        synthesis=synthesis_options(args, Protocol.preset(args.preset).synthesis),
        seed=args.seed,
        progress=not args.quiet,
        preset=args.preset,
    )
    print(format_benchmark(res))
    print(f"GMM is {res['ratio_kde_over_gmm']['total']:.2f}x faster than KDE in total (median over objects)")
    print(f"wrote {Path(args.out) / 'benchmark.json'} and {Path(args.out) / 'benchmark.png'}")
    return 0


def _vary(text: str) -> tuple:
    """--vary NAME=V1,V2,...: a sweep parameter and its values (ints for counts, else floats)."""
    from ..experiment.sweep import PARAMETERS, parameter_type

    name, sep, values = text.partition("=")
    if not sep or name not in PARAMETERS:
        raise argparse.ArgumentTypeError(
            f"expected NAME=V1,V2,... with NAME one of {', '.join(PARAMETERS)}, got {text!r}"
        )
    cast = parameter_type(name)
    try:
        return name, [cast(v) for v in values.split(",") if v.strip()]
    except ValueError:
        raise argparse.ArgumentTypeError(f"--vary {name}: expected {cast.__name__} values, got {values!r}") from None


def cmd_sweep(args: argparse.Namespace) -> int:
    from ..experiment.sweep import SWEEP_NAME, Sweep, run_sweep

    if not args.vary:
        raise CliError("give at least one --vary NAME=V1,V2,...")
    params = dict(args.vary)
    if len(params) != len(args.vary):
        raise CliError("--vary: a parameter is given twice")
    sweep = Sweep(_protocol(args), params)
    result = run_sweep(sweep, args.out, **run_options(args))
    for name, entry in result["parameters"].items():
        for m, me in entry["methods"].items():
            cells = ", ".join(f"{p['value']:g}: {100 * p['mean']:.1f}%" for p in me["points"])
            print(f"{name} ({m}, default {entry['default']:g}): {cells}; best {me['best']:g}")
    print(f"wrote {Path(args.out) / SWEEP_NAME} and {Path(args.out) / 'sweep.png'}")
    return 0


def _add_view_options(s) -> None:
    """The protocol's cameras and what an acquisition keeps (default: the preset's)."""
    s.add_argument(
        "--views", type=int_in(1, 64), help="cameras: a ring of n (the paper's 4), or 1 above the table (default 4)"
    )
    s.add_argument(
        "--cloud",
        choices=["object", "scene", "image"],
        help="what an acquisition keeps: the object's pixels, table cropped (the paper's); every pixel as points; "
        "or the depth image with its intrinsics and pose, one camera (default: the preset's; defaults with "
        "--views 1: image)",
    )


def _add_run_options(s) -> None:
    """The options the experiment and the sweep share: the protocol's and how to run it."""
    s.add_argument(
        "--preset",
        choices=["smoke", "paper", "defaults"],
        default="paper",
        help="paper: the 60 test objects, 10 trials, the paper's synthesis (default); smoke: 3 objects, 2 trials; "
        "defaults: as paper with the library's synthesis defaults (collision model, clear approach)",
    )
    s.add_argument(
        "--objects",
        type=input_path,
        help="objects file, one URDF a line (a path, or relative to pybullet_data); default: the preset's",
    )
    s.add_argument("--trials", type=int_in(1, 100_000), help="trials (default: the preset's)")
    s.add_argument("--conditions", help="comma-separated subset of A,B,C,D (default: all)")
    s.add_argument("--methods", help="comma-separated subset of gmm,kde (default: both)")
    s.add_argument(
        "--model",
        type=input_path,
        action="append",
        help="a learnt model file (graspmix_cli learn): it replaces the bundled model of its method (gmm or kde); "
        "give it twice for both methods",
    )
    s.add_argument(
        "--pixel-noise",
        type=float_in(0.0),
        help="sigma_p of the noise model, pixels (default: the paper's; 0: depth noise only)",
    )
    s.add_argument(
        "--depth-noise",
        type=float_in(0.0),
        help="sigma_d of the noise model, m (default: the paper's; 0: lateral shift only)",
    )
    _add_view_options(s)
    add_synthesis_arguments(s, base="the preset's", seed=False)
    s.add_argument("--seed", type=seed, default=None, help="base of every derived seed (default 0)")
    s.add_argument(
        "--closing",
        choices=["full", "learnt"],
        default=None,
        help="full (default): the fingers close until they stop on the object, force-limited; learnt: "
        "the simulation's default target just past the synthesised grasp joints",
    )
    s.add_argument("--jobs", type=int_in(1, 1024), default=1, help="parallel worker processes (or Ray tasks)")
    s.add_argument(
        "--executor",
        choices=["local", "ray"],
        default="local",
        help="local processes, or a Ray cluster (a local Ray instance unless --ray-address)",
    )
    s.add_argument("--ray-address", help="address of a running Ray cluster (default: start a local one)")
    s.add_argument("--quiet", action="store_true", help="no progress bar")


COMMANDS = ("experiment", "sweep", "report", "benchmark")


def add_parsers(sub) -> None:
    from ..experiment.sweep import PARAMETERS

    s = sub.add_parser(
        "experiment", help="the paper's experiment: conditions A-D, GMM vs KDE, success rates, t-tests, runtimes"
    )
    s.add_argument(
        "--out",
        type=output_folder,
        required=True,
        help="run folder (e.g. runs/NAME): attempts.csv, protocol.json, summary.json, "
        "report.md/html; running again into it resumes",
    )
    _add_run_options(s)
    s.set_defaults(func=cmd_experiment)

    s = sub.add_parser(
        "sweep",
        help="success against each method's own settings, varied one at a time on a development list of objects",
    )
    s.add_argument(
        "--out", type=output_folder, required=True, help="sweep folder: one experiment folder a value, sweep.json/png"
    )
    s.add_argument(
        "--vary",
        type=_vary,
        action="append",
        help="NAME=V1,V2,...: a setting and its values (repeat for more settings); names: " + ", ".join(PARAMETERS),
    )
    _add_run_options(s)
    s.set_defaults(func=cmd_sweep)

    s = sub.add_parser("report", help="rebuild summary.json and report.md/html of an experiment folder from its CSV")
    s.add_argument("run", type=input_path, help="the experiment folder")
    s.set_defaults(func=cmd_report)

    s = sub.add_parser("benchmark", help="the paper's runtime comparison: medians over objects per stage, GMM vs KDE")
    s.add_argument("--objects", type=input_path, help="objects file (default: the 60 test objects)")
    s.add_argument("--limit", type=int_in(1), help="only the first N objects")
    s.add_argument("--seed", type=seed, default=0)
    s.add_argument(
        "--preset",
        choices=["defaults", "paper"],
        default="defaults",
        help="whose synthesis and clouds: the library's defaults on whole depth images (default), or the paper's",
    )
    s.add_argument(
        "--out",
        type=output_folder,
        default="benchmark",
        help="folder for benchmark.json and benchmark.png (default ./benchmark)",
    )
    s.add_argument("--quiet", action="store_true", help="no progress bar")
    add_synthesis_arguments(s, base="the preset's", seed=False)
    s.set_defaults(func=cmd_benchmark)
