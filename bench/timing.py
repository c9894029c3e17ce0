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


def interleaved(fns: dict[str, Callable[[], object]], repeats: int = 15,
                warmup: int = 2) -> dict[str, list[float]]:
    """Wall times of each function, measured round-robin in the same loop.

    Returns every run's seconds per function, in round order, so that callers can pair
    runs of one round (same machine state) and take the median of per-round ratios.
    """
    for fn in fns.values():
        for _ in range(warmup):
            jax.block_until_ready(fn())
    times: dict[str, list[float]] = {k: [] for k in fns}
    for _ in range(repeats):
        for k, fn in fns.items():
            times[k].append(_once(fn))
    return times


def paired_ratio(times: dict[str, list[float]], subject: str, baselines: list[str]) -> float:
    """Median over rounds of subject / (fastest baseline in that round)."""
    rounds = zip(times[subject], *(times[b] for b in baselines))
    return statistics.median(t / min(bs) for t, *bs in rounds)


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
