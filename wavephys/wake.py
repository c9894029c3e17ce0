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
angle of maximum amplitude from any height field, and the cusp line (outer edge)
by isolating the waves that form it (``method="cusp"``).

The cusp line for any dispersion relation (:func:`cusp_line`): a wave stationary in the
ship frame has c(k) = U cos θ (θ: angle of its wavevector to the track); its energy moves
in the ship frame at (c_g cos θ − U, c_g sin θ), i.e. along the ray at angle φ behind the
source with

.. math::

    \tan\varphi(\theta) = \frac{c_g \sin\theta}{U - c_g\cos\theta}.

The wake ends where φ(θ) is largest: the cusp line. In deep water (c_g = c/2) that is
tan φ = t/(1 + 2t²), t = tan θ, largest at t = 1/√2: φ = arcsin(1/3), θ = 35.26°, and the
cusp waves have wavenumber k_c = g/(U² cos² θ) = 1.5 g/U². Because φ is stationary
there, waves whose wavenumber lies near k_c all travel along the cusp line, whatever the
shape of the source; that is what ``method="cusp"`` measures.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import jax.numpy as jnp
import numpy as np

from wavephys._inputs import check_array, check_choice, check_int, check_scalar
from wavephys.dispersion import angular_frequency, group_speed, min_phase_speed, phase_speed, surface_operator
from wavephys.heights import height_multiplier
from wavephys.params import Grid, Water

__all__ = ["GaussianPressure", "HullSource", "steady_wake", "WakeAngle", "wake_angle", "track_wavelength", "KELVIN_ANGLE",
           "transverse_wavelength", "CuspLine", "cusp_line"]

KELVIN_ANGLE = math.degrees(math.asin(1.0 / 3.0))
"""Kelvin's wake half-angle for deep-water gravity waves, degrees (19.47°)."""


def transverse_wavelength(speed, water: Water = Water(sigma=0.0)):
    """Deep-water gravity wavelength of the transverse waves on the track, 2πU²/g, m."""
    check_scalar("speed", speed, lo=0.0, lo_open=True)
    return 2 * math.pi * speed**2 / float(water.g)


@dataclass(frozen=True)
class CuspLine:
    """The outer edge of a steady wake: ray ``angle`` (degrees) behind the source, carried by
    waves of wavenumber ``wavenumber`` (rad/m) whose crests make ``wave_angle`` (degrees,
    between wavevector and track)."""

    angle: float
    wavenumber: float
    wave_angle: float


def _stationary_wavenumber(target_speed, water: Water):
    """Gravity-branch k with phase speed c(k) = target (array; NaN where none), by bisection in log k."""
    target = np.asarray(target_speed, np.float64)
    g = float(water.g)
    if float(water.sigma) > 0:
        c_min, k_hi = min_phase_speed(water)
        k_hi = k_hi if k_hi > 0 else None
    else:
        c_min, k_hi = 0.0, None
    if k_hi is None:  # no capillary minimum: the speed falls without bound (or to c_min at k = 0)
        k_hi = 1e6 * g / np.maximum(target, 1e-12) ** 2
    lo = np.full(target.shape, math.log(1e-9 * g / max(float(np.max(target)), 1e-12) ** 2))
    hi = np.log(np.broadcast_to(k_hi, target.shape).astype(np.float64))
    speed = lambda u: np.asarray(phase_speed(jnp.asarray(np.exp(u)), water), np.float64)
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        faster = speed(mid) > target  # on the gravity branch c falls with k
        lo, hi = np.where(faster, mid, lo), np.where(faster, hi, mid)
    k = np.exp(0.5 * (lo + hi))
    c_long = phase_speed(jnp.asarray(0.0), water)
    none = (target <= c_min) | (target >= float(c_long))
    return np.where(none, np.nan, k)


