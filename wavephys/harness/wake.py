"""Wake angles and track wavelengths measured from any height field (any simulator).

The field is read in the source's frame: sections perpendicular to the track at
distances d ∈ [near, far] behind the source (moving toward ``direction``, radians,
0 = +x). In each section, on each side of the track, the lateral position y(d) of the
largest envelope is located (parabolic refinement) and a line is fitted; the angle is
atan of its slope, with the fit's standard error (or half the disagreement of the two
sides, if larger) as its uncertainty. Two estimators (:data:`WAKE_ANGLE_METHODS`):

* :func:`wake_angle_max` — the angle of maximum amplitude (envelope of all the waves). It
  approaches the cusp line (Kelvin's 19.47° in deep water) only far behind a small source;
  for a Gaussian pressure source it follows the Froude number Fr = U/sqrt(g·b): on the
  track (transverse waves) below Fr ≈ 0.35, near Kelvin's angle up to Fr ≈ 0.9, then
  falling roughly as 1/Fr (Darmon, Benzaquen & Raphaël 2014; Rabaud & Moisy 2013).
  :func:`max_amplitude_angle_theory` gives linear theory's value for the same sections.
* :func:`wake_angle_cusp` — the outer edge (cusp line) for sources of any size, from the
  waves near the cusp wavenumber k_c of :func:`wavephys.physics.wake.cusp_line`.

The physics of steady wakes (Kelvin, the cusp line) is in :mod:`wavephys.physics.wake`;
``docs/physics.md`` §1.3 has the formulas.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.grid import Grid
from wavephys.core.inputs import check_array, check_instance, check_int, check_scalar
from wavephys.core.methods import Methods
from wavephys.core.water import Water
from wavephys.physics.dispersion import group_speed, phase_speed
from wavephys.physics.wake import CuspLine, GaussianPressure, cusp_line, wake_envelope

__all__ = ["WakeAngle", "wake_angle", "wake_angle_max", "wake_angle_cusp", "wake_angle_darmon", "WAKE_ANGLE_METHODS",
           "track_wavelength", "max_amplitude_angle_theory", "darmon_angle_theory", "darmon_crests", "cusp_angle_theory",
           "WAKE_ANGLE_THEORIES", "wake_angle_theory"]


@dataclass(frozen=True)
class WakeAngle:
    """A measured wake half-angle: ``angle`` ± ``uncertainty`` (degrees), by ``method``.

    Attributes
    ----------
    angle : float
        Wake half-angle, degrees (mean of the two sides of the track; 0 on the track).
    uncertainty : float
        Its uncertainty, degrees, >= 0 (the fit's standard error or half the disagreement of the two sides,
        whichever is larger).
    method : str
        The estimator: ``"max"``, ``"cusp"``, ``"darmon"``, or a theory's ``"max (linear theory)"``,
        ``"cusp (linear theory)"``, ``"darmon (linear theory)"``.
    points : int
        Number of sections used by the fits, both sides together (``"darmon"``: arcs, both sides together).
    radii : tuple of float
        ``"darmon"`` only: the arcs' distances behind the source, m (empty for the other methods).
    angles : tuple of float
        ``"darmon"`` only: the angle on each arc, degrees (``angle`` is their mean).
    """

    angle: float
    uncertainty: float
    method: str
    points: int
    radii: tuple = ()
    angles: tuple = ()

    def __str__(self):
        if self.radii:
            each = ", ".join(f"{a:.2f}° at {r:.4g} m" for r, a in zip(self.radii, self.angles))
            return f"{self.angle:.2f}° ± {self.uncertainty:.2f}° ({self.method}: {each})"
        return f"{self.angle:.2f}° ± {self.uncertainty:.2f}° ({self.method}, {self.points} sections)"




@jax.jit
def _spline_at(coefficients, u, v):
    """The periodic cubic B-spline of one channel at texel coordinates (u, v), compiled once per shape."""
    from wavephys.core.sampling import bspline

    return bspline(coefficients, u, v)[:, 0]

def _wave_envelope(eta, grid: Grid, direction: float):
    """Envelope of every wave in a steady wake: the modulus of the analytic signal along the
    direction of travel (only the wavevectors k·u > 0 kept, doubled). All stationary waves of
    a source moving along u have k·u > 0, so this is their local amplitude, for transverse
    waves (crests across the track) as for diverging ones, with no oscillation left in it."""
    spec = np.fft.fft2(eta)
    ky, kx = np.broadcast_arrays(*(np.asarray(a, np.float64) for a in grid.wavenumbers()))
    along = kx * math.cos(direction) + ky * math.sin(direction)
    tiny = 1e-9 * float(grid.dk)
    return np.abs(np.fft.ifft2(spec * np.where(along > tiny, 2.0, np.where(along < -tiny, 0.0, 1.0))))


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


def _ridge_positions(e_side, y_side, exclude: float, tolerance):
    """Per section: lateral position of the envelope's largest value (parabolic refinement)
    and its spread, half the extent of the values within ``tolerance`` (relative) of it —
    large where the maximum is flat or two ridges are nearly equal. Sections whose maximum
    lies at the outer edge, or at the edge of an excluded strip, have no ridge (NaN); those
    with the maximum on the track (``exclude = 0``) are flagged."""
    step = float(y_side[1] - y_side[0])
    lat, spread = np.full(len(e_side), np.nan), np.full(len(e_side), np.nan)
    on_track = np.zeros(len(e_side), bool)
    for r, row in enumerate(e_side):
        i = int(np.argmax(row))
        top = float(row[i])
        if not (np.isfinite(top) and top > 0) or i == row.size - 1 or (i == 0 and exclude > 0):
            continue
        off = 0.0
        on_track[r] = i == 0
        if i > 0:
            a_, b_, c_ = row[i - 1:i + 2]
            den = a_ - 2 * b_ + c_
            off = 0.5 * (a_ - c_) / den if den < 0 else 0.0
        lat[r] = y_side[i] + off * step
        if tolerance is None:
            spread[r] = step / 2
        else:
            close = y_side[row >= (1.0 - tolerance) * top]
            spread[r] = max(0.5 * float(close.max() - close.min()), step / 2)
    return lat, spread, on_track


def _fit_side(ds, lat, spread, model):
    """Weighted least squares of y(d) = model(d)·c (weights 1/spread²): slope and its standard
    error. Sections more than three spreads (or three robust deviations) off the ridge the
    others agree on are dropped and the fit repeated; the covariance is scaled up by the
    reduced χ² when the ridge scatters more than its
    spreads say, and by sections/runs when its residuals come in runs of one sign (a ridge
    hopping between two maxima: neighbouring sections are then not independent)."""
    ok = np.isfinite(lat)
    A = model(ds[ok])
    if ok.sum() <= max(A.shape[1], 0.2 * lat.size):
        raise ValueError(f"too few sections with a clear maximum ({int(ok.sum())} of {lat.size}): the largest "
                         "amplitude lies at "
                         "the edge of the sections or of the excluded strip (e.g. transverse waves on the track); "
                         "widen near..far or change exclude")
    y, spread, params = lat[ok], spread[ok], A.shape[1]
    keep = np.ones(y.size, bool)
    for _ in range(4):  # drop sections far off the ridge the others agree on (robust refits)
        w = keep / spread**2
        normal = A.T @ (A * w[:, None])
        coef = np.linalg.solve(normal, A.T @ (w * y))
        resid = A @ coef - y
        scale = 1.4826 * float(np.median(np.abs(resid[keep])))
        new = np.abs(resid) <= 3.0 * np.maximum(spread, scale)
        if np.array_equal(new, keep) or new.sum() <= params:
            break
        keep = new
    resid, w, count = resid[keep], w[keep], int(keep.sum())
    chi2 = float(np.sum(w * resid**2)) / max(count - params, 1)
    # neighbouring sections are not independent (a ridge that hops between two maxima leaves
    # long runs of residuals of one sign): count independent sections as the runs of signs
    runs = 1 + int(np.count_nonzero(np.diff(np.sign(resid)) != 0))
    cov = np.linalg.inv(normal) * max(chi2, 1.0) * max(count / max(runs, params + 1), 1.0)
    return float(coef[1]), math.sqrt(float(cov[1, 1])), count


def _side_angle(ds, lat, spread, on_track, model):
    """(angle, uncertainty, sections) on one side, degrees. Where most sections have their
    maximum on the track, that is the answer (the transverse waves of a slow, broad source:
    angle 0); otherwise those sections see the near field and the ridge off the track is
    fitted. When both kinds hold at least a tenth of the sections, the maximum jumps between
    them (near Fr ≈ 0.35 for a Gaussian source), and the uncertainty covers both answers."""
    found = np.isfinite(lat)
    share = on_track.sum() / max(int(found.sum()), 1)
    off = np.where(on_track, np.nan, lat)
    results = {}
    for name, values in (("track", lat), ("ridge", off)):
        try:
            slope, sb, count = _fit_side(ds, values, spread, model)
        except ValueError:
            continue
        results[name] = (math.degrees(math.atan(slope)), math.degrees(sb / (1 + slope**2)), count)
    main = "track" if share > 0.5 else "ridge"
    if main not in results:
        _fit_side(ds, off if main == "ridge" else lat, spread, model)  # raises the reason
    angle, error, count = results[main]
    if 0.1 <= share <= 0.9 and len(results) == 2:
        other = 0.0 if main == "ridge" else results["ridge"][0]
        error = max(error, abs(angle - other))
    return angle, error, count


def _ridge_angle(env: dict, ds, ys, exclude: float, model, tolerance=None) -> tuple[float, float, int]:
    """Fit y(d) of the envelope's maximum on each side; (mean angle, uncertainty, sections used).

    The uncertainty is the larger of the fits' standard errors and half the disagreement of
    the two sides."""
    angles, errors, used = [], [], 0
    for side in (1, -1):
        yy = side * ys
        pos = yy > exclude
        order = np.argsort(yy[pos])
        y_side, e_side = yy[pos][order], env[side][:, pos][:, order]
        lat, spread, on_track = _ridge_positions(e_side, y_side, exclude, tolerance)
        angle, error, count = _side_angle(ds, lat, spread, on_track, model)
        angles.append(angle)
        errors.append(error)
        used += count
    unc = float(max(np.sqrt(np.mean(np.square(errors))), abs(angles[0] - angles[1]) / 2))
    return float(np.mean(angles)), unc, used


def _airy_model(d):
    """y = b·d + c·d^{1/3}: the ray from the source, and the Airy width of a cusp region."""
    return np.stack([np.cbrt(d), d], 1)


def wake_angle_max(eta, grid: Grid, *, source=(0.0, 0.0), direction: float = 0.0, near: float, far: float,
                   exclude: float = 0.0, tolerance: float = 0.01) -> WakeAngle:
    """Angle of maximum amplitude of a wake (degrees ± uncertainty), from heights η (m).

    The envelope is the modulus of the analytic signal along the direction of travel (every
    stationary wave travels forward, so it is the local amplitude of transverse and diverging
    waves alike). In each section across the track its largest value is located, with a
    spread: half the width of the values within ``tolerance`` (relative, default 1 %) of it,
    so a flat maximum or two nearly equal ridges count for little. y = b·d + c·d^{1/3} (the
    ray from the source, and the Airy width of a cusp region) is fitted on each side,
    weighted by 1/spread², robustly (sections far off the ridge are dropped). The
    uncertainty is the fit's standard error (scaled up when the sections scatter more than
    their spreads, or in runs) or half the disagreement of the two sides, whichever is
    larger; where the maximum jumps between the track and a ridge, it covers both.

    ``near``, ``far``: distances behind ``source`` (m, 0 < near < far ≤ L/2); ``exclude``:
    half-width (m) of a strip along the track that is ignored (with ``exclude = 0`` a
    maximum on the track counts, as the transverse waves of slow, broad sources have it:
    the angle is then 0). Sections whose maximum lies at the edge of the strip or of the
    section have no ridge; too few of them raise ``ValueError``. The linear theory's value
    for a Gaussian source through the same fit: :func:`max_amplitude_angle_theory`.

    Parameters
    ----------
    eta : array_like (n, n)
        Heights η, m, on ``grid``, ordered (y, x), finite.
    grid : Grid
        The periodic grid of ``eta``.
    source : (float, float), optional, keyword-only
        Position (x, y) of the source, m (default the origin).
    direction : float, optional, keyword-only
        Direction of travel of the source, rad, 0 = +x, in [−2π, 2π] (default 0).
    near, far : float, keyword-only
        Distances behind ``source`` of the first and last section, m, 0 < near < far ≤ L/2.
    exclude : float, optional, keyword-only
        Half-width of the strip along the track that is ignored, m, in [0, L/2) (default 0).
    tolerance : float, optional, keyword-only
        Relative tolerance that sets each section's spread, in (0, 0.5] (default 0.01).

    Returns
    -------
    WakeAngle
        The angle of maximum amplitude, degrees ± uncertainty, ``method="max"``.

    Raises
    ------
    ValueError
        When too few sections have a clear maximum, or an argument is out of range.

    References
    ----------
    A. Darmon, M. Benzaquen & E. Raphaël (2014). Kelvin wake pattern at large Froude numbers.
    *J. Fluid Mech.* 738, R3.
    M. Rabaud & F. Moisy (2013). Ship wakes: Kelvin or Mach angle? *Phys. Rev. Lett.* 110.
    """
    eta, ds, ys = _lattice(eta, grid, source, near, far, exclude)
    check_scalar("direction", direction, lo=-2 * math.pi, hi=2 * math.pi)
    check_scalar("tolerance", tolerance, lo=0.0, hi=0.5, lo_open=True)
    env = dict.fromkeys((1, -1), _sections(_wave_envelope(eta, grid, direction), grid, source, direction, ds, ys))
    angle, unc, used = _ridge_angle(env, ds, ys, exclude, _airy_model, tolerance)
    return WakeAngle(angle, unc, "max", used)


def max_amplitude_angle_theory(speed, source: GaussianPressure, *, near: float, far: float, exclude: float = 0.0,
                               spacing: float, water: Water = Water(sigma=0.0), sections: int = 16,
                               tolerance: float = 0.01, damping: float = 0.0) -> WakeAngle:
    """The angle of maximum amplitude that linear theory gives for a Gaussian pressure source,
    through the same sections and fit as :func:`wake_angle_max` (degrees ± the fit's error).

    The envelope is the far-field integral :func:`wavephys.physics.wake.wake_envelope`
    (independent of any grid), sampled on ``sections`` sections from ``near`` to ``far`` m
    behind the source, ``spacing``/2 apart across the track (use the grid spacing of the
    field you compare with; at most 800 points a section). Compare a measured :class:`WakeAngle`
    with this one at the same ``near``, ``far``, ``exclude`` and ``tolerance``: the angle of maximum amplitude of a
    finite source still moves with distance, so only the same sections compare. ``damping``
    (1/s, default 0) is Rayleigh's ε of a damped steady wake (:func:`~wavephys.physics.wake.steady_wake`
    uses 8U/L); it fades slow diverging waves first, so it moves the angle too.

    Parameters
    ----------
    speed : float
        Source speed U, m/s, > 0.
    source : GaussianPressure
        The Gaussian pressure source.
    near, far : float, keyword-only
        Distances behind the source of the first and last section, m, 0 < near < far; far at most 1000
        transverse wavelengths 2πU²/g.
    exclude : float, optional, keyword-only
        Half-width of the strip along the track that is ignored, m, >= 0 and < far·tan(40°)/2 (default 0).
    spacing : float, keyword-only
        Grid spacing of the field compared with, m, 0 < spacing < far; points across the track are
        ``spacing``/2 apart (at most 800 a section).
    water : Water, optional, keyword-only
        The water (default ``Water(sigma=0.0)``: gravity waves only).
    sections : int, optional, keyword-only
        Number of sections from ``near`` to ``far``, in [4, 4096] (default 16).
    tolerance : float, optional, keyword-only
        Relative tolerance that sets each section's spread, in (0, 0.5] (default 0.01).
    damping : float, optional, keyword-only
        Rayleigh's damping ε, 1/s, >= 0 with damping·far/U ≤ 50 (default 0).

    Returns
    -------
    WakeAngle
        Linear theory's angle of maximum amplitude, degrees ± the fit's error, ``method="max (linear theory)"``.

    Raises
    ------
    ValueError
        When an argument is out of range (see above) or too few sections have a clear maximum.

    References
    ----------
    A. Darmon, M. Benzaquen & E. Raphaël (2014). Kelvin wake pattern at large Froude numbers.
    *J. Fluid Mech.* 738, R3.
    M. Rabaud & F. Moisy (2013). Ship wakes: Kelvin or Mach angle? *Phys. Rev. Lett.* 110.
    """
    check_scalar("speed", speed, lo=0.0, lo_open=True)
    check_instance("source", source, GaussianPressure, "wavephys.physics.wake.GaussianPressure")
    check_scalar("spacing", spacing, lo=0.0, lo_open=True)
    check_scalar("near", near, lo=0.0, lo_open=True)
    check_scalar("far", far, lo=0.0, lo_open=True)
    if not near < far:
        raise ValueError(f"near must be less than far, got near={near!r}, far={far!r}")
    check_scalar("exclude", exclude, lo=0.0)
    sections = check_int("sections", sections, lo=4, hi=4096)
    check_scalar("tolerance", tolerance, lo=0.0, hi=0.5, lo_open=True)
    check_instance("water", water, Water, "wavephys.Water")
    longest = 2 * math.pi * float(speed) ** 2 / float(water.g)  # the transverse waves' length (deep water)
    if far > 1000 * longest:
        raise ValueError(f"far must be at most 1000 transverse wavelengths (2 pi U^2/g = {longest:.4g} m) behind "
                         f"the source for the direction integral, got {far!r}")
    if not spacing < far:
        raise ValueError(f"spacing must be less than far ({far!r} m), got {spacing!r}")
    check_scalar("damping", damping, lo=0.0)
    if damping * far / float(speed) > 50.0:
        raise ValueError(f"damping {damping!r} 1/s fades the waves by more than e^-50 at far = {far!r} m "
                         f"(damping·far/U must be at most 50)")
    ds = np.linspace(near, far, sections)
    half = far * math.tan(math.radians(40.0))  # beyond any cusp line of a subcritical wake
    if not exclude < half / 2:
        raise ValueError(f"exclude must be less than far·tan(40°)/2 = {half / 2:.4g} m (the sections reach "
                         f"{half:.4g} m across the track), got {exclude!r}")
    step = max(spacing / 2, half / 400)  # the maxima are refined between lattice points
    ys = np.arange(step / 2, half, step)  # one side: the source is axisymmetric
    env = wake_envelope(ds, ys, speed, source, water, damping)
    angle, unc, used = _ridge_angle(dict.fromkeys((1, -1), np.concatenate([env[:, ::-1], env], 1)), ds,
                                    np.concatenate([-ys[::-1], ys]), exclude, _airy_model, tolerance)
    return WakeAngle(angle, unc, "max (linear theory)", used)


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

    Parameters
    ----------
    eta : array_like (n, n)
        Heights η, m, on ``grid``, ordered (y, x), finite.
    grid : Grid
        The periodic grid of ``eta``.
    source : (float, float), optional, keyword-only
        Position (x, y) of the source, m (default the origin).
    direction : float, optional, keyword-only
        Direction of travel of the source, rad, 0 = +x, in [−2π, 2π] (default 0).
    near, far : float, keyword-only
        Distances behind ``source`` of the first and last section, m, 0 < near < far ≤ L/2.
    exclude : float, optional, keyword-only
        Half-width of the strip along the track that is ignored, m, in [0, L/2) (default 0).
    speed : float, keyword-only
        Source speed U, m/s, > 0; the cusp waves must be resolved by the grid (k_c < π/dx) and fit between
        ``near`` and ``far`` (2π/k_c ≤ far − near).
    water : Water, optional, keyword-only
        The water (default ``Water(sigma=0.0)``: gravity waves only).
    bandwidth : float, optional, keyword-only
        Relative width of the band around k_c in |k|, in (0, 0.5] (default 0.1).

    Returns
    -------
    WakeAngle
        The cusp-line angle, degrees ± uncertainty (the fit's and the band's spread), ``method="cusp"``.

    Raises
    ------
    ValueError
        When the cusp waves are not resolved or do not fit between near and far, too few sections have a
        clear maximum, or an argument is out of range.
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
    angle, unc, used = _ridge_angle(env, ds, ys, exclude, lambda d: np.stack([np.ones_like(d), d], 1), 0.01)
    return WakeAngle(angle, float(math.hypot(unc, _band_spread(speed, water, cusp, bandwidth))), "cusp", used)


def _arc_points(radius: float, span: float, step: float):
    """Polar angles φ (rad, 0 on the track, from −span to span) ``step`` m apart along an arc of ``radius``
    behind the source, and the points' (distance behind, lateral) offsets."""
    count = max(int(math.ceil(radius * span / step)), 8)
    phi = np.linspace(-span, span, 2 * count + 1)
    return phi, radius * np.cos(phi), radius * np.sin(phi)


