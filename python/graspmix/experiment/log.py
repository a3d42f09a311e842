"""attempts.csv: one row per executed grasp, appended as work units finish. The log is generic over its
columns (a CsvSchema): the paper's experiment uses EXPERIMENT_CSV, the clutter protocol its own."""

from __future__ import annotations

import csv
import gzip
import io
import os
from dataclasses import dataclass
from pathlib import Path

from ..io.checks import check_input_file, quote

CSV_NAME = "attempts.csv"

# Columns of attempts.csv. Times are in seconds.
KEY_COLUMNS = ["object", "trial", "condition", "method"]
RESULT_COLUMNS = [
    "noise",
    "optimise",
    "acquisition_seed",
    "synthesis_seed",
    "n_points",
    "success",
    "reason",
    "lift_height",
    "contact_count",
    "log_likelihood",
    "grasp",
    "evaluations",
    "rejected",
    "error",
]
TIME_COLUMNS = ["t_acquisition", "t_features", "t_query", "t_sampling", "t_optimisation", "t_synthesis", "t_execution"]
COLUMNS = KEY_COLUMNS + RESULT_COLUMNS + TIME_COLUMNS
INT_COLUMNS = {
    "trial",
    "noise",
    "optimise",
    "acquisition_seed",
    "synthesis_seed",
    "n_points",
    "success",
    "contact_count",
    "evaluations",
    "rejected",
}
FLOAT_COLUMNS = {"lift_height", "log_likelihood", *TIME_COLUMNS}
# The numbers a failed synthesis leaves empty (experiment/attempt.py); every attempt records the others.
EMPTY_IF_SYNTHESIS_FAILED = {"log_likelihood", "t_features", "t_query", "t_sampling", "t_optimisation"}
RECORDED_COLUMNS = tuple(
    c for c in COLUMNS if (c in INT_COLUMNS or c in FLOAT_COLUMNS) and c not in EMPTY_IF_SYNTHESIS_FAILED
)


@dataclass(frozen=True)
class CsvSchema:
    """The columns of an append-only attempts log: all of them in order, those that identify a row (its
    key), and those read back as integers or floats (empty: None); the others are text."""

    columns: tuple
    key: tuple
    ints: frozenset
    floats: frozenset
    what: str = "attempts"

    def key_of(self, row: dict) -> tuple:
        return tuple(int(row[k]) if k in self.ints else row[k] for k in self.key)


EXPERIMENT_CSV = CsvSchema(tuple(COLUMNS), tuple(KEY_COLUMNS), frozenset(INT_COLUMNS), frozenset(FLOAT_COLUMNS))


def _format(v) -> str:
    if isinstance(v, float):
        return repr(v)
    return str(v)


class AttemptLog:
    """attempts.csv: append-only, one row per attempt, flushed and synced after every unit."""

    def __init__(self, path: Path, schema: CsvSchema = EXPERIMENT_CSV):
        self.path = Path(path)
        self.schema = schema
        self._repair()
        if not self.path.exists() or self.path.stat().st_size == 0:
            with open(self.path, "w", newline="") as f:
                csv.writer(f).writerow(schema.columns)

    def _repair(self) -> None:
        """A run killed while writing can leave a partial last line: cut it (its unit is run again)."""
        if not self.path.exists():
            return
        data = check_input_file(self.path, self.schema.what).read_bytes()
        if data and not data.endswith(b"\n"):
            cut = data.rfind(b"\n") + 1
            with open(self.path, "r+b") as f:
                f.truncate(cut)
        if self.path.stat().st_size > 0:
            with open(self.path, newline="", encoding="utf-8", errors="replace") as f:
                try:
                    header = next(csv.reader(f), None)
                except csv.Error:
                    header = None
            if header != list(self.schema.columns):
                raise ValueError(
                    f"{self.path}: its columns are not those of this graspmix version's {self.schema.what} log"
                )

    def done(self) -> set[tuple]:
        return {self.schema.key_of(r) for r in read_rows(self.path, self.schema)}

    def append(self, rows: list[dict]) -> None:
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        for r in rows:
            w.writerow([_format(r.get(c, "")) for c in self.schema.columns])
        with open(self.path, "a", newline="") as f:
            f.write(buf.getvalue())
            f.flush()
            os.fsync(f.fileno())


def read_rows(path: str | Path, schema: CsvSchema = EXPERIMENT_CSV) -> list[dict]:
    """The rows of an attempts.csv (of the given schema), typed (ints, floats, None for empty numbers), in
    file order; a trailing partial line (a killed run) is ignored. A path ending in .gz is read gzip-compressed
    (the results kept in the repository)."""
    path = check_input_file(path, schema.what)
    try:
        raw = path.read_bytes()
        if path.suffix == ".gz":
            raw = gzip.decompress(raw)
        text = raw.decode("utf-8")
    except (gzip.BadGzipFile, EOFError) as e:
        raise ValueError(f"{path}: not a gzip file ({e})") from None
    except UnicodeDecodeError as e:
        raise ValueError(f"{path}: not UTF-8 text (byte {e.start})") from None
    if text and not text.endswith("\n"):
        text = text[: text.rfind("\n") + 1]
    try:
        reader = csv.DictReader(io.StringIO(text))
        if reader.fieldnames is None:
            return []
        missing = [c for c in schema.columns if c not in reader.fieldnames]
        if missing:
            raise ValueError(f"{path}: not an {schema.what} log (missing columns {', '.join(missing)})")
        return [_typed(r, path, reader.line_num, schema) for r in reader]
    except csv.Error as e:
        raise ValueError(f"{path}: not a CSV file ({e})") from None


def _typed(r: dict, path: Path, line: int, schema: CsvSchema) -> dict:
    out = {}
    for k in schema.columns:
        v = r[k]
        if v is None:
            raise ValueError(f"{path}: line {line} has fewer columns than the header")
        try:
            if k in schema.ints:
                out[k] = int(v) if v != "" else None
            elif k in schema.floats:
                out[k] = float(v) if v != "" else None
            else:
                out[k] = v
        except ValueError:
            kind = "an integer" if k in schema.ints else "a number"
            raise ValueError(f"{path}: line {line}, column {k!r}: expected {kind}, got {quote(v)}") from None
    return out
