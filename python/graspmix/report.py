"""Deprecated module path, kept for one release: the experiment's report is
``graspmix.experiment.report`` (its figures ``graspmix.viz``). Every name of the old module is here."""

from .experiment.log import CSV_NAME, read_rows
from .experiment.protocol import CONDITIONS, load_protocol
from .experiment.report import (
    REASONS,
    build_report,
    findings_table,
    md_table,
    outcomes_table,
    runtime_table,
    summarize,
)
from .experiment.stats import mean_ci, paired_ttest
from .io import SUMMARY_FORMAT
from .model.grasps import STAGE_LABELS, STAGES
from .model.settings import METHOD_LABELS, METHODS
from .viz.experiment import COLOURS, STAGE_COLOURS, plot_runtime, plot_success

_md_table = md_table  # the old private name, which scripts used

__all__ = [
    "COLOURS",
    "CONDITIONS",
    "CSV_NAME",
    "METHOD_LABELS",
    "METHODS",
    "REASONS",
    "STAGES",
    "STAGE_COLOURS",
    "STAGE_LABELS",
    "SUMMARY_FORMAT",
    "build_report",
    "findings_table",
    "load_protocol",
    "md_table",
    "mean_ci",
    "outcomes_table",
    "paired_ttest",
    "plot_runtime",
    "plot_success",
    "read_rows",
    "runtime_table",
    "summarize",
]