def cusp_line(speed, water: Water = Water(sigma=0.0), samples: int = 4001) -> CuspLine:
    """The cusp line (outer edge) of the steady wake of a source moving at ``speed``.

    Maximizes the ray angle φ(θ) (module docstring) over the wave directions θ that
    have a stationary gravity-branch wave, for any depth and surface tension (gravity
    branch only: the capillary branch of a capillary-gravity wake, ahead of the source,
    is not covered). Deep water, gravity only: 19.47° at k_c = 1.5 g/U², θ = 35.26°.
    Finite depth widens the wedge as U approaches sqrt(g h) (Havelock).

    Parameters
    ----------
    speed : float
        U, m/s, > 0 (and > c_min with surface tension).
    water : Water
    samples : int
        Directions θ tried in (0, π/2); the maximum is then refined parabolically.
    """
    check_scalar("speed", speed, lo=0.0, lo_open=True)
    samples = check_int("samples", samples, lo=3)
    theta = np.linspace(0.0, math.pi / 2, samples + 2)[1:-1]
    k = _stationary_wavenumber(speed * np.cos(theta), water)
    if not np.isfinite(k).any():
        raise ValueError(f"speed {speed} m/s: no stationary gravity wave (below c_min = "
                         f"{min_phase_speed(water)[0]:.4g} m/s?), so there is no wake")
    cg = np.asarray(group_speed(jnp.asarray(np.where(np.isfinite(k), k, 1.0)), water), np.float64)
    phi = np.where(np.isfinite(k), np.arctan2(cg * np.sin(theta), speed - cg * np.cos(theta)), -np.inf)
    i = int(np.argmax(phi))
    t, kk = theta[i], k[i]
    if 0 < i < samples - 1 and np.all(np.isfinite(phi[i - 1:i + 2])):
        a, b, c = phi[i - 1:i + 2]
        den = a - 2 * b + c
        if den < 0:
            off = 0.5 * (a - c) / den
            t = theta[i] + off * (theta[1] - theta[0])
            kk = float(_stationary_wavenumber(np.array([speed * math.cos(t)]), water)[0])
            cgt = float(group_speed(jnp.asarray(kk), water))
            return CuspLine(math.degrees(math.atan2(cgt * math.sin(t), speed - cgt * math.cos(t))), kk,
                            math.degrees(t))
    return CuspLine(math.degrees(float(phi[i])), float(kk), math.degrees(float(t)))


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


def _cusp_band(eta, grid: Grid, wavenumber: float, bandwidth: float, direction: float, side: int):
    """Complex field of the waves near |k| = ``wavenumber`` travelling to one ``side`` (±1) of
    a track heading ``direction``: one quadrant of the spectrum (forward along the track,
    ``side`` across it), so the modulus is the envelope and the mirror wave on the other
    side is left out. Whitened so that every |k| in the band weighs the same."""
    n = grid.n
    spec = np.fft.fft2(eta)
    ky, kx = np.broadcast_arrays(*(np.asarray(a, np.float64) for a in grid.wavenumbers()))
    along = kx * math.cos(direction) + ky * math.sin(direction)
    across = -kx * math.sin(direction) + ky * math.cos(direction)
    quadrant = (along > 0) & (side * across > 0)
    k = np.hypot(kx, ky)
    window = np.exp(-0.5 * ((k - wavenumber) / (bandwidth * wavenumber)) ** 2) * quadrant
    # whitening: divide by the RMS amplitude on the ring |k| (±dk/2) of the quadrant, so that
    # a source whose spectrum falls steeply (a large hull) does not shift the band's centre
    dk = 2 * math.pi / float(grid.length)
    ring = np.minimum(np.rint(k / dk).astype(np.int64), n)
    power = np.bincount(ring.ravel(), weights=(np.abs(spec) ** 2 * quadrant).ravel(), minlength=n + 1)
    count = np.bincount(ring.ravel(), weights=quadrant.ravel().astype(np.float64), minlength=n + 1)
    rms = np.sqrt(power / np.maximum(count, 1))
    floor = 1e-30 + 1e-12 * rms.max()
    return np.fft.ifft2(spec * window / np.maximum(rms[ring], floor))