def _arc_maximum(phi, height, tolerance: float):
    """Per side of the track: the φ (degrees, parabolic refinement) of the largest |ζ|, and the half-width of the
    φ within ``tolerance`` of it; then their mean and the uncertainty (half the side disagreement or the
    widest half-width, whichever is larger)."""
    zeta = np.abs(np.asarray(height, np.float64))
    centre = phi.size // 2
    sides = []
    for sel in (np.arange(centre, phi.size), np.arange(centre, -1, -1)):
        a = zeta[sel]
        i = int(np.argmax(a))
        frac = 0.0
        if 0 < i < a.size - 1:
            den = a[i - 1] - 2 * a[i] + a[i + 1]
            frac = 0.5 * (a[i - 1] - a[i + 1]) / den if den < 0 else 0.0
        angle = abs(math.degrees(phi[sel][i] + frac * (phi[sel][1] - phi[sel][0])))
        near = np.abs(np.degrees(phi[sel][a >= (1 - tolerance) * a[i]]))
        sides.append((angle, 0.5 * float(near.max() - near.min())))
    (a1, w1), (a2, w2) = sides
    return 0.5 * (a1 + a2), max(0.5 * abs(a1 - a2), w1, w2)


def _darmon(sample, radii, span: float, step: float, tolerance: float, method: str) -> WakeAngle:
    angles, uncertainties = [], []
    for r in radii:
        phi, behind, lateral = _arc_points(float(r), math.radians(span), step)
        angle, unc = _arc_maximum(phi, sample(behind, lateral), tolerance)
        angles.append(angle)
        uncertainties.append(unc)
    return WakeAngle(float(np.mean(angles)), float(max(uncertainties)), method, 2 * len(angles),
                     tuple(float(r) for r in radii), tuple(angles))


