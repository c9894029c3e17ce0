"""Dispersion measured from any simulator's output: the ω–k ridge of a space–time height field.

:func:`measure_dispersion` takes heights ``(n_t, n_y, n_x)`` sampled every Δt on a grid
of spacing Δx (any simulator: ours, a shader, a finite-difference toy) and returns one
measured (k, ω) per shell of equal |k|; :func:`dispersion_error` compares them with
linear theory for given :class:`~wavephys.Water`. Host-side float64 numpy: measurement
code, not the hot path.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from wavephys.core.inputs import check_array, check_instance, check_scalar
from wavephys.core.spectral import angular_wavenumbers
from wavephys.core.water import Water

__all__ = ["DispersionSamples", "measure_dispersion", "dispersion_error"]


@dataclass(frozen=True)
class DispersionSamples:
    """Measured points of the dispersion relation, one per wavenumber shell.

    Attributes
    ----------
    k : ndarray
        Shell wavenumber |k|, rad/m (ascending).
    omega : ndarray
        Measured angular frequency of the spectral ridge, rad/s.
    power : ndarray
        Ridge power (arbitrary units, relative to each other).
    resolution : float
        Frequency bin width 2π/(n_t Δt), rad/s.
    """

    k: np.ndarray
    omega: np.ndarray
    power: np.ndarray
    resolution: float

    def select(self, k_min: float = 0.0, k_max: float = math.inf) -> "DispersionSamples":
        """The samples with k_min ≤ k ≤ k_max."""
        m = (self.k >= k_min) & (self.k <= k_max)
        return DispersionSamples(self.k[m], self.omega[m], self.power[m], self.resolution)


def _shells(power, dx):
    """Sum the space–time power (n_t, n_y, n_x) over shells of equal |k|: (k of each shell, (n_t, shells))."""
    nt, ny, nx = power.shape
    mx = np.fft.fftfreq(nx) * nx
    my = np.fft.fftfreq(ny) * ny
    if nx == ny:  # exact shells: integer m² = mx² + my²
        shell_key = (my[:, None] ** 2 + mx[None, :] ** 2).astype(np.int64)
    else:
        shell_key = np.round(np.sqrt((my[:, None] / ny) ** 2 + (mx[None, :] / nx) ** 2) * 1e9).astype(np.int64)
    ky, kx = angular_wavenumbers((ny, nx), dx, xp=np)
    kmag = np.sqrt(kx * kx + ky * ky)
    keys, inverse = np.unique(shell_key.ravel(), return_inverse=True)
    flat = power.reshape(nt, -1)
    shells = np.stack([np.bincount(inverse, weights=flat[t], minlength=keys.size) for t in range(nt)])
    k_shell = np.zeros(keys.size)
    np.maximum.at(k_shell, inverse, kmag.ravel())
    return k_shell, shells


def measure_dispersion(eta, dx: float, dt: float, *, min_relative_power: float = 1e-6,
                       min_bins: float = 4.0) -> DispersionSamples:
    """Measure ω(k) from a space–time height field.

    The field is Hann-windowed in time and Fourier transformed in x, y and t. For each
    shell of equal |k| the power is summed over the shell and over ±ω (a wave and its
    mirror image); the ridge is the peak in ω, refined by a parabola through the
    log-power of the peak bin and its neighbours (error ≲ 0.05 bins for a clean ridge).

    Parameters
    ----------
    eta : array_like
        Heights, m, shape ``(n_t, n_y, n_x)``, uniformly sampled in time; n_t ≥ 8.
    dx : float
        Grid spacing, m, > 0 (the same along x and y).
    dt : float
        Time between frames, s, > 0. Frequencies above π/Δt alias: sample fast enough.
    min_relative_power : float
        Shells whose ridge power is below this fraction of the strongest are dropped.
    min_bins : float
        Ridges closer than this many frequency bins to ω = 0 or to π/Δt are dropped
        (they cannot be located reliably).

    Returns
    -------
    DispersionSamples
    """
    check_array("eta", eta, min_ndim=3)
    eta = np.asarray(eta, dtype=np.float64)
    if eta.ndim != 3:
        raise ValueError(f"eta must have shape (n_t, n_y, n_x), got {eta.shape}")
    nt, ny, nx = eta.shape
    if nt < 8:
        raise ValueError(f"eta must have at least 8 time samples, got {nt}")
    check_scalar("dx", dx, lo=0.0, lo_open=True)
    check_scalar("dt", dt, lo=0.0, lo_open=True)
    check_scalar("min_relative_power", min_relative_power, lo=0.0, hi=1.0)

    eta = eta - eta.mean(axis=0)
    window = np.hanning(nt + 2)[1:-1]
    power = np.abs(np.fft.fft(np.fft.fft2(eta) * window[:, None, None], axis=0)) ** 2  # (ω, ky, kx)
    k_shell, shells = _shells(power, dx)
    half = nt // 2
    folded = shells[: half + 1].copy()
    folded[1:half] += shells[nt - 1: nt - half: -1]
    dw = 2 * np.pi / (nt * dt)

    ks, ws, ps = [], [], []
    for j in range(k_shell.size):
        if k_shell[j] == 0:
            continue
        col = folded[:, j]
        i = int(np.argmax(col))
        if i < 1 or i >= half or col[i] <= 0:
            continue
        a, b, c = np.log(np.maximum(col[i - 1: i + 2], 1e-300))
        denom = a - 2 * b + c
        offset = 0.5 * (a - c) / denom if denom < 0 else 0.0
        w = (i + offset) * dw
        if w < min_bins * dw or w > (half - min_bins) * dw:
            continue
        ks.append(k_shell[j])
        ws.append(w)
        ps.append(col[i])
    ks, ws, ps = map(np.asarray, (ks, ws, ps))
    if ks.size:
        keep = ps >= min_relative_power * ps.max()
        ks, ws, ps = ks[keep], ws[keep], ps[keep]
    order = np.argsort(ks)
    return DispersionSamples(ks[order], ws[order], ps[order], dw)


def dispersion_error(samples: DispersionSamples, water: Water) -> np.ndarray:
    """Relative error of measured ω against ω(k) of linear theory for ``water`` (signed)."""
    from wavephys.physics.dispersion import angular_frequency

    check_instance("samples", samples, DispersionSamples, "wavephys.harness.DispersionSamples")
    check_instance("water", water, Water, "wavephys.Water")

    theory = np.asarray(angular_frequency(np.asarray(samples.k, np.float32), water), np.float64)
    return samples.omega / theory - 1.0
