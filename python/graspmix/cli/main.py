"""graspmix_cli: the command line over the graspmix library.

Every subcommand turns a bad input into one line on stderr and exit status 2.
"""
from __future__ import annotations

import argparse
import sys

from ..io import package_version
from . import core_commands, experiment_commands, grasp_commands, sim_commands
from .common import CliError


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="graspmix_cli", description=__doc__.splitlines()[0])
    p.add_argument("--version", action="version", version=f"graspmix {package_version()}")
    sub = p.add_subparsers(dest="command", required=True)
    for commands in (core_commands, grasp_commands, sim_commands, experiment_commands):
        commands.add_parsers(sub)
    return p


def main(argv: list[str] | None = None) -> int:
    args = build_parser().parse_args(argv)
    args.argv = list(sys.argv[1:] if argv is None else argv)
    try:
        return args.func(args)
    except BrokenPipeError:  # the reader went away (e.g. `| head`): nothing more to say
        sys.stderr.close()
        return 0
    except (CliError, ValueError) as e:
        message = " ".join(str(e).split())  # one line, whatever the exception's text
        print(f"graspmix_cli {args.command}: error: {message}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print(f"\ngraspmix_cli {args.command}: stopped; finished attempts are kept, the same command resumes",
              file=sys.stderr)
        return 130