def _check_radii(radii, limit: float):
    check_array("radii", radii, ndim=1, lo=0.0, lo_open=True)
    radii = np.asarray(radii, np.float64)
    if radii.size == 0 or radii.size > 64:
        raise ValueError(f"radii must hold 1 to 64 distances, got {radii.size}")
    if np.max(radii) > limit:
        raise ValueError(f"radii must be at most L/2 = {limit:g} m (the arcs stay on the grid), got "
                         f"{float(np.max(radii))!r}")
    return radii


def wake_angle_darmon(eta, grid: Grid, *, source=(0.0, 0.0), direction: float = 0.0, radii, span: float = 40.0,
                      tolerance: float = 0.01) -> WakeAngle:
    """The angle of maximum amplitude as Darmon, Benzaquen & Raphaël (2014) define it (degrees ± uncertainty).

    On each arc at a distance R (``radii``) behind the source, the polar angle φ (0 on the track) at which the
    height's modulus |ζ| is largest, on each side of the track; the angle is the mean of both sides over the
    arcs, with each arc's value in ``angles``. This is the published definition: the heights themselves on
    arcs, not an envelope on sections across the track (:func:`wake_angle_max` measures that other angle, which
    differs from this one by several degrees near Fr ≈ 1). The angle depends on R in the near field, so compare
    it with :func:`darmon_angle_theory` at the same radii. The field is sampled by its periodic cubic B-spline,
    a quarter of a grid spacing apart along each arc, from −``span`` to ``span`` degrees. The uncertainty is
    half the disagreement of the two sides or half the spread of the angles whose |ζ| is within ``tolerance`` of
    the largest (a second crest nearly as high widens it), whichever is larger, over the arcs.

    Parameters
    ----------
    eta : array_like (n, n)
        Heights η, m, on ``grid``, ordered (y, x), finite.
    grid : Grid
        The periodic grid of ``eta``.
    source : (float, float), optional, keyword-only
        Position (x, y) of the source, m (default the origin).
    direction : float, optional, keyword-only
        Direction of travel of the source, rad, 0 = +x, in [−2π, 2π] (default 0).
    radii : array_like (m,), keyword-only
        Distances of the arcs behind the source, m, 0 < R ≤ L/2, 1 to 64 of them.
    span : float, optional, keyword-only
        Largest polar angle searched on each side, degrees, in [20, 80] (default 40: beyond any deep-water cusp
        line).
    tolerance : float, optional, keyword-only
        Relative tolerance that sets the spread, in (0, 0.5] (default 0.01).

    Returns
    -------
    WakeAngle
        ``method="darmon"``: the mean angle over the arcs, degrees ± uncertainty, with ``radii`` and ``angles``.

    Raises
    ------
    ValueError
        When an argument is out of range.

    References
    ----------
    A. Darmon, M. Benzaquen & E. Raphaël (2014). Kelvin wake pattern at large Froude numbers.
    *J. Fluid Mech.* 738, R3.

    Examples
    --------
    >>> import numpy as np
    >>> from wavephys import Grid, Water
    >>> from wavephys.physics.wake import GaussianPressure, steady_wake
    >>> grid = Grid(256, 16.0)
    >>> eta = steady_wake(grid, Water(sigma=0.0), 1.0, GaussianPressure(100.0, 0.15), damping=0.1)
    >>> m = wake_angle_darmon(np.asarray(eta), grid, radii=[4.0, 6.0])
    >>> len(m.angles)
    2
    """
    check_instance("grid", grid, Grid, "wavephys.Grid")
    n = grid.n
    check_array("eta", eta, ndim=2, shape_tail=(n, n))
    if np.asarray(eta).shape != (n, n):
        raise ValueError(f"eta must have shape ({n}, {n}) to match the grid, got {np.asarray(eta).shape}")
    check_array("source", source, ndim=1, shape_tail=(2,))
    check_scalar("direction", direction, lo=-2 * math.pi, hi=2 * math.pi)
    radii = _check_radii(radii, float(grid.length) / 2)
    check_scalar("span", span, lo=20.0, hi=80.0)
    check_scalar("tolerance", tolerance, lo=0.0, hi=0.5, lo_open=True)
    from wavephys.core.spectral import bspline_coefficients

    coefficients = jnp.asarray(bspline_coefficients(np.asarray(eta, np.float32))[..., None])  # numpy: no compiles
    c, s = math.cos(direction), math.sin(direction)
    length, dx = float(grid.length), float(grid.dx)

    def sample(behind, lateral):
        x = source[0] - c * behind - s * lateral
        y = source[1] - s * behind + c * lateral
        u = np.ravel((x + 0.5 * length) / dx - 0.5).astype(np.float32)
        v = np.ravel((y + 0.5 * length) / dx - 0.5).astype(np.float32)
        # one compiled program per power-of-two count of points (the arcs' counts vary with the radius)
        count = u.size
        size = max(64, 1 << (count - 1).bit_length())
        padded = [np.pad(a, (0, size - count)) for a in (u, v)]
        return np.asarray(_spline_at(coefficients, *padded))[:count]

    return _darmon(sample, radii, span, dx / 4, tolerance, "darmon")


