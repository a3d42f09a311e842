"""A progress bar with the time left, for long runs."""

from __future__ import annotations

import math
import sys
import time


def hms(seconds: float) -> str:
    if not math.isfinite(seconds):
        return "--:--"
    s = int(round(seconds))
    return f"{s // 3600}:{s % 3600 // 60:02d}:{s % 60:02d}" if s >= 3600 else f"{s // 60:02d}:{s % 60:02d}"


class Progress:
    """A one-line progress bar on stderr with the time left (from this session's pace). Off a terminal
    it prints a line every 5% instead of redrawing."""

    def __init__(
        self, total: int, done: int = 0, stream=None, width: int = 30, enabled: bool = True, unit: str = "attempts"
    ):
        self.total, self.done, self.start_done = total, done, done
        self.unit = unit
        self.stream = stream or sys.stderr
        self.width = width
        self.enabled = enabled
        self.t0 = time.perf_counter()
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self._last_pct = -1

    def line(self) -> str:
        frac = self.done / self.total if self.total else 1.0
        n = int(frac * self.width)
        elapsed = time.perf_counter() - self.t0
        new = self.done - self.start_done
        left = elapsed / new * (self.total - self.done) if new > 0 else math.inf
        return (
            f"[{'#' * n}{'.' * (self.width - n)}] {self.done}/{self.total} {self.unit} {frac * 100:5.1f}%  "
            f"elapsed {hms(elapsed)}  left {hms(left)}"
        )

    def update(self, n: int) -> None:
        self.done += n
        if not self.enabled:
            return
        if self.tty:
            print("\r" + self.line(), end="", file=self.stream, flush=True)
        else:
            pct = int(100 * self.done / max(self.total, 1)) // 5 * 5
            if pct != self._last_pct:
                self._last_pct = pct
                print(self.line(), file=self.stream, flush=True)

    def close(self) -> None:
        if self.enabled and self.tty:
            print(file=self.stream, flush=True)
