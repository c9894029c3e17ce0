r"""Steady wakes of moving pressure sources, and wake-angle measurement (any simulator).

Steady wake (ship frame, source moving at speed U in +x): the complex wave field ψ
obeys ψ_t = −iωψ + S with the pressure forcing S = −p/ρ (linearized Bernoulli), so a
steady pattern Ψ(x − Ut) has, per Fourier mode,

.. math::

    \hat\Psi(\mathbf k) = \frac{-\hat p(\mathbf k)/\rho}{i(\omega(k) - k_x U) + \varepsilon},
    \qquad \hat\eta = \mathrm{Re}\text{-part of } \frac{iK}{\omega}\hat\Psi,

where ε > 0 is Rayleigh's fictitious damping: the radiation condition that puts the
waves behind the source (ε → 0⁺ is the physical limit; a finite ε fades the wake over
a distance ≈ U/ε so that it does not wrap around the periodic grid). Gravity,
capillarity and finite depth all enter through ω(k) and K(k) (SPEC §1.1). At U = 0 it
reduces to the hydrostatic depression η = −p/(ρg) for a broad source.

Kelvin's result for deep water, gravity only: the wake is confined to a wedge of
half-angle arcsin(1/3) = 19.47° whose edge (the cusp line) carries the largest
amplitude for a point source; transverse waves on the track have wavelength 2πU²/g.
For sources that are not small against 2πU²/g the angle of maximum amplitude shrinks
(Rabaud & Moisy 2013: ∝ 1/Fr at large Froude number): :func:`wake_angle` measures the
angle of maximum amplitude from any height field.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import jax.numpy as jnp
import numpy as np

from wavephys._inputs import check_array, check_choice, check_scalar
from wavephys.dispersion import angular_frequency, surface_operator
from wavephys.heights import height_multiplier
from wavephys.params import Grid, Water

__all__ = ["GaussianPressure", "HullSource", "steady_wake", "WakeAngle", "wake_angle", "track_wavelength", "KELVIN_ANGLE",
           "transverse_wavelength"]

KELVIN_ANGLE = math.degrees(math.asin(1.0 / 3.0))
"""Kelvin's wake half-angle for deep-water gravity waves, degrees (19.47°)."""


def transverse_wavelength(speed, water: Water = Water(sigma=0.0)):
    """Deep-water gravity wavelength of the transverse waves on the track, 2πU²/g, m."""
    check_scalar("speed", speed, lo=0.0, lo_open=True)
    return 2 * math.pi * speed**2 / float(water.g)


@dataclass(frozen=True)
class GaussianPressure:
    """Surface pressure p(x) = p0·exp(−|x − x_s|²/(2σ²)) (Pa), x_s at the grid centre.

    Parameters
    ----------
    amplitude : float
        p0, Pa (positive pushes the surface down).
    size : float
        σ, m, > 0 (resolved: ≥ the grid spacing).
    """

    amplitude: float = 100.0
    size: float = 0.1

    def __post_init__(self):
        check_scalar("amplitude", self.amplitude)
        check_scalar("size", self.size, lo=0.0, lo_open=True)

    def spectrum(self, grid: Grid):
        """DFT of p on the grid (Pa per point, DFT convention), full spectrum (n, n)."""
        k2 = grid.wavenumber_magnitude() ** 2
        ky, kx = grid.wavenumbers()
        half = grid.length / 2
        phase = jnp.exp(-1j * (kx + ky) * half)  # source at coordinate 0 = index n // 2
        return (self.amplitude * 2 * jnp.pi * self.size**2 / grid.dx**2) * jnp.exp(-0.5 * k2 * self.size**2) * phase


@dataclass(frozen=True)
class HullSource:
    """The moving-hull source of Loviscach's ship kernels, as a steady-wake forcing.

    A hull f (``wavephys.ship_waves.Hull``) of strength s (m²/s) moving at U in +x feeds
    ψ at the rate ∂(s f)/∂t = −s U ∂f/∂x; as a pressure, p = ρ s U ∂f/∂x (a dipole).
    Use it to compare :class:`~wavephys.simulation.Simulation` ships with their steady wake.
    """

    hull: object
    strength: float = 0.01

    def forcing(self, grid: Grid, water: Water, speed: float):
        from wavephys.ship_waves import hull_spectrum

        ky, kx = grid.wavenumbers()
        f_hat = hull_spectrum(self.hull, grid, (0.0, 0.0), (0.0, 0.0, 0.0))
        return -1j * kx * speed * self.strength * f_hat