def darmon_angle_theory(speed, source: GaussianPressure, *, radii, water: Water = Water(sigma=0.0),
                        damping: float = 0.0, span: float = 40.0, step: float | None = None,
                        tolerance: float = 0.01) -> WakeAngle:
    """Linear theory's angle of maximum amplitude on arcs behind a Gaussian source (Darmon et al.'s definition).

    The heights are the far-field direction integral :func:`wavephys.physics.wake.wake_surface` (independent of
    any grid), read on the same arcs and by the same rule as :func:`wake_angle_darmon`. At large Froude number it
    falls as ≈ 0.2243/Fr rad far behind the source (Darmon, Benzaquen & Raphaël 2014, eq. 4.11).

    Parameters
    ----------
    speed : float
        Source speed U, m/s, > 0.
    source : GaussianPressure
        The Gaussian pressure source.
    radii : array_like (m,), keyword-only
        Distances of the arcs behind the source, m, > 0, 1 to 64 of them, at most 1000 transverse wavelengths.
    water : Water, optional, keyword-only
        The water (default ``Water(sigma=0.0)``: gravity waves only).
    damping : float, optional, keyword-only
        Rayleigh's ε, 1/s, >= 0 with damping·R/U ≤ 50 (default 0).
    span : float, optional, keyword-only
        Largest polar angle searched, degrees, in [20, 80] (default 40).
    step : float, optional, keyword-only
        Spacing of the points along each arc, m, > 0 (default: the source size σ/8).
    tolerance : float, optional, keyword-only
        Relative tolerance that sets the spread, in (0, 0.5] (default 0.01).

    Returns
    -------
    WakeAngle
        ``method="darmon (linear theory)"``, with ``radii`` and ``angles``.

    Raises
    ------
    ValueError
        When an argument is out of range.

    References
    ----------
    A. Darmon, M. Benzaquen & E. Raphaël (2014). Kelvin wake pattern at large Froude numbers.
    *J. Fluid Mech.* 738, R3.
    """
    from wavephys.physics.wake import wake_surface

    check_scalar("speed", speed, lo=0.0, lo_open=True)
    check_instance("source", source, GaussianPressure, "wavephys.physics.wake.GaussianPressure")
    check_instance("water", water, Water, "wavephys.Water")
    longest = 2 * math.pi * float(speed) ** 2 / float(water.g)
    radii = _check_radii(radii, 1000 * longest)
    check_scalar("damping", damping, lo=0.0)
    if damping * float(np.max(radii)) / float(speed) > 50.0:
        raise ValueError(f"damping {damping!r} 1/s fades the waves by more than e^-50 on the farthest arc")
    check_scalar("span", span, lo=20.0, hi=80.0)
    step = float(source.size) / 8 if step is None else step
    check_scalar("step", step, lo=0.0, lo_open=True)
    check_scalar("tolerance", tolerance, lo=0.0, hi=0.5, lo_open=True)

    def sample(behind, lateral):
        return wake_surface(-behind, lateral, speed, source, water, damping).real

    return _darmon(sample, radii, span, step, tolerance, "darmon (linear theory)")



