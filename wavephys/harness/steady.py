"""Wake angles of a user's frame as check rows, in degrees: the outer edge and the angle of maximum amplitude.

A wake behind a source moving at U has two angles that are often confused (docs/physics.md,
wake angles):

* the **outer edge** (cusp line): Kelvin's 19.47° in deep water for any source shape, wider in
  finite depth; measured by :func:`wavephys.harness.wake.wake_angle_cusp` and expected from
  :func:`wavephys.physics.wake.cusp_line`;
* the **angle of maximum amplitude** by Darmon, Benzaquen & Raphaël's definition (the largest
  |ζ| on arcs at fixed distances behind the source), which depends on the source's size
  through the Froude number Fr = U/√(g b): near Kelvin's angle for 0.4 ≲ Fr ≲ 0.8, falling as
  ≈ 0.2243/Fr rad above; measured by :func:`wavephys.harness.wake.wake_angle_darmon` and
  expected from :func:`wavephys.harness.wake.darmon_angle_theory` for a Gaussian pressure
  source of the claimed size, at the same distances.

:func:`wake_check` takes one frame (heights in the grid convention: cell-centred, the origin
at the middle of the square), the source's position and direction of travel (degrees), and
returns a :class:`~wavephys.harness.Check` row in degrees with the likely cause when it fails
(a non-dispersive scheme has a Mach cone instead of a Kelvin wedge; a wrong g, depth or speed
moves the edge).
"""

from __future__ import annotations

import math
from typing import Optional

import numpy as np

from wavephys.core.grid import Grid
from wavephys.core.inputs import check_array, check_choice, check_instance, check_scalar
from wavephys.core.water import Water
from wavephys.harness.checks import bound, compare

__all__ = ["wake_check", "WAKE_ANGLES", "CREST_FRACTION", "NEAREST_ARC"]

NEAREST_ARC = 8.0
"""The nearest arc ``wake_check(angle="max")`` reads, in source lengths b = π√2σ: from there on a correct
periodic steady wake matched the direction integral on every arc tried (Fr 0.5-3, grids of 20 b to 100 b);
nearer, at 3-6 b, its maximum sat on a crest the integral puts 10-90 % lower."""

CREST_FRACTION = 0.1
"""How far below theory's largest |ζ| on an arc a crest may be and still be where a correct simulator's maximum
lands: the FFT steady wake's heights differ from the direction integral by 4-12 % of the peak (periodic images,
the near field), enough to swap two nearly equal crests."""

WAKE_ANGLES = ("edge", "max")
"""What :func:`wake_check` measures: ``"edge"`` the outer edge (cusp line), ``"max"`` the angle of maximum
amplitude by Darmon, Benzaquen & Raphaël's definition."""


def _cause_edge(measured: float, expected: float, speed: float, water: Water) -> str:
    """Likely cause of an outer edge that is not the cusp line's."""
    if not math.isfinite(measured):
        return "no wake ridge was found between near and far (is the source where you said, moving that way?)"
    if measured < expected:
        return (f"the wedge is narrower than the cusp line's {expected:.2f}°: check U ({speed:g} m/s), g "
                f"({float(water.g):g} m/s^2) and the depth (shallower water widens the wedge, not narrows it)")
    deep = math.degrees(math.asin(1 / 3))
    if not math.isfinite(float(water.depth)) and measured > deep + 3:
        c = speed * math.sin(math.radians(measured))
        return (f"the wedge is wider than Kelvin's 19.47°: a non-dispersive scheme (one wave speed c makes a Mach "
                f"cone of half-angle asin(c/U); c = {c:.3g} m/s gives this one, the long-wave speed of water "
                f"{c * c / float(water.g):.3g} m deep), or finite depth not claimed (a Havelock wedge: claim the "
                f"depth)")
    return "the wedge is wider than theory's: a shallower floor than claimed, or a scheme with too little dispersion"


