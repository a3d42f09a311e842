"""What every subcommand shares: the user-error type and the parsers of option values."""
from __future__ import annotations

import numpy as np


class CliError(Exception):
    """A user error: printed as one line, exit status 2."""


def parse_floats(text: str, n: int, what: str) -> np.ndarray:
    try:
        v = np.array([float(x) for x in text.split(",")])
    except ValueError:
        raise CliError(f"{what}: expected {n} comma-separated numbers, got {text!r}") from None
    if v.shape != (n,) or not np.all(np.isfinite(v)):
        raise CliError(f"{what}: expected {n} comma-separated finite numbers, got {text!r}")
    return v


def parse_joints(text: str, what: str) -> dict:
    out = {}
    for item in text.split(","):
        name, sep, value = item.partition("=")
        if not sep:
            raise CliError(f"{what}: expected name=value[,name=value...], got {text!r}")
        try:
            out[name.strip()] = float(value)
        except ValueError:
            raise CliError(f"{what}: {value!r} is not a number") from None
    return out


def split_list(text: str, what: str, known) -> list[str]:
    items = [x.strip() for x in text.split(",") if x.strip()]
    if not items:
        raise CliError(f"{what}: empty list")
    for x in items:
        if x not in known:
            raise CliError(f"{what}: unknown value {x!r} (known: {', '.join(known)})")
    return items


def given(args, *names) -> dict:
    """The options among names that were given (not None), as keyword arguments: the library's defaults
    apply to the others."""
    return {n: getattr(args, n) for n in names if getattr(args, n) is not None}