def _band_spread(speed, water: Water, cusp: CuspLine, bandwidth: float) -> float:
    """How far inside the cusp line (degrees) the waves at k_c(1 ± bandwidth) travel: the
    band's systematic inward bias (φ is largest at k_c), added to the uncertainty."""
    phis = []
    for k in (cusp.wavenumber * (1 - bandwidth), cusp.wavenumber * (1 + bandwidth)):
        cos_t = float(phase_speed(jnp.asarray(k), water)) / speed
        if not 0.0 < cos_t < 1.0:
            return abs(cusp.angle)  # the band reaches past the stationary waves
        cg, sin_t = float(group_speed(jnp.asarray(k), water)), math.sqrt(1 - cos_t * cos_t)
        phis.append(math.degrees(math.atan2(cg * sin_t, speed - cg * cos_t)))
    return cusp.angle - 0.5 * sum(phis)


def _sections(field, grid: Grid, source, direction, ds, ys):
    """Bilinear (periodic) samples of ``field`` on the track-aligned lattice (d behind, y across)."""
    n, dx = grid.n, float(grid.dx)
    c, s = math.cos(direction), math.sin(direction)
    D, Y = np.meshgrid(ds, ys, indexing="ij")
    u = (source[0] - c * D - s * Y) / dx + n / 2
    v = (source[1] - s * D + c * Y) / dx + n / 2
    i0, j0 = np.floor(u).astype(int), np.floor(v).astype(int)
    fu, fv = u - i0, v - j0
    g = lambda j, i: field[j % n, i % n]
    return ((1 - fu) * (1 - fv) * g(j0, i0) + fu * (1 - fv) * g(j0, i0 + 1)
            + (1 - fu) * fv * g(j0 + 1, i0) + fu * fv * g(j0 + 1, i0 + 1))