def wake_check(eta, dx: float, *, speed: float, water: Optional[Water] = None, source=(0.0, 0.0),
               direction: float = 0.0, angle: str = "edge", size: Optional[float] = None, near=None, far=None,
               radii=None, atol: float = 1.0, rtol: float = 0.1):
    """Check a wake's angle in one frame against linear theory, in degrees.

    Parameters
    ----------
    eta : array_like (n, n)
        Heights, m, one frame, rows along y, finite; square, periodic (the wake must not wrap into itself).
    dx : float
        Grid spacing, m, > 0.
    speed : float, keyword-only
        The source's speed U, m/s, > 0.
    water : Water, optional, keyword-only
        The water of the theory (default gravity waves in deep water, ``Water(sigma=0.0)``).
    source : (float, float), optional, keyword-only
        Where the source is in this frame, m, in the grid convention (the origin at the square's centre).
    direction : float, optional, keyword-only
        Its direction of travel, degrees (0 = +x, 90 = +y), in [−360, 360] (default 0).
    angle : {"edge", "max"}, optional, keyword-only
        ``"edge"``: the outer edge (cusp line); ``"max"``: the angle of maximum amplitude by Darmon et al.'s
        definition, which needs ``size``.
    size : float, optional, keyword-only
        The source as a Gaussian pressure p0·exp(−r²/(2σ²)): σ, m, > 0 (needed by ``"max"``).
    near, far : float, optional, keyword-only
        ``"edge"``: distances behind the source of the first and last section, m (default L/8 and 3L/8).
    radii : array_like, optional, keyword-only
        ``"max"``: distances of the arcs behind the source, m, each at least 8 b (:data:`NEAREST_ARC`; b = π√2σ)
        and at most L/2 (default three from 8 b to 0.45 L).
    atol, rtol : float, optional, keyword-only
        The tolerance is max(``atol`` degrees, ``rtol`` × expected), > 0 and >= 0 (default 1° and 10 %).

    Returns
    -------
    Check
        ``"edge"``: a ``"~="`` row, degrees, the measured outer edge against the cusp line's, with the
        measurement's uncertainty in the note. ``"max"``: a ``"<="`` row, degrees, of the largest distance (over
        the arcs) between the measured angle and the nearest crest that theory puts within 10 % of its largest
        |ζ| on that arc (:data:`CREST_FRACTION`; Darmon et al.'s angle jumps between nearly equal crests, and a
        correct field's amplitudes differ from the integral's by that much), with every arc's measured and
        theory's angle in the note. Either with the likely cause when it fails.

    Raises
    ------
    ValueError
        When ``angle`` is ``"max"`` without ``size``, the cusp waves are not resolved, or a value is out of range.

    References
    ----------
    A. Darmon, M. Benzaquen & E. Raphaël (2014). Kelvin wake pattern at large Froude numbers.
    *J. Fluid Mech.* 738, R3.

    Examples
    --------
    >>> import numpy as np
    >>> from wavephys import Grid, Water
    >>> from wavephys.physics.wake import GaussianPressure, steady_wake
    >>> eta = steady_wake(Grid(256, 16.0), Water(sigma=0.0), 1.0, GaussianPressure(100.0, 0.15), damping=0.1)
    >>> wake_check(np.asarray(eta), 16.0 / 256, speed=1.0, near=2.0, far=7.0).ok
    True
    """
    check_array("eta", eta, ndim=2)
    eta = np.asarray(eta, np.float64)
    if eta.shape[0] != eta.shape[1]:
        raise ValueError(f"eta must be square (n, n), got shape {eta.shape}")
    check_scalar("dx", dx, lo=0.0, lo_open=True)
    check_scalar("speed", speed, lo=0.0, lo_open=True)
    water = Water(sigma=0.0) if water is None else water
    check_instance("water", water, Water, "wavephys.Water")
    check_array("source", source, ndim=1, shape_tail=(2,))
    check_scalar("direction", direction, lo=-360.0, hi=360.0)
    check_choice("angle", angle, WAKE_ANGLES)
    check_scalar("atol", atol, lo=0.0, lo_open=True)
    check_scalar("rtol", rtol, lo=0.0)
    if size is not None:
        check_scalar("size", size, lo=0.0, lo_open=True)
    if radii is not None:
        check_array("radii", radii, ndim=1, lo=0.0, lo_open=True)
    for name, value in (("near", near), ("far", far)):
        if value is not None:
            check_scalar(name, value, lo=0.0, lo_open=True)
    grid = Grid(eta.shape[0], eta.shape[0] * float(dx))
    if angle == "edge":
        return _edge_row(eta, grid, speed, water, tuple(source), math.radians(direction), near, far, atol, rtol)
    if size is None:
        raise ValueError("size: the angle of maximum amplitude needs the source's size σ (m) to give theory's "
                         "value (it depends on the Froude number); or check angle='edge'")
    return _max_row(eta, grid, speed, water, tuple(source), math.radians(direction), float(size), radii, atol, rtol)


