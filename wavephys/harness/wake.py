"""Wake angles and track wavelengths measured from any height field (any simulator).

The field is read in the source's frame: sections perpendicular to the track at
distances d ∈ [near, far] behind the source (moving toward ``direction``, radians,
0 = +x). In each section, on each side of the track, the lateral position y(d) of the
largest envelope is located (parabolic refinement) and a line is fitted; the angle is
atan of its slope, with the fit's standard error (or half the disagreement of the two
sides, if larger) as its uncertainty. Two estimators (:data:`WAKE_ANGLE_METHODS`):

* :func:`wake_angle_max` — the angle of maximum amplitude (envelope of η itself). For a
  near-point source it is the cusp line (Kelvin's 19.47° in deep water); for sources that
  are not small against 2πU²/g it is a different quantity that moves inward (Rabaud &
  Moisy 2013).
* :func:`wake_angle_cusp` — the outer edge (cusp line) for sources of any size, from the
  waves near the cusp wavenumber k_c of :func:`wavephys.physics.wake.cusp_line`.

The physics of steady wakes (Kelvin, the cusp line) is in :mod:`wavephys.physics.wake`;
``docs/physics.md`` §1.3 has the formulas.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import jax.numpy as jnp
import numpy as np

from wavephys.core.grid import Grid
from wavephys.core.inputs import check_array, check_instance, check_scalar
from wavephys.core.methods import Methods
from wavephys.core.water import Water
from wavephys.physics.dispersion import group_speed, phase_speed
from wavephys.physics.wake import CuspLine, cusp_line

__all__ = ["WakeAngle", "wake_angle", "wake_angle_max", "wake_angle_cusp", "WAKE_ANGLE_METHODS", "track_wavelength"]


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
    ring = np.minimum(np.rint(k / float(grid.dk)).astype(np.int64), n)
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
    """``field`` sampled (periodic bilinear) on the track-aligned lattice: d behind, y across."""
    c, s = math.cos(direction), math.sin(direction)
    D, Y = np.meshgrid(ds, ys, indexing="ij")
    return grid.sample(field, source[0] - c * D - s * Y, source[1] - s * D + c * Y)


def _check_reach(near, far, length):
    """0 < near < far ≤ L/2 (m behind the source), with both names in the message."""
    check_scalar("near", near, lo=0.0, hi=length / 2, lo_open=True, hi_open=True)
    check_scalar("far", far, lo=0.0, hi=length / 2, lo_open=True)
    if not near < far:
        raise ValueError(f"near must be less than far (0 < near < far <= L/2 = {length / 2:g} m), "
                         f"got near={near!r}, far={far!r}")


def _lattice(eta, grid: Grid, source, near: float, far: float, exclude: float):
    """Checked inputs and the (distance, lateral) sample lattice of the section fits."""
    check_instance("grid", grid, Grid, "wavephys.Grid")
    n = grid.n
    check_array("eta", eta, ndim=2, shape_tail=(n, n))
    check_array("source", source, ndim=1, shape_tail=(2,))
    L, dx = float(grid.length), float(grid.dx)
    _check_reach(near, far, L)
    check_scalar("exclude", exclude, lo=0.0, hi=L / 2, hi_open=True)
    ds = np.arange(near, far + dx / 2, dx)
    ys = np.arange(-L / 2 + dx, L / 2, dx / 2) * 0.98
    return np.asarray(eta, np.float64), ds, ys


def _ridge_angle(env: dict, ds, ys, exclude: float, model) -> tuple[float, float, int]:
    """Fit y(d) of the envelope's maximum on each side; (mean angle, uncertainty, sections used)."""
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
        angles.append(math.degrees(math.atan(coef[1])))
        errors.append(math.degrees(sb / (1 + coef[1] ** 2)))
        used += int(ok.sum())
    unc = float(max(np.sqrt(np.mean(np.square(errors))), abs(angles[0] - angles[1]) / 2))
    return float(np.mean(angles)), unc, used


def wake_angle_max(eta, grid: Grid, *, source=(0.0, 0.0), direction: float = 0.0, near: float, far: float,
                   exclude: float = 0.0) -> WakeAngle:
    """Angle of maximum amplitude of a wake (degrees ± uncertainty), from heights η (m).

    Envelope of η across the track (analytic signal); y = a + b·d + c·d^{1/3} is fitted to
    its maximum on each side (d^{1/3}: the Airy width of the cusp region; a: the offset of
    a finite source). ``near``, ``far``: distances behind ``source`` (m, 0 < near < far ≤
    L/2); ``exclude``: half-width (m) of a strip along the track that is ignored (the
    transverse waves).
    """
    eta, ds, ys = _lattice(eta, grid, source, near, far, exclude)
    check_scalar("direction", direction, lo=-2 * math.pi, hi=2 * math.pi)
    env = dict.fromkeys((1, -1), _envelope(_sections(eta, grid, source, direction, ds, ys)))
    angle, unc, used = _ridge_angle(env, ds, ys, exclude, lambda d: np.stack([np.ones_like(d), d, np.cbrt(d)], 1))
    return WakeAngle(angle, unc, "max", used)


