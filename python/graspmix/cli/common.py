"""What every subcommand shares: the user-error type, the argument parser that reports in one line, and
the parsers of option values. Every number is checked (finite, in its range) and every path (UTF-8,
names <= 255 bytes; outputs writable) while the command line is parsed, so a bad value is reported
before any work starts, by the helpers of graspmix.io.checks."""

from __future__ import annotations

import argparse
import os
import re
import sys
from pathlib import Path

import numpy as np

from ..io.checks import (
    INT_MAX,
    SEED_MAX,
    check_float,
    check_int,
    check_output_folder,
    check_output_path,
    check_path_text,
    quote,
)
from ..io.paths import PACKAGE_PREFIX, PYBULLET_DATA_PREFIX, resolve_path


class CliError(Exception):
    """A user error: printed as one line, exit status 2."""


# What argparse takes for a negative number (its own rule, ^-\d+$|^-\d*\.\d+$), widened to a comma-separated list
# of numbers whose first is negative, as poses and points are given.
_NUMBER = r"\d*\.?\d+(?:[eE][-+]?\d+)?"
NEGATIVE_NUMBERS = re.compile(rf"^-{_NUMBER}(?:,[-+]?{_NUMBER})*$")


class OneLineParser(argparse.ArgumentParser):
    """argparse's parser, but an error is one line on stderr ("graspmix_cli sub: error: ...") and exit
    status 2, like every other error of the command line (argparse prints the usage first). A value that
    starts with a minus sign and is a comma-separated list of numbers (`--wrist -0.004,0,0.258,1,0,0,0`) is
    a value, as a single negative number is to argparse, not an unknown option."""

    def __init__(self, *args, **kwargs):
        super().__init__(*args, **kwargs)
        self._negative_number_matcher = NEGATIVE_NUMBERS

    def error(self, message: str):
        text = " ".join(message.split())
        self.exit(2, f"{self.prog}: error: {text} (see {self.prog} --help)\n")


def _typed(check, what: str):
    """An argparse type: parses the text with check(text, name); a ValueError becomes argparse's error."""

    def parse(text: str):
        try:
            return check(text)
        except ValueError as e:
            raise argparse.ArgumentTypeError(str(e)) from None

    parse.__name__ = what  # argparse names the type in "invalid <name> value"
    return parse


def int_in(lo: int | None = None, hi: int | None = INT_MAX):
    """An integer option within [lo, hi] (hi defaults to C++'s int)."""

    def check(text):
        try:
            v = int(text, 10)
        except ValueError:
            raise ValueError(f"expected an integer{_range_text(lo, hi)}, got {quote(text)}") from None
        return check_int(v, "", lo, hi)

    return _typed(check, "integer")


def _range_text(lo, hi) -> str:
    if lo is not None and hi is not None:
        return f" in [{lo}, {hi}]"
    return f" >= {lo}" if lo is not None else ""


seed = int_in(0, SEED_MAX)


def float_in(lo: float | None = None, hi: float | None = None, *, gt: float | None = None):
    """A finite number option, >= lo, > gt, <= hi."""

    def check(text):
        try:
            v = float(text)
        except ValueError:
            raise ValueError(f"expected a number, got {quote(text)}") from None
        return check_float(v, "", lo, hi, gt=gt)

    return _typed(check, "number")


def _box(text: str) -> list:
    v = [float(x) for x in text.split(",")] if text.count(",") == 5 else []
    if len(v) != 6 or not all(np.isfinite(v)) or not all(v[k] < v[k + 3] for k in range(3)):
        raise ValueError(
            f"expected x_min,y_min,z_min,x_max,y_max,z_max (m, each minimum below its maximum), got {text!r}"
        )
    return v


box = _typed(_box, "box")  # a box in the world frame: six numbers, minima then maxima


def _path(text: str) -> str:
    check_path_text(text)
    return text


def _output_file(text: str) -> str:
    check_output_path(text, "")
    return text


def _output_folder(text: str) -> str:
    check_output_folder(text, "")
    return text


# What matplotlib writes a picture as, by the file's suffix (a name without one would be written as NAME.png).
PICTURE_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg", ".webp", ".tif", ".tiff", ".eps", ".ps", ".svgz")


def _suffixed(text: str, suffixes: tuple, what: str) -> str:
    _output_file(text)
    if not text.lower().endswith(suffixes):
        raise ValueError(f"expected {what} ending in {', '.join(suffixes)}, got {quote(text)}")
    return text