def steady_wake(grid: Grid, water: Water, speed: float, source, damping: float | None = None):
    """Steady first-order height (m) of ``source`` moving in +x at ``speed``, centred on the grid.

    Parameters
    ----------
    grid : Grid
    water : Water
    speed : float
        U, m/s, ≥ 0.
    source : GaussianPressure
        The pressure distribution (its size must be ≥ the grid spacing).
    damping : float, optional
        ε, 1/s, > 0 (default 8U/L: the wake fades to e⁻⁴ over half the grid).
    """
    if not isinstance(grid, Grid):
        raise TypeError(f"grid must be a wavephys.Grid, got {type(grid).__name__}")
    check_scalar("speed", speed, lo=0.0)
    if not isinstance(source, (GaussianPressure, HullSource)):
        raise TypeError(f"source must be a GaussianPressure or HullSource, got {type(source).__name__}")
    if isinstance(source, GaussianPressure) and source.size < float(grid.dx):
        raise ValueError(f"source size {source.size} m must be ≥ the grid spacing {float(grid.dx)} m")
    if damping is None:
        damping = 8.0 * max(speed, 1e-3) / float(grid.length)
    check_scalar("damping", damping, lo=0.0, lo_open=True)
    k = grid.wavenumber_magnitude()
    ky, kx = grid.wavenumbers()
    omega = angular_frequency(k, water)
    forcing = (-source.spectrum(grid) / water.rho if isinstance(source, GaussianPressure)
               else source.forcing(grid, water, speed))
    psi_hat = forcing / (1j * (omega - kx * speed) + damping)
    eta_hat = 1j * height_multiplier(k, water) * psi_hat
    return jnp.fft.ifft2(eta_hat).real


@dataclass(frozen=True)
class WakeAngle:
    """A measured wake half-angle: ``angle`` ± ``uncertainty`` (degrees), by ``method``."""

    angle: float
    uncertainty: float
    method: str
    points: int

    def __str__(self):
        return f"{self.angle:.2f}° ± {self.uncertainty:.2f}° ({self.method}, {self.points} sections)"