def _crests(phi, height, fraction: float):
    """|φ| (degrees) of the local maxima of |ζ| on both sides whose |ζ| is within ``fraction`` of that side's
    largest (parabolic refinement)."""
    zeta = np.abs(np.asarray(height, np.float64))
    centre = phi.size // 2
    out = []
    for sel in (np.arange(centre, phi.size), np.arange(centre, -1, -1)):
        a, p = zeta[sel], np.abs(np.degrees(phi[sel]))
        top = a.max()
        inner = np.nonzero((a[1:-1] >= a[:-2]) & (a[1:-1] >= a[2:]) & (a[1:-1] >= (1 - fraction) * top))[0] + 1
        for i in inner:
            den = a[i - 1] - 2 * a[i] + a[i + 1]
            frac = 0.5 * (a[i - 1] - a[i + 1]) / den if den < 0 else 0.0
            out.append(float(p[i] + frac * (p[1] - p[0])))
        if a[0] >= (1 - fraction) * top and a[0] >= a[1]:  # on the track
            out.append(0.0)
    return tuple(sorted(out))


def darmon_crests(speed, source: GaussianPressure, *, radii, water: Water = Water(sigma=0.0), fraction: float = 0.1,
                  span: float = 40.0, step: float | None = None) -> tuple:
    """On each arc behind a Gaussian source, the angles at which linear theory's |ζ| has a crest within
    ``fraction`` of its largest: where Darmon et al.'s angle of maximum amplitude may land on a field whose
    amplitudes differ from the integral's by up to that fraction (a grid's periodic images, the near field).

    Parameters
    ----------
    speed : float
        Source speed U, m/s, > 0.
    source : GaussianPressure
        The Gaussian pressure source.
    radii : array_like (m,), keyword-only
        Distances of the arcs behind the source, m, > 0, 1 to 64 of them.
    water : Water, optional, keyword-only
        The water (default gravity waves in deep water).
    fraction : float, optional, keyword-only
        How far below the largest |ζ| a crest may be, in [0, 0.5] (default 0.1).
    span : float, optional, keyword-only
        Largest polar angle searched, degrees, in [20, 80] (default 40).
    step : float, optional, keyword-only
        Spacing of the points along each arc, m, > 0 (default σ/8).

    Returns
    -------
    tuple of tuple of float
        Per arc, the crests' polar angles |φ|, degrees, both sides together, ascending.

    Raises
    ------
    ValueError
        When an argument is out of range.
    """
    from wavephys.physics.wake import wake_surface

    check_scalar("speed", speed, lo=0.0, lo_open=True)
    check_instance("source", source, GaussianPressure, "wavephys.physics.wake.GaussianPressure")
    check_instance("water", water, Water, "wavephys.Water")
    radii = _check_radii(radii, 1000 * 2 * math.pi * float(speed) ** 2 / float(water.g))
    check_scalar("fraction", fraction, lo=0.0, hi=0.5)
    check_scalar("span", span, lo=20.0, hi=80.0)
    step = float(source.size) / 8 if step is None else step
    check_scalar("step", step, lo=0.0, lo_open=True)
    out = []
    for r in radii:
        phi, behind, lateral = _arc_points(float(r), math.radians(span), step)
        out.append(_crests(phi, wake_surface(-behind, lateral, speed, source, water).real, fraction))
    return tuple(out)


