"""Timing helpers: compile once, then medians of several runs (machines are noisy).

Comparisons against a baseline interleave the two (A, B, A, B, …) so that both see the
same machine load, and report the ratio of the medians.
"""

from __future__ import annotations

import os
from typing import Callable

import numpy as np

from wavephys.core.timing import interleaved, median_seconds  # noqa: F401  (the one place; re-exported)


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