def _edge_row(eta, grid: Grid, speed, water, source, heading, near, far, atol, rtol):
    """The outer edge against the cusp line (:func:`wake_check`, ``angle="edge"``)."""
    from wavephys.harness.wake import wake_angle_cusp
    from wavephys.physics.wake import cusp_line

    length, dx = float(grid.length), float(grid.dx)
    near = length / 8 if near is None else near
    far = 3 * length / 8 if far is None else far
    cusp = cusp_line(speed, water)
    expected = float(cusp.angle)
    if cusp.wavenumber >= math.pi / dx:
        raise ValueError(f"dx: {dx!r} m does not resolve the wake's cusp waves (k_c = {cusp.wavenumber:.4g} "
                         f"rad/m, 2 pi/k_c = {2 * math.pi / cusp.wavenumber:.4g} m; the grid holds k < pi/dx = "
                         f"{math.pi / dx:.4g} rad/m)")
    try:
        m = wake_angle_cusp(eta, grid, source=source, direction=heading, near=near, far=far, speed=speed, water=water)
    except ValueError as exc:
        if "too few sections" not in str(exc):
            raise
        m = None
    measured = math.nan if m is None else m.angle
    note = (f"outer edge (cusp line) {near:.4g}-{far:.4g} m behind the source"
            + ("" if m is None else f", measured ± {m.uncertainty:.2f}°"))
    quantity = f"wake outer edge, U = {speed:g} m/s"
    tolerance = max(atol, rtol * abs(expected))
    row = compare(quantity, measured, expected, atol=tolerance, unit="deg", note=note)
    if row.ok:
        return row
    cause = _cause_edge(measured, expected, speed, water)
    return compare(quantity, measured, expected, atol=tolerance, unit="deg", note=f"{note}; likely cause: {cause}")


def _default_radii(size: float, length: float, radii):
    """The arcs of the maximum-amplitude check: from :data:`NEAREST_ARC` b to 0.45 L, or the given ones checked."""
    b = math.pi * math.sqrt(2) * size
    nearest = NEAREST_ARC * b
    if radii is None:
        if nearest > 0.45 * length:
            raise ValueError(f"eta: the grid ({length:.4g} m) is too small to check this source's angle of maximum "
                             f"amplitude: its arcs must lie {NEAREST_ARC:g} b = {nearest:.4g} m or more behind the "
                             f"source (b = pi sqrt(2) sigma = {b:.4g} m) and within 0.45 L = {0.45 * length:.4g} m")
        return np.linspace(nearest, 0.45 * length, 3)
    if np.min(radii) < nearest * (1 - 1e-9):
        raise ValueError(f"radii: the angle of maximum amplitude is compared with theory from {NEAREST_ARC:g} b = "
                         f"{nearest:.4g} m behind the source (b = pi sqrt(2) sigma); nearer, the source's local "
                         f"field and a small grid's images move it; got {float(np.min(radii)):.4g} m")
    return radii


def _max_row(eta, grid: Grid, speed, water, source, heading, size, radii, atol, rtol):
    """The angle of maximum amplitude on arcs against theory's crests (:func:`wake_check`, ``angle="max"``)."""
    from wavephys.harness.wake import darmon_angle_theory, darmon_crests, wake_angle_darmon
    from wavephys.physics.wake import GaussianPressure, froude_number

    radii = _default_radii(size, float(grid.length), radii)
    m = wake_angle_darmon(eta, grid, source=source, direction=heading, radii=radii)
    gaussian = GaussianPressure(1.0, size)
    t = darmon_angle_theory(speed, gaussian, radii=radii, water=water)
    crests = darmon_crests(speed, gaussian, radii=radii, water=water, fraction=CREST_FRACTION)
    # per arc: how far the measured angle is from the nearest crest theory rates within 10 % of its largest
    off = [min(abs(a - c) for c in cs) if cs else math.inf for a, cs in zip(m.angles, crests)]
    tolerance = max(atol, rtol * abs(t.angle))
    fr = froude_number(speed, size, water)
    each = "; ".join(f"{r:.4g} m: {a:.2f}° (theory {e:.2f}°, crests within 10 %: "
                     f"{', '.join(dict.fromkeys(f'{c:.1f}' for c in cs))})"
                     for r, a, e, cs in zip(m.radii, m.angles, t.angles, crests))
    note = f"Fr = {fr:.3g}, arcs behind the source (Darmon et al.'s definition): {each}"
    quantity = (f"wake angle of maximum amplitude, U = {speed:g} m/s, Fr = {fr:.3g}: worst distance from "
                f"theory's near-largest crests")
    row = bound(quantity, max(off), tolerance, unit="deg", note=note)
    if row.ok:
        return row
    cause = ("the source's size or speed is not what was claimed (the angle follows Fr = U/sqrt(g b), "
             "b = pi sqrt(2) sigma: near 0 below Fr ~ 0.35, about Kelvin's 19.5 deg for Fr 0.4-0.8, "
             "~ 0.2243/Fr rad above), or the short diverging waves are damped (smoothing, a coarse grid)")
    return bound(quantity, max(off), tolerance, unit="deg", note=f"{note}; likely cause: {cause}")