WAKE_ANGLE_METHODS = Methods("wake angle", max=wake_angle_max, cusp=wake_angle_cusp, darmon=wake_angle_darmon)
"""Wake-angle estimators by name. Each measures a different published quantity; linear theory's
value of it is :data:`WAKE_ANGLE_THEORIES` under the same name (a new estimator registers both)."""


def cusp_angle_theory(speed, source: GaussianPressure | None = None, *, water: Water = Water(sigma=0.0)) -> WakeAngle:
    """The cusp line's half-angle that :func:`wake_angle_cusp` measures: Kelvin's 19.47° in deep water,
    wider in finite depth (Havelock), for a source of any size (degrees; uncertainty 0).

    Parameters
    ----------
    speed : float
        Source speed U, m/s, > 0 (above c_min with surface tension).
    source : GaussianPressure, optional
        Not used: the cusp line does not depend on the source (taken so that every entry of
        :data:`WAKE_ANGLE_THEORIES` has one signature).
    water : Water, optional, keyword-only
        The water (default gravity waves in deep water).

    Returns
    -------
    WakeAngle
        ``method="cusp (linear theory)"``.

    Raises
    ------
    ValueError
        Below c_min (no stationary wave, no wake).

    References
    ----------
    Lord Kelvin (1887). On ship waves. *Proc. Inst. Mech. Eng.* 38, 409–434; T. H. Havelock (1908).
    The propagation of groups of waves in dispersive media, with application to waves on water produced
    by a travelling disturbance. *Proc. R. Soc. A* 81, 398–430.
    """
    if source is not None:
        check_instance("source", source, GaussianPressure, "wavephys.physics.wake.GaussianPressure")
    check_instance("water", water, Water, "wavephys.Water")
    return WakeAngle(float(cusp_line(speed, water).angle), 0.0, "cusp (linear theory)", 0)


