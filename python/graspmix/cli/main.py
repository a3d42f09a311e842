"""graspmix_cli: the command line over the graspmix library.

Every subcommand turns a bad input into one line on stderr and exit status 2.
"""

from __future__ import annotations

import argparse
import sys

from ..io import package_version
from . import (
    clutter_commands,
    core_commands,
    experiment_commands,
    grasp_commands,
    hand_commands,
    plot_commands,
    scene_commands,
    segment_commands,
    sim_commands,
)
from .common import CliError, OneLineParser, report_error


def build_parser() -> argparse.ArgumentParser:
    p = OneLineParser(prog="graspmix_cli", description=__doc__.splitlines()[0])
    p.add_argument("--version", action="version", version=f"graspmix {package_version()}")
    sub = p.add_subparsers(dest="command", required=True, parser_class=OneLineParser)
    for commands in (
        core_commands,
        segment_commands,
        grasp_commands,
        plot_commands,
        hand_commands,
        sim_commands,
        scene_commands,
        experiment_commands,
        clutter_commands,
    ):
        commands.add_parsers(sub)
    return p


def main(argv: list[str] | None = None) -> int:
    try:
        args = build_parser().parse_args(argv)
    except SystemExit as e:  # a bad option (one line already printed, status 2), or --help / --version
        return e.code if isinstance(e.code, int) else 2
    args.argv = list(sys.argv[1:] if argv is None else argv)
    try:
        return args.func(args)
    except BrokenPipeError:  # the reader went away (e.g. `| head`): nothing more to say
        sys.stderr.close()
        return 0
    except (CliError, ValueError) as e:
        return report_error(args.command, str(e))
    except OSError as e:  # a file the checks could not foresee (a disk that filled up, a file that vanished)
        where = f"{e.filename}: " if e.filename else ""
        return report_error(args.command, f"{where}{e.strerror or e}")
    except RecursionError:
        return report_error(args.command, "an input is nested too deeply")
    except KeyboardInterrupt:
        print(
            f"\ngraspmix_cli {args.command}: stopped; finished attempts are kept, the same command resumes",
            file=sys.stderr,
        )
        return 130