def _envelope(profile):
    """Amplitude envelope along the last axis (analytic signal of each half)."""
    n = profile.shape[-1]
    spec = np.fft.fft(profile, axis=-1)
    h = np.zeros(n)
    h[0] = 1
    h[1:(n + 1) // 2] = 2
    if n % 2 == 0:
        h[n // 2] = 1
    return np.abs(np.fft.ifft(spec * h, axis=-1))


def wake_angle(eta, grid: Grid, *, source=(0.0, 0.0), direction: float = 0.0, method: str = "max",
               near: float, far: float, exclude: float = 0.0) -> WakeAngle:
    """Measure the half-angle of a wake in a height field (any source, any simulator).

    The field is read in the source's frame: sections perpendicular to the track at
    distances d ∈ [``near``, ``far``] behind ``source`` (moving toward ``direction``,
    radians, 0 = +x). In each section the envelope of η across the track (analytic
    signal) is taken and, on each side, the lateral position y(d) of its maximum
    (``method="max"``: the angle of maximum amplitude, which for a near-point source is
    the cusp line, Kelvin's 19.47° in deep water). Then y(d) = a + b·d + c·d^{1/3} is
    fitted (d^{1/3}: the Airy width of the cusp region; a: the offset of a finite
    source); the angle is atan(b), with the fit's standard error (or half the
    disagreement of the two sides, if larger) as uncertainty.

    Only ``"max"`` is implemented and validated so far (19.47° ± 0.02° measured for a
    near-point source); an outer-edge measurement for sources of moderate size is not.

    Parameters
    ----------
    eta : array_like (n, n)
        Heights on ``grid``, m.
    near, far : float
        Range of distances behind the source, m, 0 < near < far ≤ L/2.
    exclude : float
        Half-width of a strip along the track that is ignored, m (the transverse waves).
    """
    n = grid.n
    check_array("eta", eta, shape_tail=(n, n))
    if np.ndim(eta) != 2:
        raise ValueError(f"eta must have shape ({n}, {n}), got {np.shape(eta)}")
    check_choice("method", method, ("max",))
    L, dx = float(grid.length), float(grid.dx)
    check_scalar("near", near, lo=0.0, lo_open=True)
    check_scalar("far", far, lo=near, hi=L / 2, lo_open=True)
    check_scalar("exclude", exclude, lo=0.0)
    eta = np.asarray(eta, np.float64)
    # sample the field on a track-aligned lattice (bilinear, periodic)
    c, s = math.cos(direction), math.sin(direction)
    ds = np.arange(near, far + dx / 2, dx)
    ys = np.arange(-L / 2 + dx, L / 2, dx / 2) * 0.98
    D, Y = np.meshgrid(ds, ys, indexing="ij")
    u = (source[0] - c * D - s * Y) / dx + n / 2
    v = (source[1] - s * D + c * Y) / dx + n / 2
    i0, j0 = np.floor(u).astype(int), np.floor(v).astype(int)
    fu, fv = u - i0, v - j0
    g = lambda j, i: eta[j % n, i % n]
    sec = ((1 - fu) * (1 - fv) * g(j0, i0) + fu * (1 - fv) * g(j0, i0 + 1)
           + (1 - fu) * fv * g(j0 + 1, i0) + fu * fv * g(j0 + 1, i0 + 1))
    env = _envelope(sec)
    angles, errors, used = [], [], 0
    for side in (1, -1):
        yy = side * ys
        pos = yy > exclude
        order = np.argsort(yy[pos])
        y_side, e_side = yy[pos][order], env[:, pos][:, order]
        lat = np.full(ds.size, np.nan)
        for r, row in enumerate(e_side):
            i = int(np.argmax(row))
            if 0 < i < row.size - 1:
                a_, b_, c_ = row[i - 1:i + 2]
                den = a_ - 2 * b_ + c_
                off = 0.5 * (a_ - c_) / den if den < 0 else 0.0
                lat[r] = y_side[i] + off * (y_side[1] - y_side[0])
        ok = np.isfinite(lat)
        A = np.stack([np.ones(ok.sum()), ds[ok], np.cbrt(ds[ok])], axis=1)
        coef, *_ = np.linalg.lstsq(A, lat[ok], rcond=None)
        sigma2 = float(np.sum((A @ coef - lat[ok]) ** 2)) / max(int(ok.sum()) - 3, 1)
        sb = math.sqrt(sigma2 * np.linalg.inv(A.T @ A)[1, 1])
        b = coef[1]
        angles.append(math.degrees(math.atan(b)))
        errors.append(math.degrees(sb / (1 + b * b)))
        used += int(ok.sum())
    angle = float(np.mean(angles))
    unc = float(max(np.sqrt(np.mean(np.square(errors))), abs(angles[0] - angles[1]) / 2))
    return WakeAngle(angle, unc, method, used)


def track_wavelength(eta, grid: Grid, *, source=(0.0, 0.0), near: float, far: float) -> float:
    """Wavelength of the waves along the track behind a source moving in +x, m.

    Zero crossings of η on the line y = source y, between ``near`` and ``far`` metres
    behind the source, are located by linear interpolation; a line through crossing
    position against crossing number has slope λ/2. For a deep-water gravity wake this
    is the transverse wavelength 2πU²/g.
    """
    n = grid.n
    check_array("eta", eta, shape_tail=(n, n))
    check_scalar("near", near, lo=0.0, lo_open=True)
    check_scalar("far", far, lo=near, hi=float(grid.length) / 2, lo_open=True)
    dx = float(grid.dx)
    row = int(round(source[1] / dx)) + n // 2
    col = int(round(source[0] / dx)) + n // 2
    line = np.asarray(eta, np.float64)[row % n, np.arange(col, col - n // 2, -1) % n]
    d = np.arange(line.size) * dx
    sel = (d >= near) & (d <= far)
    y, dd = line[sel], d[sel]
    i = np.nonzero(np.sign(y[:-1]) * np.sign(y[1:]) < 0)[0]
    if i.size < 4:
        raise ValueError("fewer than 4 zero crossings between near and far: no wave train to measure")
    crossings = dd[i] - y[i] * (dd[i + 1] - dd[i]) / (y[i + 1] - y[i])
    return 2.0 * float(np.polyfit(np.arange(crossings.size), crossings, 1)[0])
