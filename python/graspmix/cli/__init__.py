"""graspmix_cli: the command line over the graspmix library (entry point ``graspmix.cli:main``).

One module per group of subcommands, each a thin layer of argument parsing over library calls:
core_commands (info, fit-gmm, features), grasp_commands (demo, learn, synthesize), sim_commands
(acquire, execute), experiment_commands (experiment, report, benchmark).
"""

from .common import CliError
from .main import build_parser, main

__all__ = ["CliError", "build_parser", "main"]
