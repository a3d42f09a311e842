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
from .common import CliError, OneLineParser, check_distinct_files, report_error


class _VersionAction(argparse.Action):
    """argparse's "version" action with the version looked up when asked (importlib.metadata costs an import
    that every other command would pay)."""

    def __init__(self, option_strings, dest=argparse.SUPPRESS, default=argparse.SUPPRESS, help=None):
        super().__init__(option_strings=option_strings, dest=dest, default=default, nargs=0, help=help)

    def __call__(self, parser, namespace, values, option_string=None):
        parser.exit(message=f"graspmix {package_version()}\n")


# The command modules; each lists in COMMANDS the subcommands its add_parsers adds (tests/python/package/
# test_imports.py holds them to it), so that build_parser can build one group's alone.
GROUPS = (
    core_commands,
    segment_commands,
    grasp_commands,
    plot_commands,
    hand_commands,
    sim_commands,
    scene_commands,
    experiment_commands,
    clutter_commands,
)


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The command line's parser: every subcommand's, or with `command` (a subcommand's name) only that of
    its group, so that a command does not import what the other commands' options need (their defaults
    come from the layers above the model: the simulator, the experiment)."""
    p = OneLineParser(prog="graspmix_cli", description=__doc__.splitlines()[0])
    p.add_argument("--version", action=_VersionAction, help="print graspmix's version and exit")
    sub = p.add_subparsers(dest="command", required=True, parser_class=OneLineParser)
    for commands in [g for g in GROUPS if command in g.COMMANDS] or GROUPS:
        commands.add_parsers(sub)
    return p


def _subparser(parser: argparse.ArgumentParser, command: str) -> argparse.ArgumentParser:
    """The parser of one subcommand."""
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return sub.choices[command]


def main(argv: list[str] | None = None) -> int:
    words = list(sys.argv[1:] if argv is None else argv)
    parser = build_parser(next((w for w in words if not w.startswith("-")), None))
    try:
        args = parser.parse_args(argv)
    except SystemExit as e:  # a bad option (one line already printed, status 2), or --help / --version
        return e.code if isinstance(e.code, int) else 2
    args.argv = words
    try:
        check_distinct_files(_subparser(parser, args.command), args)
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
