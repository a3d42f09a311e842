"""graspmix_cli: the command line over the graspmix library (entry point ``graspmix.cli:main``).

One module per group of subcommands, each a thin layer of argument parsing over library calls:
core_commands (info, fit-gmm, features), grasp_commands (demo, learn, synthesize), sim_commands
(acquire, execute), experiment_commands (experiment, report, benchmark).
"""

from ..io import data_path
from .common import CliError
from .main import build_parser, main

DATA = data_path()  # deprecated: use graspmix.io.data_path()

__all__ = ["DATA", "CliError", "build_parser", "main"]
