"""Experiment folders whose attempts.csv lost a column or a value: `graspmix_cli report` and build_report name the
file and the column (corpus_json.py holds the edits that give a column a wrong value)."""

from __future__ import annotations

from cases import COLUMNS, api, attempts_csv, cli, run_folder
from graspmix.experiment.log import EMPTY_IF_SYNTHESIS_FAILED, RECORDED_COLUMNS

# A row of a failed synthesis, as experiment/attempt.py writes it.
FAILED_SYNTHESIS = {
    **dict.fromkeys(EMPTY_IF_SYNTHESIS_FAILED, ""),
    "success": 0,
    "reason": "synthesis failed",
    "grasp": "",
    "error": "segment_scene: no object",
}


def _without_column(column: str) -> str:
    """attempts.csv with `column` taken out of the header and of every row."""
    lines = attempts_csv().splitlines()
    i = lines[0].split(",").index(column)
    return "\n".join(",".join(c for j, c in enumerate(line.split(",")) if j != i) for line in lines) + "\n"


def _emptied(column: str, row: int = 3) -> str:
    def edit(i, r):
        if i == row:
            r[column] = ""

    return attempts_csv(edit)


def report_cases():
    cases = [
        cli(
            f"json/csv/empty-{column}",
            "report",
            "{tmp}/run",
            files=run_folder(csv=_emptied(column)),
            names=("attempts.csv", "row 4", column),
        )
        for column in RECORDED_COLUMNS
    ]
    cases += [
        cli(
            f"json/csv/no-column-{column}",
            "report",
            "{tmp}/run",
            files=run_folder(csv=_without_column(column)),
            names=("attempts.csv", column),
        )
        for column in ("t_execution", "t_acquisition", "success", "object", "log_likelihood")
    ]
    cases.append(
        api(
            "api/report/empty-t_execution",
            "from graspmix.experiment.report import build_report\nbuild_report('run')",
            files=run_folder(csv=_emptied("t_execution")),
            names=("attempts.csv", "t_execution"),
        )
    )

    def failed(i, r):
        if i == 2:
            r.update(FAILED_SYNTHESIS)

    cases.append(
        cli(
            "json/csv/ok-a-failed-synthesis",
            "report",
            "{tmp}/run",
            files=run_folder(csv=attempts_csv(failed)),
            expect="ok",
            timeout=120,
        )
    )
    return cases


assert set(RECORDED_COLUMNS) < set(COLUMNS)
CASES = report_cases()
