"""Checks of user input at the Python boundary, one helper per kind of value, so every entry point (the
library's functions, the command line, the file readers) fails the same way: a ValueError naming the input
and what was wrong, before any work starts and before a value reaches a C++ cast.

    check_int(seed, "seed", 0, SEED_MAX)          # 1.5, 2**63, True -> ValueError naming "seed"
    check_float(radius, "radius", gt=0.0)         # nan, inf, -1 -> ValueError
    check_output_path("out/grasps.json", "--out")  # missing folder, a folder, not writable -> ValueError
    quote(value)                                   # repr of a value, clipped to QUOTE_LIMIT characters
"""

from __future__ import annotations

import math
import numbers
import os
from pathlib import Path

QUOTE_LIMIT = 80  # characters of a value quoted in a message
SEED_MAX = 2**63 - 1  # seeds cross to C++ as 64-bit integers (signed on some paths)
INT_MAX = 2**31 - 1  # counts cross to C++ as int
# Counts bounded by what finishes in reasonable memory and time, so a typo (3e9 samples) is an error,
# not an allocation that fails after minutes or a machine brought to a halt.
MAX_SAMPLES = 1_000_000  # query samples per link, points drawn
# Grasps sampled per target: every one is returned with its frames (~7-13 KB each with its Python objects), so
# 100k take ~1 GB and ~10 s a target; a million, ~10 GB a target, can bring the machine down.
MAX_GRASPS = 100_000
# Grasps drawn per target (sampling.n_samples * sampling.oversample): a drawn grasp not returned is a few hundred
# bytes, but each is scored by every expert.
MAX_DRAWN = MAX_SAMPLES
MAX_COMPONENTS = 1000  # mixture components
MAX_ITERATIONS = 10_000_000  # EM or annealing iterations, simulation steps
MAX_SIM_TIME = 60.0  # s: longest simulated phase (closing, lifting, holding)
NAME_MAX = 255  # bytes of one file or folder name (Linux, macOS, Windows)
PATH_MAX = 4096  # bytes of a whole path (Linux)


def quote(value, limit: int = QUOTE_LIMIT) -> str:
    """repr(value), clipped to about `limit` characters (a 100 MB field is not echoed back)."""
    if isinstance(value, str) and len(value) > limit:
        return repr(value[:limit]) + f"... ({len(value)} characters)"
    try:
        text = repr(value)
    except Exception:  # a broken __repr__ must not hide the real error
        text = f"<{type(value).__name__}>"
    return text if len(text) <= limit else text[:limit] + "..."


def check_int(value, name: str, lo: int | None = None, hi: int | None = None) -> int:
    """value as an int: an integer (not a bool, not 1.5 or "3") within [lo, hi]; ValueError naming it."""
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise ValueError(f"{_subject(name)}must be an integer{_range(lo, hi)}, got {quote(value)}")
    v = int(value)
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        raise ValueError(f"{_subject(name)}must be an integer{_range(lo, hi)}, got {quote(v)}")
    return v


def check_seed(value, name: str = "seed") -> int:
    """A seed: an integer in [0, SEED_MAX]."""
    return check_int(value, name, 0, SEED_MAX)