WAKE_ANGLE_THEORIES = Methods("wake angle (linear theory)", max=max_amplitude_angle_theory, cusp=cusp_angle_theory,
                              darmon=darmon_angle_theory)
"""Linear theory's value of the quantity each estimator of :data:`WAKE_ANGLE_METHODS` measures, under the
same name: the angle of maximum amplitude through the same sections (``max``), the cusp line (``cusp``),
Darmon, Benzaquen & Raphaël's angle of maximum amplitude on the same arcs (``darmon``). The problem set
``tests/test_families.py`` measures every estimator against its entry here on steady wakes."""


def wake_angle_theory(speed, source: GaussianPressure, *, method: str = "max", **options) -> WakeAngle:
    """Linear theory's value of the quantity that ``method`` of :data:`WAKE_ANGLE_METHODS` measures, for a
    Gaussian pressure source at ``speed``, by :data:`WAKE_ANGLE_THEORIES`.

    Parameters
    ----------
    speed : float
        Source speed U, m/s, > 0.
    source : GaussianPressure
        The Gaussian pressure source.
    method : str, optional, keyword-only
        A name in :data:`WAKE_ANGLE_THEORIES` (default ``"max"``).
    **options
        The measurement's own options, passed to the theory that takes them: ``near``, ``far``,
        ``exclude``, ``spacing`` (the field's grid spacing), ``sections``, ``tolerance`` for ``"max"``;
        ``radii``, ``span``, ``step``, ``tolerance`` for ``"darmon"``; ``damping`` (Rayleigh's ε of a
        damped field, 1/s) for both; ``water`` for all.

    Returns
    -------
    WakeAngle

    Raises
    ------
    TypeError
        For a ``source`` that is not a GaussianPressure, or an option no theory takes.
    ValueError
        For an unknown ``method`` or an option out of its theory's range.

    Examples
    --------
    >>> round(wake_angle_theory(1.0, GaussianPressure(1.0, 0.05), method="cusp").angle, 2)   # Kelvin
    19.47
    """
    check_instance("source", source, GaussianPressure, "wavephys.physics.wake.GaussianPressure")
    return WAKE_ANGLE_THEORIES(method, speed, source, **options)


