"""The windowed space–time spectrum of a record, computed once for the checks that read it.

The dispersion ridge, the standing-wave locking and the direction of travel all read the same
transform: the frames less their time mean, a Hann window in time, and the Fourier transform in
x, y and t. :func:`spacetime_spectrum` computes it with scipy's FFT on every core; a
:class:`~wavephys.harness.Record` keeps the one of its frames (``Record.spectrum()``), so the
checks of one ``check_record`` call share it. Records of more than 2²² samples are transformed in
single precision (complex64: the rounding floor lies below 1e-12 of the peak power, far under the
1e-6 the measurements keep), smaller ones in double.
"""

from __future__ import annotations

import os

import numpy as np

__all__ = ["spacetime_spectrum", "SINGLE_ABOVE", "workers"]

SINGLE_ABOVE = 1 << 22
"""Records with more samples than this are transformed in single precision (module doc)."""


def workers() -> int:
    """How many threads the harness's FFTs use: the machine's cores, at most 4.

    Returns
    -------
    int
        The thread count, >= 1.
    """
    return max(1, min(4, os.cpu_count() or 1))


def spacetime_spectrum(eta) -> np.ndarray:
    """The Hann-windowed (in time) 3-D Fourier transform of frames ``(n_t, n_y, n_x)`` less their time mean.

    Parameters
    ----------
    eta : array_like (n_t, n_y, n_x)
        Heights, m, finite, n_t ≥ 2.

    Returns
    -------
    numpy.ndarray (n_t, n_y, n_x)
        Complex spectrum, axes (ω, k_y, k_x) in numpy's FFT order; complex64 above :data:`SINGLE_ABOVE` samples,
        else complex128. The window is ``hanning(n_t + 2)[1:-1]`` (no zero end samples).
    """
    import scipy.fft

    from wavephys.core.inputs import check_array

    check_array("eta", eta, ndim=3)
    if np.shape(eta)[0] < 2 or min(np.shape(eta)) < 1:
        raise ValueError(f"eta must be frames (n_t, n_y, n_x) with n_t >= 2 (one row, n_y = 1, is a 1-D record), got "
                         f"shape {np.shape(eta)}")
    single = np.size(eta) > SINGLE_ABOVE
    real = np.float32 if single else np.float64
    eta = np.asarray(eta, real)
    nt = eta.shape[0]
    window = np.hanning(nt + 2)[1:-1].astype(real)
    spatial = scipy.fft.fft2(eta - eta.mean(axis=0), workers=workers())
    spatial *= window[:, None, None]
    return scipy.fft.fft(spatial, axis=0, workers=workers(), overwrite_x=True)