def wake_angle_cusp(eta, grid: Grid, *, source=(0.0, 0.0), direction: float = 0.0, near: float, far: float,
                    exclude: float = 0.0, speed: float, water: Water = Water(sigma=0.0),
                    bandwidth: float = 0.1) -> WakeAngle:
    """The outer edge (cusp line) of a wake, for sources of any size (degrees ± uncertainty).

    The field is band-passed around the cusp wavenumber k_c of the source ``speed`` (m/s)
    in ``water`` (:func:`wavephys.physics.wake.cusp_line`; a Gaussian of relative width
    ``bandwidth`` in |k|, whitened so that the source's spectrum does not tilt the band),
    one spectral quadrant per side, so that its modulus is the envelope of that side's
    waves only; y = a + b·d is fitted. φ is largest at k_c, so the band's other waves pull
    the ridge inward: the uncertainty adds that spread (0.21° in deep water at
    ``bandwidth=0.1``). The band-passed field is smeared over ≈ 1/(bandwidth·k_c) across
    the ray: use d ≫ that (near ≥ 3/(bandwidth·k_c·tan φ) is a safe start). A simulator
    with the wrong dispersion puts these waves elsewhere, and the measured angle shows it.
    """
    eta, ds, ys = _lattice(eta, grid, source, near, far, exclude)
    check_scalar("direction", direction, lo=-2 * math.pi, hi=2 * math.pi)
    check_scalar("speed", speed, lo=0.0, lo_open=True)
    check_instance("water", water, Water, "wavephys.Water")
    check_scalar("bandwidth", bandwidth, lo=0.0, hi=0.5, lo_open=True)
    cusp = cusp_line(speed, water)
    if cusp.wavenumber >= math.pi / float(grid.dx):
        raise ValueError(f"the cusp wavenumber {cusp.wavenumber:.4g} rad/m is not resolved by the grid "
                         f"(Nyquist {math.pi / float(grid.dx):.4g} rad/m): lower speed or finer grid")
    if 2 * math.pi / cusp.wavenumber > far - near:
        raise ValueError(f"speed {speed!r} m/s: the cusp waves ({2 * math.pi / cusp.wavenumber:.4g} m long) do not "
                         f"fit between near and far ({far - near:.4g} m): lower the speed or use a larger domain")
    env = {side: np.abs(_sections(_cusp_band(eta, grid, cusp.wavenumber, bandwidth, direction, side), grid,
                                  source, direction, ds, ys)) for side in (1, -1)}
    angle, unc, used = _ridge_angle(env, ds, ys, exclude, lambda d: np.stack([np.ones_like(d), d], 1))
    return WakeAngle(angle, float(math.hypot(unc, _band_spread(speed, water, cusp, bandwidth))), "cusp", used)


WAKE_ANGLE_METHODS = Methods("wake angle", max=wake_angle_max, cusp=wake_angle_cusp)
"""Wake-angle estimators by name."""


def wake_angle(eta, grid: Grid, *, method: str = "max", **options) -> WakeAngle:
    """Measure the half-angle of a wake in a height field by ``method`` in :data:`WAKE_ANGLE_METHODS`.

    ``options`` go to the method (each takes only its own): ``source``, ``direction``,
    ``near``, ``far``, ``exclude`` for both; ``speed``, ``water``, ``bandwidth`` for
    ``"cusp"``. See :func:`wake_angle_max` and :func:`wake_angle_cusp`.
    """
    return WAKE_ANGLE_METHODS(method, eta, grid, **options)


def track_wavelength(eta, grid: Grid, *, source=(0.0, 0.0), near: float, far: float) -> float:
    """Wavelength of the waves along the track behind a source moving in +x, m.

    Zero crossings of η on the grid row through the source, between ``near`` and ``far``
    metres behind it, are located by linear interpolation; a line through crossing
    position against crossing number has slope λ/2. For a deep-water gravity wake this
    is the transverse wavelength 2πU²/g.
    """
    check_instance("grid", grid, Grid, "wavephys.Grid")
    n = grid.n
    check_array("eta", eta, ndim=2, shape_tail=(n, n))
    check_array("source", source, ndim=1, shape_tail=(2,))
    _check_reach(near, far, float(grid.length))
    dx = float(grid.dx)
    row, col = grid.nearest(source[0], source[1])
    line = np.asarray(eta, np.float64)[row, np.arange(col, col - n // 2, -1) % n]
    d = np.arange(line.size) * dx
    sel = (d >= near) & (d <= far)
    y, dd = line[sel], d[sel]
    i = np.nonzero(np.sign(y[:-1]) * np.sign(y[1:]) < 0)[0]
    if i.size < 4:
        raise ValueError("fewer than 4 zero crossings between near and far: no wave train to measure")
    crossings = dd[i] - y[i] * (dd[i + 1] - dd[i]) / (y[i + 1] - y[i])
    return 2.0 * float(np.polyfit(np.arange(crossings.size), crossings, 1)[0])