input_path = _typed(_path, "path")  # an input file: UTF-8, names <= 255 bytes (existence: the readers')
input_path.file_of = str  # the file a value names (check_distinct_files; a NAME=FILE type says its own)


def _urdf(text: str) -> str:
    check_path_text(text)
    if text.startswith((PACKAGE_PREFIX, PYBULLET_DATA_PREFIX)):
        return str(resolve_path(text, Path.cwd()))
    return text


# A URDF file as files name it too: package://graspmix/... (the bundled data), pybullet_data://... (the installed
# pybullet_data's, e.g. pybullet_data://pr2_gripper.urdf), or a path.
urdf_path = _typed(_urdf, "URDF")
urdf_path.file_of = str
output_file = _typed(_output_file, "output file")  # a file that can be written, checked before the work
output_folder = _typed(_output_folder, "output folder")  # a folder that exists or can be made, writable
# an output_file that is a picture, or an interactive page, by its suffix
picture_file = _typed(lambda text: _suffixed(text, PICTURE_SUFFIXES, "a picture file"), "picture file")
html_file = _typed(lambda text: _suffixed(text, (".html", ".htm"), "a page"), "page file")
png_file = _typed(lambda text: _suffixed(text, (".png",), "a PNG file"), "PNG file")  # a 16-bit depth image
OUTPUT_TYPES = (output_file, picture_file, html_file, png_file)


def check_distinct_files(parser: argparse.ArgumentParser, args: argparse.Namespace) -> None:
    """A CliError when a file the command writes is also one it reads or another it writes (the same file by
    any path): writing it would replace the input, or one output the other."""
    seen: dict = {}
    for action in parser._actions:
        writes = action.type in OUTPUT_TYPES
        file_of = getattr(action.type, "file_of", None)  # an input type: the file a value names
        if not writes and file_of is None:
            continue
        value = getattr(args, action.dest, None)
        for text in value if isinstance(value, list) else [value]:
            if not isinstance(text, str):
                continue
            path = text if writes else file_of(text)
            key = os.path.realpath(path)
            name = f"{action.option_strings[0] if action.option_strings else action.dest} {path}"
            if key in seen:
                other, other_writes = seen[key]
                if writes or other_writes:
                    raise CliError(f"{name} and {other} are the same file: one would replace the other")
            seen[key] = (name, writes)


def parse_floats(text: str, n: int, what: str) -> np.ndarray:
    try:
        v = np.array([float(x) for x in text.split(",")])
    except ValueError:
        raise CliError(f"{what}: expected {n} comma-separated numbers, got {quote(text)}") from None
    if v.shape != (n,) or not np.all(np.isfinite(v)):
        raise CliError(f"{what}: expected {n} comma-separated finite numbers, got {quote(text)}")
    return v


def parse_joints(text: str, what: str) -> dict:
    out = {}
    for item in text.split(","):
        name, sep, value = item.partition("=")
        if not sep or not name.strip():
            raise CliError(f"{what}: expected name=value[,name=value...], got {quote(text)}")
        if name.strip() in out:
            raise CliError(f"{what}: joint {quote(name.strip())} is given twice")
        try:
            out[name.strip()] = check_float(float(value), f"{what}: joint {quote(name.strip())}")
        except ValueError:
            raise CliError(f"{what}: {quote(value)} is not a finite number") from None
    return out


def split_list(text: str, what: str, known) -> list[str]:
    items = [x.strip() for x in text.split(",") if x.strip()]
    if not items:
        raise CliError(f"{what}: empty list")
    for x in items:
        if x not in known:
            raise CliError(f"{what}: unknown value {quote(x)} (known: {', '.join(known)})")
    return items


def given(args, *names) -> dict:
    """The options among names that were given (not None), as keyword arguments: the library's defaults
    apply to the others."""
    return {n: getattr(args, n) for n in names if getattr(args, n) is not None}


def one_line(message: str, limit: int = 2000) -> str:
    """An error's text as one line of bounded length (a C++ message may quote a whole field)."""
    text = " ".join(str(message).split())
    return text if len(text) <= limit else text[:limit] + "..."


def report_error(command: str, message: str) -> int:
    print(f"graspmix_cli {command}: error: {one_line(message)}", file=sys.stderr)
    return 2
