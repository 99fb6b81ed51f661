"""A progress bar with rate and ETA for long runs (stderr; one line on a terminal)."""

from __future__ import annotations

import sys
import time


class ProgressBar:
    """``bar(done, total, from_cache)`` redraws ``[#####.....] 640/1600 40% 52 pts/s ETA 0:18``.

    On a terminal the line is redrawn in place (at most 10 times a second);
    otherwise a line is written at every further 10 % so logs stay short.
    """

    def __init__(self, label: str, stream=None, width: int = 30):
        self.label = label
        self.stream = stream or sys.stderr
        self.width = width
        self.tty = bool(getattr(self.stream, "isatty", lambda: False)())
        self.t0 = time.perf_counter()
        self.last_draw = 0.0
        self.last_decile = -1
        self.first = None

    def __call__(self, done: int, total: int, from_cache: int) -> None:
        now = time.perf_counter()
        if self.first is None:
            self.first = done
            if from_cache:
                self.stream.write(f"{self.label}: {from_cache} of {total} points taken from the cache (resuming)\n")
        frac = done / total if total else 1.0
        fresh = done - self.first
        rate = fresh / (now - self.t0) if now > self.t0 and fresh else 0.0
        eta = (total - done) / rate if rate else None
        fill = int(round(frac * self.width))
        text = (f"{self.label}: [{'#' * fill}{'.' * (self.width - fill)}] {done}/{total} {100 * frac:3.0f}%"
                f" {rate:.0f} pts/s ETA {_clock(eta)}")
        if self.tty:
            if done == total or now - self.last_draw > 0.1:
                self.stream.write("\r" + text + ("\n" if done == total else ""))
                self.stream.flush()
                self.last_draw = now
        elif int(10 * frac) > self.last_decile:
            self.last_decile = int(10 * frac)
            self.stream.write(text + "\n")
            self.stream.flush()


def _clock(seconds: float | None) -> str:
    if seconds is None:
        return "--:--"
    m, s = divmod(int(round(seconds)), 60)
    h, m = divmod(m, 60)
    return f"{h}:{m:02d}:{s:02d}" if h else f"{m}:{s:02d}"