def wake_angle(eta, grid: Grid, *, source=(0.0, 0.0), direction: float = 0.0, method: str = "max",
               near: float, far: float, exclude: float = 0.0, speed: float | None = None,
               water: Water = Water(sigma=0.0), bandwidth: float = 0.1) -> WakeAngle:
    """Measure the half-angle of a wake in a height field (any source, any simulator).

    The field is read in the source's frame: sections perpendicular to the track at
    distances d ∈ [``near``, ``far``] behind ``source`` (moving toward ``direction``,
    radians, 0 = +x). In each section, on each side of the track, the lateral position
    y(d) of the largest envelope is found (parabolic refinement), and the angle is
    atan(b) of a least-squares fit, with the fit's standard error (or half the
    disagreement of the two sides, if larger) as its uncertainty.

    ``method="max"`` — the angle of maximum amplitude. Envelope of η across the track
    (analytic signal); fit y = a + b·d + c·d^{1/3} (d^{1/3}: the Airy width of the cusp
    region; a: the offset of a finite source). For a near-point source the maximum is on
    the cusp line (Kelvin's 19.47° in deep water); for sources that are not small
    against 2πU²/g it is a different quantity and moves inward (Rabaud & Moisy 2013).

    ``method="cusp"`` — the outer edge (cusp line), for sources of any size. Needs
    ``speed`` (and ``water``): the field is band-passed around the cusp wavenumber k_c of
    :func:`cusp_line` (Gaussian of relative width ``bandwidth`` in |k|, whitened so that
    the source's spectrum does not tilt the band), one quadrant per side (forward along
    the track, toward that side) so that its modulus is the envelope of that side's
    waves only. Those waves travel along the cusp ray from the source, so y = a + b·d
    is fitted. φ is largest at k_c, so the band's other waves pull the ridge inward: the
    uncertainty adds that spread (0.21° for deep water at ``bandwidth=0.1``), and the
    measured angles sit 0.1–0.3° inside Kelvin's (see the README's table). The band-passed field is smeared over ≈ 1/(bandwidth·k_c)
    across the ray: use d ≫ that (near ≥ 3/(bandwidth·k_c·tan φ) is a safe start). A
    simulator with the wrong dispersion puts these waves elsewhere, and the measured
    angle shows it.

    Parameters
    ----------
    eta : array_like (n, n)
        Heights on ``grid``, m.
    near, far : float
        Range of distances behind the source, m, 0 < near < far ≤ L/2.
    exclude : float
        Half-width of a strip along the track that is ignored, m (the transverse waves).
    speed : float
        Source speed U, m/s (``method="cusp"`` only).
    water : Water
        Dispersion used to find k_c (``method="cusp"`` only; deep gravity by default).
    bandwidth : float
        Relative width of the band around k_c, in (0, 0.5].
    """
    n = grid.n
    check_array("eta", eta, shape_tail=(n, n))
    if np.ndim(eta) != 2:
        raise ValueError(f"eta must have shape ({n}, {n}), got {np.shape(eta)}")
    check_choice("method", method, ("max", "cusp"))
    L, dx = float(grid.length), float(grid.dx)
    check_scalar("near", near, lo=0.0, lo_open=True)
    check_scalar("far", far, lo=near, hi=L / 2, lo_open=True)
    check_scalar("exclude", exclude, lo=0.0)
    check_scalar("bandwidth", bandwidth, lo=0.0, hi=0.5, lo_open=True)
    eta = np.asarray(eta, np.float64)
    ds = np.arange(near, far + dx / 2, dx)
    ys = np.arange(-L / 2 + dx, L / 2, dx / 2) * 0.98
    if method == "cusp":
        if speed is None:
            raise ValueError("method='cusp' needs the source speed: pass speed (m/s)")
        check_scalar("speed", speed, lo=0.0, lo_open=True)
        cusp = cusp_line(speed, water)
        k_c = cusp.wavenumber
        spread = _band_spread(speed, water, cusp, bandwidth)
        if k_c >= math.pi / dx:
            raise ValueError(f"the cusp wavenumber {k_c:.4g} rad/m is not resolved by the grid "
                             f"(Nyquist {math.pi / dx:.4g} rad/m): lower speed or finer grid")
        env = {side: np.abs(_sections(_cusp_band(eta, grid, k_c, bandwidth, direction, side), grid, source,
                                      direction, ds, ys)) for side in (1, -1)}
        model = lambda d: np.stack([np.ones_like(d), d], axis=1)
    else:
        spread = 0.0
        env = dict.fromkeys((1, -1), _envelope(_sections(eta, grid, source, direction, ds, ys)))
        model = lambda d: np.stack([np.ones_like(d), d, np.cbrt(d)], axis=1)
    angles, errors, used = [], [], 0
    for side in (1, -1):
        yy = side * ys
        pos = yy > exclude
        order = np.argsort(yy[pos])
        y_side, e_side = yy[pos][order], env[side][:, pos][:, order]
        lat = np.full(ds.size, np.nan)
        for r, row in enumerate(e_side):
            i = int(np.argmax(row))
            if 0 < i < row.size - 1:
                a_, b_, c_ = row[i - 1:i + 2]
                den = a_ - 2 * b_ + c_
                off = 0.5 * (a_ - c_) / den if den < 0 else 0.0
                lat[r] = y_side[i] + off * (y_side[1] - y_side[0])
        ok = np.isfinite(lat)
        A = model(ds[ok])
        if ok.sum() <= A.shape[1]:
            raise ValueError("too few sections with a clear maximum: widen near..far")
        coef, *_ = np.linalg.lstsq(A, lat[ok], rcond=None)
        sigma2 = float(np.sum((A @ coef - lat[ok]) ** 2)) / max(int(ok.sum()) - A.shape[1], 1)
        sb = math.sqrt(sigma2 * np.linalg.inv(A.T @ A)[1, 1])
        b = coef[1]
        angles.append(math.degrees(math.atan(b)))
        errors.append(math.degrees(sb / (1 + b * b)))
        used += int(ok.sum())
    angle = float(np.mean(angles))
    unc = float(max(np.sqrt(np.mean(np.square(errors))), abs(angles[0] - angles[1]) / 2))
    return WakeAngle(angle, float(math.hypot(unc, spread)), method, used)


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
