"""Wall times of compiled work: compile once, then medians of several runs (machines are noisy).

Comparisons against a baseline interleave the two (A, B, A, B, …) so that both see the same
machine load; callers report ratios of the medians. Used by the planner's calibration
(``wavephys calibrate``) and by the bench.
"""

from __future__ import annotations

import statistics
import time
from typing import Callable

import jax

__internal__ = True  # tooling for the library's own measurements
__all__ = ["median_seconds", "interleaved"]


def _once(fn) -> float:
    t = time.perf_counter()
    jax.block_until_ready(fn())
    return time.perf_counter() - t


def median_seconds(fn: Callable[[], object], repeats: int = 7, warmup: int = 1) -> float:
    """Median wall time of ``fn()``, s, over ``repeats`` runs after ``warmup`` runs (JAX results
    are waited for with ``block_until_ready``).

    Parameters
    ----------
    fn : Callable
        Called with no arguments.
    repeats : int
        Timed runs.
    warmup : int
        Untimed runs first (compilation, caches).

    Returns
    -------
    float
        The median, s.
    """
    for _ in range(warmup):
        jax.block_until_ready(fn())
    return statistics.median(_once(fn) for _ in range(repeats))


def interleaved(fns: dict[str, Callable[[], object]], repeats: int = 15, warmup: int = 2,
                block: int = 5) -> dict[str, list[float]]:
    """Wall times of each function, s, measured round-robin in the same loop.

    Each round runs every function ``block`` times in a row and keeps the median of that
    block: the first run after switching can be slowed by the previous function's worker
    threads still spinning (XLA's pool does), and the block median discards it. Returns one
    time per round per function, in round order, so callers can pair the functions of one
    round (same machine state).

    Parameters
    ----------
    fns : dict of str to Callable
        The functions, each called with no arguments.
    repeats : int
        Rounds.
    warmup : int
        Untimed runs of each function first.
    block : int
        Runs of a function in a row within a round (their median is kept).

    Returns
    -------
    dict of str to list of float
        Per function, one time per round, s, in round order.
    """
    for fn in fns.values():
        for _ in range(warmup):
            jax.block_until_ready(fn())
    times: dict[str, list[float]] = {k: [] for k in fns}
    for _ in range(repeats):
        for k, fn in fns.items():
            times[k].append(statistics.median(_once(fn) for _ in range(block)))
    return times