def wake_angle(eta, grid: Grid, *, method: str = "max", **options) -> WakeAngle:
    """Measure the half-angle of a wake in a height field by ``method`` in :data:`WAKE_ANGLE_METHODS`.

    ``options`` go to the method (each takes only its own): ``source``, ``direction``,
    ``near``, ``far``, ``exclude`` for both; ``speed``, ``water``, ``bandwidth`` for
    ``"cusp"``. See :func:`wake_angle_max` and :func:`wake_angle_cusp`.

    Parameters
    ----------
    eta : array_like (n, n)
        Heights η, m, on ``grid``, ordered (y, x).
    grid : Grid
        The periodic grid of ``eta``.
    method : {"max", "cusp"}, optional, keyword-only
        Estimator, a name in :data:`WAKE_ANGLE_METHODS` (default ``"max"``).
    **options
        Keyword arguments for the method; each method takes only those its signature declares (ranges as
        documented there).

    Returns
    -------
    WakeAngle
        The measured half-angle, degrees ± uncertainty.

    Raises
    ------
    ValueError
        When ``method`` is unknown, or as the method raises.

    Examples
    --------
    >>> import numpy as np
    >>> from wavephys import Grid, Water
    >>> from wavephys.physics.wake import GaussianPressure, steady_wake
    >>> grid = Grid(256, 16.0)
    >>> eta = steady_wake(grid, Water(sigma=0.0), 1.0, GaussianPressure(100.0, 0.15), damping=0.1)
    >>> m = wake_angle(np.asarray(eta), grid, method="cusp", speed=1.0, near=2.0, far=7.0)
    >>> abs(m.angle - 19.47) < 1.0   # Kelvin's angle
    True
    """
    return WAKE_ANGLE_METHODS(method, eta, grid, **options)


def track_wavelength(eta, grid: Grid, *, source=(0.0, 0.0), near: float, far: float) -> float:
    """Wavelength of the waves along the track behind a source moving in +x, m.

    Zero crossings of η on the grid row through the source, between ``near`` and ``far``
    metres behind it, are located by linear interpolation; a line through crossing
    position against crossing number has slope λ/2. For a deep-water gravity wake this
    is the transverse wavelength 2πU²/g.

    Parameters
    ----------
    eta : array_like (n, n)
        Heights η, m, on ``grid``, ordered (y, x).
    grid : Grid
        The periodic grid of ``eta``.
    source : (float, float), optional, keyword-only
        Position (x, y) of the source, m (default the origin).
    near, far : float, keyword-only
        Distances behind ``source`` of the measured stretch, m, 0 < near < far ≤ L/2.

    Returns
    -------
    float
        Wavelength λ along the track, m.

    Raises
    ------
    ValueError
        When there are fewer than 4 zero crossings between near and far, or an argument is out of range.
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
