"""Validation harness: measure the physics of *any* simulator's output.

Users call these from their own test suites on height fields produced by whatever code
they want to check (ours, a shader, a finite-difference toy):

* :func:`measure_dispersion` — the ω–k ridge of a space–time height field;
* :func:`dispersion_error` — measured ω against theory for given :class:`~wavephys.Water`;
* :func:`measure_energy` — potential, capillary and kinetic energy per unit area from η
  and η̇ (linear theory, SPEC §1.8);
* :class:`Check`, :func:`compare`, :func:`bound`, :func:`assert_check` — results that
  report expected vs measured vs tolerance, and fail with that table.

The pytest plugin (:mod:`wavephys.pytest_plugin`, registered as ``pytest11``) exposes
them as fixtures. Everything here runs on the host in float64 numpy: it is measurement
code, not the hot path.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from wavephys._inputs import check_array, check_choice, check_scalar
from wavephys.params import Water

__all__ = [
    "DispersionSamples",
    "measure_dispersion",
    "dispersion_error",
    "Energy",
    "measure_energy",
    "Check",
    "compare",
    "bound",
    "assert_check",
]


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
    spec = np.fft.fft(np.fft.fft2(eta) * window[:, None, None], axis=0)
    power = np.abs(spec) ** 2  # (nt, ny, nx) over (ω, ky, kx)
    mx = np.fft.fftfreq(nx) * nx
    my = np.fft.fftfreq(ny) * ny
    if nx == ny:
        # exact shells: integer m² = mx² + my²
        shell_key = (my[:, None] ** 2 + mx[None, :] ** 2).astype(np.int64)
    else:
        kk = np.sqrt((my[:, None] / ny) ** 2 + (mx[None, :] / nx) ** 2)
        shell_key = np.round(kk * 1e9).astype(np.int64)
    kmag = 2 * np.pi * np.sqrt((my[:, None] / (ny * dx)) ** 2 + (mx[None, :] / (nx * dx)) ** 2)
    keys, inverse = np.unique(shell_key.ravel(), return_inverse=True)
    flat = power.reshape(nt, -1)
    shells = np.zeros((nt, keys.size))
    for t in range(nt):
        shells[t] = np.bincount(inverse, weights=flat[t], minlength=keys.size)
    k_shell = np.zeros(keys.size)
    np.maximum.at(k_shell, inverse, kmag.ravel())
    half = nt // 2
    folded = shells[: half + 1].copy()
    folded[1:half] += shells[nt - 1: nt - half: -1]
    dw = 2 * np.pi / (nt * dt)

    ks, ws, ps = [], [], []
    for j in range(keys.size):
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
    from wavephys.dispersion import angular_frequency

    theory = np.asarray(angular_frequency(np.asarray(samples.k, np.float32), water), np.float64)
    return samples.omega / theory - 1.0


@dataclass(frozen=True)
class Energy:
    """Mean wave energy per unit area, J/m² (linear theory)."""

    potential: float
    capillary: float
    kinetic: float

    @property
    def total(self) -> float:
        return self.potential + self.capillary + self.kinetic


def measure_energy(eta, eta_dot, dx: float, water: Water) -> Energy:
    """Energy per unit area from height η (m) and its rate η̇ (m/s) on a periodic grid.

    potential ½ρg⟨η²⟩; capillary ½σ⟨|∇η|²⟩ (spectral gradient); kinetic ½ρ⟨φ·Kφ⟩ with the
    surface potential recovered from the kinematic condition, φ̂ = η̇̂ / K,
    K = |k| tanh(|k| h) (SPEC §1.8). For free waves kinetic ≈ potential + capillary
    (equipartition); a monochromatic wave of amplitude A has total ½ρgA² (σ = 0).

    Parameters
    ----------
    eta, eta_dot : array_like
        Same shape ``(..., n_y, n_x)``; leading axes give one Energy of arrays each.
    dx : float
        Grid spacing, m, > 0.
    water : Water
    """
    check_array("eta", eta, min_ndim=2)
    check_array("eta_dot", eta_dot, min_ndim=2)
    if np.shape(eta) != np.shape(eta_dot):
        raise ValueError(f"eta and eta_dot must have one shape, got {np.shape(eta)} and {np.shape(eta_dot)}")
    check_scalar("dx", dx, lo=0.0, lo_open=True)
    eta = np.asarray(eta, np.float64)
    eta_dot = np.asarray(eta_dot, np.float64)
    ny, nx = eta.shape[-2:]
    ky = 2 * np.pi * np.fft.fftfreq(ny, dx)[:, None]
    kx = 2 * np.pi * np.fft.fftfreq(nx, dx)[None, :]
    k = np.sqrt(kx**2 + ky**2)
    depth = float(water.depth)
    K = k * (1.0 if math.isinf(depth) else np.tanh(k * depth))
    n = nx * ny
    eh = np.fft.fft2(eta)
    dh = np.fft.fft2(eta_dot)
    mean_sq = lambda f: np.sum(np.abs(f) ** 2, axis=(-2, -1)) / n**2  # Parseval: ⟨|f|²⟩
    pot = 0.5 * float(water.rho) * float(water.g) * np.mean(eta**2, axis=(-2, -1))
    cap = 0.5 * float(water.sigma) * mean_sq(k * eh)
    invK = np.where(K > 0, 1.0 / np.where(K > 0, K, 1.0), 0.0)
    kin = 0.5 * float(water.rho) * np.sum(np.abs(dh) ** 2 * invK, axis=(-2, -1)) / n**2
    return Energy(pot, cap, kin)


@dataclass(frozen=True)
class Check:
    """One validated quantity: what was expected, what was measured, and the verdict.

    ``relation`` is ``"≈"`` (|error| ≤ tolerance, error relative if ``relative``), or
    ``"≤"``/``"≥"`` (a bound: the measured value against ``expected``).
    """

    quantity: str
    expected: float
    measured: float
    tolerance: float
    relation: str = "≈"
    relative: bool = True
    unit: str = ""

    @property
    def error(self) -> float:
        if self.relation != "≈":
            return self.measured - self.expected
        diff = self.measured - self.expected
        return diff / self.expected if self.relative and self.expected != 0 else diff

    @property
    def ok(self) -> bool:
        m = self.measured
        if not math.isfinite(m):
            return False
        if self.relation == "≤":
            return m <= self.expected
        if self.relation == "≥":
            return m >= self.expected
        return abs(self.error) <= self.tolerance

    def as_dict(self) -> dict:
        return dict(quantity=self.quantity, expected=self.expected, measured=self.measured,
                    error=self.error, tolerance=self.tolerance, relation=self.relation,
                    relative=self.relative, unit=self.unit, ok=self.ok)

    def report(self) -> str:
        tol = (f"±{self.tolerance:.3g}{' rel' if self.relative else ''}"
               if self.relation == "≈" else f"{self.relation} {self.expected:.6g}")
        return (f"{self.quantity}: expected {self.expected:.6g} {self.unit}, measured "
                f"{self.measured:.6g} {self.unit}, error {self.error:.3g}, tolerance {tol}: "
                f"{'ok' if self.ok else 'FAILED'}")


def compare(quantity: str, measured, expected, *, rtol: Optional[float] = None,
            atol: Optional[float] = None, unit: str = "") -> Check:
    """A Check that ``measured`` ≈ ``expected`` within ``rtol`` (relative) or ``atol``."""
    if (rtol is None) == (atol is None):
        raise ValueError("give exactly one of rtol, atol")
    tol = rtol if rtol is not None else atol
    check_scalar("rtol" if rtol is not None else "atol", tol, lo=0.0)
    return Check(quantity, float(expected), float(measured), float(tol), "≈", rtol is not None, unit)


def bound(quantity: str, measured, limit, *, relation: str = "≤", unit: str = "") -> Check:
    """A Check that ``measured`` ≤ ``limit`` (or ≥ with ``relation="≥"``)."""
    check_choice("relation", relation, ("≤", "≥"))
    return Check(quantity, float(limit), float(measured), 0.0, relation, False, unit)


def assert_check(check: Check) -> Check:
    """Raise ``AssertionError`` with the check's report unless it is ok; return it."""
    if not check.ok:
        raise AssertionError(check.report())
    return check
