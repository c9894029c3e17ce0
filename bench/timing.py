"""Timing helpers: compile once, then medians of several runs (machines are noisy).

Comparisons against a baseline interleave the two (A, B, A, B, …) so that both see the
same machine load, and report the ratio of the medians.
"""

from __future__ import annotations

import os
import statistics
import time
from typing import Callable

import jax
import numpy as np


def _once(fn) -> float:
    t = time.perf_counter()
    jax.block_until_ready(fn())
    return time.perf_counter() - t


def median_seconds(fn: Callable[[], object], repeats: int = 7, warmup: int = 1) -> float:
    """Median wall time of ``fn()`` over ``repeats`` runs after ``warmup`` runs.

    JAX results are waited for with ``block_until_ready``.
    """
    for _ in range(warmup):
        jax.block_until_ready(fn())
    return statistics.median(_once(fn) for _ in range(repeats))


def interleaved(fns: dict[str, Callable[[], object]], repeats: int = 15, warmup: int = 2,
                block: int = 5) -> dict[str, list[float]]:
    """Wall times of each function, measured round-robin in the same loop.

    Each round runs every function ``block`` times in a row and keeps the median of
    that block: the first run after switching libraries can be slowed by the previous
    library's worker threads still spinning (XLA's pool does), and the block median
    discards it. Returns one time per round per function, in round order, so callers
    can pair the functions of one round (same machine state).
    """
    for fn in fns.values():
        for _ in range(warmup):
            jax.block_until_ready(fn())
    times: dict[str, list[float]] = {k: [] for k in fns}
    for _ in range(repeats):
        for k, fn in fns.items():
            times[k].append(statistics.median(_once(fn) for _ in range(block)))
    return times


def paired_ratio(times: dict[str, list[float]], subject: str, baselines: list[str]):
    """Per-round subject / (fastest baseline that round): (median, 25th, 75th percentile)."""
    rounds = zip(times[subject], *(times[b] for b in baselines))
    ratios = np.array([t / min(bs) for t, *bs in rounds])
    q1, med, q3 = np.percentile(ratios, [25, 50, 75])
    return float(med), float(q1), float(q3)


def fft_work(n: int, forward: int, inverse: int) -> dict[str, Callable[[], object]]:
    """The bare real-FFT work of a step on the fastest CPU FFTs here, as callables.

    ``forward`` real (n, n) float32 fields through ``rfft2`` and ``inverse`` half spectra
    through ``irfft2``, batched, with every core: scipy.fft (``workers``) and ducc0
    (``nthreads``) when installed.
    """
    cores = os.cpu_count() or 1
    rng = np.random.default_rng(0)
    x = rng.standard_normal((forward, n, n)).astype(np.float32)
    spec = (rng.standard_normal((inverse, n, n // 2 + 1))
            + 1j * rng.standard_normal((inverse, n, n // 2 + 1))).astype(np.complex64)
    import scipy.fft as sfft

    work = {"scipy.fft": lambda: (sfft.rfft2(x, workers=cores), sfft.irfft2(spec, s=(n, n), workers=cores))}
    try:
        import ducc0
    except ImportError:
        return work
    work["ducc0"] = lambda: (ducc0.fft.r2c(x, axes=(1, 2), nthreads=cores),
                             ducc0.fft.c2r(spec, axes=(1, 2), lastsize=n, forward=False, inorm=2,
                                           nthreads=cores))
    return work