def check_float(
    value, name: str, lo: float | None = None, hi: float | None = None, *, gt: float | None = None, finite: bool = True
) -> float:
    """value as a float: a real number (finite unless finite=False, never NaN), >= lo, > gt, <= hi."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValueError(f"{_subject(name)}must be a number{_bounds(lo, hi, gt)}, got {quote(value)}")
    try:
        v = float(value)
    except OverflowError:  # an integer beyond any float
        v = math.inf if value > 0 else -math.inf
    bad = math.isnan(v) or (finite and math.isinf(v))
    bad = bad or (lo is not None and v < lo) or (hi is not None and v > hi) or (gt is not None and v <= gt)
    if bad:
        kind = "a finite number" if finite else "a number"
        raise ValueError(f"{_subject(name)}must be {kind}{_bounds(lo, hi, gt)}, got {quote(v)}")
    return v


def check_sim_time(value, name: str) -> float:
    """A simulated duration in seconds: finite, >= 0, at most MAX_SIM_TIME."""
    return check_float(value, name, 0.0, MAX_SIM_TIME)


def _subject(name: str) -> str:
    return f"{name} " if name else ""


def _prefix(what: str) -> str:
    return f"{what}: " if what else ""


def _range(lo, hi) -> str:
    if lo is not None and hi is not None:
        return f" in [{lo}, {hi}]"
    if lo is not None:
        return f" >= {lo}"
    return f" <= {hi}" if hi is not None else ""


def _bounds(lo, hi, gt) -> str:
    parts = [
        f">= {lo:g}" if lo is not None else None,
        f"> {gt:g}" if gt is not None else None,
        f"<= {hi:g}" if hi is not None else None,
    ]
    parts = [p for p in parts if p]
    return " " + " and ".join(parts) if parts else ""


# ---- paths ----------------------------------------------------------------------------------------


def check_path_text(path, what: str = "") -> Path:
    """A path that can be named in files and passed to C++: UTF-8, names of at most NAME_MAX bytes."""
    if not isinstance(path, (str, bytes, os.PathLike)):
        raise ValueError(f"{_subject(what)}must be a path, got {quote(path)}")
    text = os.fspath(path)
    if isinstance(text, bytes):
        try:
            text = text.decode("utf-8")
        except UnicodeDecodeError:
            raise ValueError(f"{_prefix(what)}the path {quote(text)} is not valid UTF-8") from None
    if not text:
        raise ValueError(f"{_prefix(what)}empty path")
    if "\0" in text:
        raise ValueError(f"{_prefix(what)}the path {quote(text)} contains a NUL character")
    try:
        raw = text.encode("utf-8")
    except UnicodeEncodeError:
        raise ValueError(f"{_prefix(what)}the path {quote(text)} is not valid UTF-8") from None
    if len(raw) > PATH_MAX:
        raise ValueError(f"{_prefix(what)}the path {quote(text)} is longer than {PATH_MAX} bytes")
    for part in Path(text).parts:
        if len(part.encode("utf-8")) > NAME_MAX:
            raise ValueError(f"{_prefix(what)}the path {quote(text)} has a name longer than {NAME_MAX} bytes")
    return Path(text)


def check_input_file(path, what: str = "") -> Path:
    """An existing, readable file (not a folder); ValueError naming it otherwise ("no such <what> file")."""
    p = check_path_text(path, what)
    kind = f"{what} file" if what else "file"
    try:
        if p.is_dir():
            raise ValueError(f"{p}: is a folder, not a {kind}")
        if not p.is_file():
            raise ValueError(f"{p}: no such {kind}")
        if not os.access(p, os.R_OK):
            raise ValueError(f"{p}: the {kind} is not readable (permission denied)")
    except OSError as e:
        raise ValueError(f"{p}: cannot open the {kind} ({e.strerror})") from None
    return p


def check_output_path(path, what: str = "output") -> Path:
    """A file that can be written: its folder exists and is writable, and it is not itself a folder (or
    an unwritable file). Called before the work whose result it will hold, so nothing is lost."""
    p = check_path_text(path, what)
    folder = p.parent if str(p.parent) else Path(".")
    try:
        if p.is_dir():
            raise ValueError(f"{_prefix(what)}{p} is a folder, expected a file name")
        if not folder.exists():
            raise ValueError(f"{_prefix(what)}{p}: the folder {folder} does not exist")
        if not folder.is_dir():
            raise ValueError(f"{_prefix(what)}{p}: {folder} is not a folder")
        if not os.access(folder, os.W_OK | os.X_OK):
            raise ValueError(f"{_prefix(what)}{p}: the folder {folder} is not writable")
        if p.exists() and not os.access(p, os.W_OK):
            raise ValueError(f"{_prefix(what)}{p} exists and is not writable")
    except OSError as e:
        raise ValueError(f"{_prefix(what)}{p}: cannot be written ({e.strerror})") from None
    return p


def check_output_folder(path, what: str = "output folder") -> Path:
    """A folder that exists and is writable, or can be made: its nearest existing ancestor is a writable
    folder."""
    p = check_path_text(path, what)
    try:
        if p.exists():
            if not p.is_dir():
                raise ValueError(f"{_prefix(what)}{p} exists and is not a folder")
            if not os.access(p, os.W_OK | os.X_OK):
                raise ValueError(f"{_prefix(what)}the folder {p} is not writable")
            return p
        parent = p.absolute().parent
        while not parent.exists():
            parent = parent.parent
        if not parent.is_dir():
            raise ValueError(f"{_prefix(what)}{p}: {parent} is not a folder")
        if not os.access(parent, os.W_OK | os.X_OK):
            raise ValueError(f"{_prefix(what)}{p}: cannot be created, {parent} is not writable")
    except OSError as e:
        raise ValueError(f"{_prefix(what)}{p}: cannot be used ({e.strerror})") from None
    return p
