"""Progress on stderr that reads well on a terminal and in a log.

On a terminal: a tqdm bar (one line, redrawn). Elsewhere (CI logs, pipes, notebooks'
captured stderr): plain lines, at most one every ``every`` seconds plus the last, so
updates never pile up on one line with carriage returns.
"""

from __future__ import annotations

import sys
import time

__internal__ = True  # tooling for the library's own modules
__all__ = ["Progress"]


class Progress:
    """``with Progress(total, "frames") as p: ... p.update()`` (``enabled=False``: silent).

    A tqdm bar on a terminal; elsewhere (a log, a pipe) a line ``done/total unit (rate, elapsed)``
    every ``every`` seconds and at the end.

    Parameters
    ----------
    total : int
        Units of work in all.
    unit : str
        Their name (``"frames"``).
    stream : file, optional, keyword-only
        Where it writes (default ``sys.stderr``).
    every : float, optional, keyword-only
        Seconds between lines when not on a terminal.
    enabled : bool, optional, keyword-only
        False: counts but writes nothing.
    """

    def __init__(self, total: int, unit: str, *, stream=None, every: float = 5.0, enabled: bool = True):
        self.total, self.unit, self.every, self.enabled = int(total), unit, float(every), bool(enabled)
        self.stream = sys.stderr if stream is None else stream
        self.done, self.start, self._last = 0, time.perf_counter(), -float("inf")
        self._bar = None
        if self.enabled and getattr(self.stream, "isatty", lambda: False)():
            from tqdm import tqdm

            self._bar = tqdm(total=self.total, unit=unit, file=self.stream, dynamic_ncols=True)

    def update(self, n: int = 1) -> None:
        self.done += n
        if not self.enabled:
            return
        if self._bar is not None:
            self._bar.update(n)
            return
        now = time.perf_counter()
        if now - self._last >= self.every or self.done >= self.total:
            self._last = now
            rate = self.done / max(now - self.start, 1e-9)
            self.stream.write(f"{self.done}/{self.total} {self.unit} ({rate:.2f} {self.unit}/s, "
                              f"{now - self.start:.1f} s)\n")
            self.stream.flush()

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False
