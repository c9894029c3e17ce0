r"""Moving sources: the ship-wave kernels Φ1/Φ2 of Loviscach (2003), eq. 2 (docs/physics.md §1.3).

A ship profile f (1 inside the hull, 0 outside, optionally blurred by a Gaussian in
Fourier space) moving on a straight line at velocity v during [t, t + Δt] adds, at
t + Δt, the complex wave field

.. math::

    \mathcal F^{-1}\left[\hat f_t\,M_1 + \hat f_{t+\Delta t}\,M_2\right],\qquad
    M_1 = e^{-i\omega\Delta t}\left(-1 + i\omega\Delta t\,Q_1(\alpha)\right),\quad
    M_2 = 1 + i\omega\Delta t\,Q_2(\alpha),

    Q_1 = \frac{e^{-i\alpha} + i\alpha - 1}{\alpha^2},\quad
    Q_2 = \frac{e^{i\alpha} - i\alpha - 1}{\alpha^2},\quad
    \alpha = (\mathbf k\cdot\mathbf v - \omega)\Delta t .

For straight motion this is the exact Duhamel integral of the source ∂(s·f)/∂t (s the
ship's strength, m²/s): M1 + M2·e^{−ik·vΔt} = e^{−iωΔt}(e^{−iα} − 1)(k·vΔt)/α, so one
step of Δt equals two of Δt/2, and a ship at rest adds nothing (M1 + M2 = 0).

Near the resonance α → 0 (k·v = ω: the stationary Kelvin waves) Q1 → −1/2 + iα/6 and
Q2 → −1/2 − iα/6; evaluated as written they lose all digits in float32. Below
|α| < 1/2 we sum their Taylor series (13 terms: truncation below 1e-16 relative);
:func:`ship_multipliers_naive` keeps the textbook form as the documented failure.

The new waves matter only near the ship, so they are computed on a 2M × 2M patch of
the grid around it and added to the N × N field; :func:`patch_leak` measures how much
of them a patch misses (against a patch twice as large) and the simulation refuses a
Δt whose leak exceeds a tolerance.

Two methods make the new waves (:data:`SHIP_METHODS`): :func:`ship_waves_kernels`
(Φ1/Φ2, exact for straight motion within a step) and :func:`ship_waves_impulses` (the
naive row of dropped stones the paper warns about, kept for comparison). A
:class:`Ship` is a source of the simulation: it adds its waves after each step's cutoff.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache, partial
from typing import Callable, Optional

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.inputs import (Array, Choice, Instance, Int, Maybe, Real, check_array, check_choice, check_instance,
                                  check_int, check_scalar, validate)
from wavephys.core.specs import field_of, COMPLEX_ARRAY, GRID, POSITIVE, REAL, VECTOR2, WATER, model_grid
from wavephys.core.methods import Methods
from wavephys.physics.dispersion import angular_frequency
from wavephys.core.grid import Grid
from wavephys.core.water import Water

__all__ = [
    "ship_multipliers",
    "ship_multipliers_naive",
    "resonance_quotients",
    "resonance_quotients_exact",
    "Hull",
    "Path",
    "straight_path",
    "turning_path",
    "Ship",
    "hull_spectrum",
    "ship_waves_kernels",
    "ship_waves_impulses",
    "SHIP_METHODS",
    "ship_patch_waves",
    "add_ship_waves",
    "patch_leak",
    "max_patch_dt",
]

_SERIES_TERMS = 13
_SERIES_RADIUS = 0.5


@validate(alpha=COMPLEX_ARRAY)
def resonance_quotients(alpha):
    """(Q1, Q2) = ((e^{−iα} + iα − 1)/α², (e^{iα} − iα − 1)/α²), cancellation-free.

    Taylor series Σ_{j≥2} (∓iα)^j / (j! α²) for |α| < 1/2, the closed form elsewhere.

    Parameters
    ----------
    alpha : array_like
        α = (k·v − ω)Δt, rad, real or complex, any shape.

    Returns
    -------
    (Q1, Q2) : tuple of jax.Array
        Complex, dimensionless, shape of ``alpha``; Q1, Q2 → −1/2 at α = 0.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 2 (docs/physics.md §1.3).
    """
    alpha = jnp.asarray(alpha)
    small = jnp.abs(alpha) < _SERIES_RADIUS
    a_s = jnp.where(small, alpha, 0.0)
    a_b = jnp.where(small, 1.0, alpha)

    def series(sign):
        # Horner on c_j = (sign·i)^j / j!, j = 2 … 2 + terms − 1, divided by α²
        acc = jnp.zeros_like(a_s, dtype=jnp.result_type(a_s, jnp.complex64))
        for j in range(_SERIES_TERMS + 1, 1, -1):
            acc = acc * a_s + (sign * 1j) ** j / math.factorial(j)
        return acc

    q1 = jnp.where(small, series(-1), (jnp.exp(-1j * a_b) + 1j * a_b - 1.0) / (a_b * a_b))
    q2 = jnp.where(small, series(+1), (jnp.exp(1j * a_b) - 1j * a_b - 1.0) / (a_b * a_b))
    return q1, q2


@validate(alpha=Array(hi=1e6, lo=-1e6))
def resonance_quotients_exact(alpha):
    """Reference (Q1, Q2) for float64 inputs, independent of :func:`resonance_quotients`.

    Exact rational arithmetic on the Taylor series (41 terms: below double precision for
    |α| ≤ 2), rounded once at the end. Slow; for tests and checks.

    Parameters
    ----------
    alpha : array_like
        α, rad, real, in [−1e6, 1e6] (accurate for |α| ≤ 2).

    Returns
    -------
    (Q1, Q2) : tuple of numpy.ndarray (m,)
        Complex, dimensionless, over ``alpha`` flattened to 1-D (at least one entry).

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 2 (docs/physics.md §1.3).
    """
    from fractions import Fraction

    out = []
    for sign in (-1, 1):
        vals = []
        for a in np.atleast_1d(np.asarray(alpha, np.float64)):
            if a == 0:  # the limit: (±i)²/2! = −1/2
                vals.append(complex(-0.5, 0.0))
                continue
            af = Fraction(float(a))
            re, im, term = Fraction(0), Fraction(0), Fraction(1)
            for j in range(1, 42):
                term = term * af / j  # α^j / j!
                if j >= 2:
                    unit = [(1, 0), (0, 1), (-1, 0), (0, -1)][(j * (1 if sign > 0 else 3)) % 4]  # (±i)^j
                    re += unit[0] * term
                    im += unit[1] * term
            vals.append(complex(float(re / af**2), float(im / af**2)))
        out.append(np.asarray(vals))
    return out[0], out[1]


def _multipliers(k_dot_v, omega, dt, quotients):
    alpha = (k_dot_v - omega) * dt
    q1, q2 = quotients(alpha)
    wdt = omega * dt
    m1 = jnp.exp(-1j * wdt) * (-1.0 + 1j * wdt * q1)
    m2 = 1.0 + 1j * wdt * q2
    return m1, m2


def _k_dot_v_omega(grid: Grid, water: Water, velocity):
    ky, kx = grid.wavenumbers()
    return kx * velocity[0] + ky * velocity[1], angular_frequency(grid.wavenumber_magnitude(), water)


def _check_velocity(velocity):
    return jnp.asarray(velocity, dtype=jnp.result_type(float, jnp.asarray(velocity)))


_VELOCITY = Array(min_ndim=1, shape=(2,), lo=-1e4, hi=1e4)  # m/s
_DT = Real(lo=0.0, hi=1e4, lo_open=True)


@validate(grid=GRID, water=WATER, velocity=_VELOCITY, dt=_DT)
def ship_multipliers(grid: Grid, water: Water, velocity, dt):
    """Fourier multipliers (M1, M2) of a hull moving at ``velocity`` (m/s, (vx, vy)) for Δt (s).

    Complex arrays ``(n, n)`` on the grid's full ``fft2`` spectrum; dimensionless.
    Stable near the resonance α = 0 in float32 and float64 (module doc).

    Parameters
    ----------
    grid : Grid
    water : Water
    velocity : array_like (2,)
        (vx, vy) of the hull over the step, m/s, each in [−1e4, 1e4].
    dt : float
        Δt, s, in (0, 1e4].

    Returns
    -------
    (M1, M2) : tuple of jax.Array (n, n)
        Complex, dimensionless.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 2 (docs/physics.md §1.3).
    """
    velocity = _check_velocity(velocity)
    kv, omega = _k_dot_v_omega(grid, water, velocity)
    return _multipliers(kv, omega, dt, resonance_quotients)


@validate(grid=GRID, water=WATER, velocity=_VELOCITY, dt=_DT)
def ship_multipliers_naive(grid: Grid, water: Water, velocity, dt):
    """(M1, M2) with the quotients evaluated as written: a documented failure near α = 0.

    Parameters
    ----------
    grid : Grid
    water : Water
    velocity : array_like (2,)
        (vx, vy) of the hull over the step, m/s, each in [−1e4, 1e4].
    dt : float
        Δt, s, in (0, 1e4].

    Returns
    -------
    (M1, M2) : tuple of jax.Array (n, n)
        Complex, dimensionless; inaccurate (or NaN at α = 0) near the resonance.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 2 (docs/physics.md §1.3).
    """
    velocity = _check_velocity(velocity)
    kv, omega = _k_dot_v_omega(grid, water, velocity)

    def naive(alpha):
        return ((jnp.exp(-1j * alpha) + 1j * alpha - 1.0) / (alpha * alpha),
                (jnp.exp(1j * alpha) - 1j * alpha - 1.0) / (alpha * alpha))

    return _multipliers(kv, omega, dt, naive)


# -- hulls ------------------------------------------------------------------------------
HULL_KINDS = ("ellipse", "gaussian", "mask")


@dataclass(frozen=True, eq=False)
class Hull:
    """A ship's footprint f in its own frame (x forward, y to port), dimensionless.

    Hulls compare and hash by value (the mask by its bytes), so compiled patch kernels
    are shared by equal hulls.

    Parameters
    ----------
    kind : {"ellipse", "gaussian", "mask"}
        ``"ellipse"``: 1 inside the ellipse of the given length × width; ``"gaussian"``:
        exp(−x²/(2(L/4)²) − y²/(2(W/4)²)); ``"mask"``: the array ``mask`` (values in
        [0, 1], rows = y, columns = x) spanning length × width.
    length, width : float
        m, > 0.
    blur : float
        Standard deviation of the Gaussian blur applied in Fourier space, m, ≥ 0.
    mask : array, optional
        For ``kind="mask"``.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 2 (docs/physics.md §1.3).
    """

    kind: str = "ellipse"
    length: float = 1.0
    width: float = 0.4
    blur: float = 0.0
    mask: Optional[np.ndarray] = None

    def __post_init__(self):
        check_choice("kind", self.kind, HULL_KINDS)
        check_scalar("length", self.length, lo=0.0, lo_open=True)
        check_scalar("width", self.width, lo=0.0, lo_open=True)
        check_scalar("blur", self.blur, lo=0.0)
        if self.kind == "mask":
            if self.mask is None:
                raise ValueError("mask must be given for kind='mask'")
            check_array("mask", self.mask, lo=0.0, hi=1.0, ndim=2)
            object.__setattr__(self, "mask", np.asarray(self.mask, np.float32))
        elif self.mask is not None:
            raise ValueError(f"mask is only used with kind='mask', got kind={self.kind!r} and a mask")

    def _key(self):
        mask = None if self.mask is None else (self.mask.shape, self.mask.tobytes())
        return (self.kind, float(self.length), float(self.width), float(self.blur), mask)

    def __eq__(self, other):
        return isinstance(other, Hull) and self._key() == other._key()

    def __hash__(self):
        return hash(self._key())

    @validate(u=Array(), v=Array())
    def evaluate(self, u, v):
        """f at ship-frame coordinates (u forward, v to port), m → dimensionless."""
        a, b = self.length / 2, self.width / 2
        if self.kind == "ellipse":
            return ((u / a) ** 2 + (v / b) ** 2 <= 1.0).astype(jnp.float32)
        if self.kind == "gaussian":
            return jnp.exp(-0.5 * ((u / (a / 2)) ** 2 + (v / (b / 2)) ** 2))
        mask = jnp.asarray(self.mask, jnp.float32)
        rows, cols = mask.shape
        i = jnp.round((v / self.width + 0.5) * rows - 0.5).astype(jnp.int32)
        j = jnp.round((u / self.length + 0.5) * cols - 0.5).astype(jnp.int32)
        inside = (i >= 0) & (i < rows) & (j >= 0) & (j < cols)
        return jnp.where(inside, mask[jnp.clip(i, 0, rows - 1), jnp.clip(j, 0, cols - 1)], 0.0)

    @property
    def radius(self):
        """Radius of the circle that holds the hull (3σ for a Gaussian), m."""
        r = 0.5 * math.hypot(self.length, self.width)
        return 1.5 * r if self.kind == "gaussian" else r


# -- paths ------------------------------------------------------------------------------
@dataclass(frozen=True)
class Path:
    """A ship's pose over time: ``pose(t) → (x, y, heading)`` in m, m, rad (grid frame).

    Calling the path with t (s) returns the pose as three floats, ValueError if ``pose``
    returns anything else or a non-finite value.

    Parameters
    ----------
    pose : callable
        ``pose(t) -> (x, y, heading)``: t in s; x, y in m, heading in rad, all finite.
    """

    pose: Callable[[float], tuple]

    def __post_init__(self):
        if not callable(self.pose):
            raise TypeError(f"pose must be a callable t → (x, y, heading), got {type(self.pose).__name__}")

    def __call__(self, t: float):
        out = self.pose(float(t))
        if not isinstance(out, (tuple, list)) or len(out) != 3:
            raise ValueError(f"path pose(t) must return (x, y, heading), got {out!r} at t={t}")
        x, y, heading = out
        for name, v in (("x", x), ("y", y), ("heading", heading)):
            if not math.isfinite(float(v)):
                raise ValueError(f"path gave a non-finite {name} at t={t}: {v}")
        return float(x), float(y), float(heading)


def straight_path(start, velocity) -> Path:
    """Straight line from ``start`` (x, y; m, at t = 0) at constant ``velocity`` (m/s).

    Parameters
    ----------
    start : array_like (2,)
        (x, y) at t = 0, m.
    velocity : array_like (2,)
        (vx, vy), m/s; the heading is its direction.

    Returns
    -------
    Path
    """
    check_array("start", start, ndim=1, shape_tail=(2,))
    check_array("velocity", velocity, ndim=1, shape_tail=(2,))
    (x0, y0), (vx, vy) = np.asarray(start, float), np.asarray(velocity, float)
    heading = math.atan2(vy, vx)
    return Path(lambda t: (x0 + vx * t, y0 + vy * t, heading))


def turning_path(center, radius: float, speed: float, start_angle: float = 0.0) -> Path:
    """Circle of ``radius`` (m) about ``center`` at ``speed`` (m/s, > 0: counter-clockwise).

    Parameters
    ----------
    center : array_like (2,)
        (x, y) of the circle's centre, m.
    radius : float
        m, > 0.
    speed : float
        m/s along the circle; > 0 counter-clockwise, < 0 clockwise.
    start_angle : float
        Polar angle of the position at t = 0, rad.

    Returns
    -------
    Path
    """
    check_array("center", center, ndim=1, shape_tail=(2,))
    check_scalar("radius", radius, lo=0.0, lo_open=True)
    check_scalar("speed", speed)
    check_scalar("start_angle", start_angle)
    cx, cy = np.asarray(center, float)
    w = speed / radius

    def pose(t):
        a = start_angle + w * t
        return cx + radius * math.cos(a), cy + radius * math.sin(a), a + math.copysign(math.pi / 2, speed)

    return Path(pose)


@dataclass(frozen=True)
class Ship:
    """A hull moving on a path, with a strength s (m²/s) scaling its wave source s·f.

    A source of the simulation (``wavephys.simulation.Source``): after each step's cutoff
    it adds the waves it made over [t, t + Δt] on its patch, by the model's
    ``ship_method``.

    Parameters
    ----------
    hull : Hull
        The footprint f.
    path : Path
        Its pose over time.
    strength : float
        s, m²/s (any real number).

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 2 (docs/physics.md §1.3).
    """

    hull: Hull
    path: Path
    strength: float = 0.01

    def __post_init__(self):
        check_instance("hull", self.hull, Hull, "wavephys.physics.ship_waves.Hull")
        check_instance("path", self.path, Path, "wavephys.physics.ship_waves.Path")
        check_scalar("strength", self.strength)

    # -- the simulation's source protocol -------------------------------------------
    def check(self, model) -> None:
        """Host-side checks: the patch fits the grid (nothing else is known before the step)."""
        grid = model_grid(model)
        if getattr(model, "tank", None) is not None:
            raise ValueError(f"ships in a tank smaller than the grid (tank={model.tank}) are not supported yet: "
                             f"their patch would fold at the grid's edges, not the tank's walls")
        if model.ship_patch > grid.n:
            raise ValueError(f"ship_patch {model.ship_patch} must not exceed the grid's n = {grid.n}")

    def add(self, model, fields, t: float):
        """Add this step's ship waves to the stacked (φ, χ) ``fields`` (donated), after the cutoff.

        Refuses a Δt whose patch leak (:func:`patch_leak`) exceeds ``model.leak_tolerance``.
        """
        half, n = model.ship_patch // 2, model.grid.n
        leak = _leak_at_speed(self, model, t)
        if leak > model.leak_tolerance:
            raise ValueError(f"dt = {float(model.dt)} s is too large for the ship patch of {2 * half} points: "
                             f"{leak:.2g} of the new waves leak past it (leak_tolerance {model.leak_tolerance}); "
                             f"lower dt or raise ship_patch")
        walls = getattr(model, "walls", ())
        if not walls:
            return add_ship_waves(fields, self, model.grid, model.water, t, float(model.dt), half, model.ship_method,
                                  interior=(model.margin, n - model.margin))
        m = model.margin
        rows = (None if "bottom" in walls else m, None if "top" in walls else n - m)
        cols = (None if "left" in walls else m, None if "right" in walls else n - m)
        return add_ship_waves(fields, self, model.grid, model.water, t, float(model.dt), half, model.ship_method,
                              interior=(rows, cols), mirror=model.wall_axes)


def _leak_at_speed(ship: Ship, model, t: float) -> float:
    """patch_leak of the ship over this step, cached by hull, speed and the model's numbers."""
    p0, p1 = ship.path(t), ship.path(t + float(model.dt))
    speed = round(math.hypot(p1[0] - p0[0], p1[1] - p0[1]) / float(model.dt), 6)
    args = (ship.hull, speed, float(model.dt), model.ship_patch // 2, model.grid.n, float(model.grid.length),
            model.water, model.ship_method)
    try:
        return _leak_cached(*args)
    except TypeError:  # unhashable values (arrays in Water): measure without the cache
        return _leak_cached.__wrapped__(*args)


@lru_cache(maxsize=256)
def _leak_cached(hull, speed, dt, half, n, length, water, method):
    probe = Ship(hull, straight_path((0.0, 0.0), (speed, 0.0)), 1.0)
    return patch_leak(probe, Grid(n, length), water, 0.0, dt, half, method)


_SHIP = Instance(Ship, "wavephys.physics.ship_waves.Ship")


# -- patch computation -----------------------------------------------------------------
@validate(hull=Instance(Hull, "wavephys.physics.ship_waves.Hull"), patch=GRID, center=Array(shape=(2,), ndim=1),
          pose=Array(shape=(3,), ndim=1))
def hull_spectrum(hull: Hull, patch: Grid, center, pose):
    """FFT of the hull at ``pose`` = (x, y, heading) on a patch grid centred at ``center``, blurred.

    Pure ``jnp`` (poses may be traced).

    Parameters
    ----------
    hull : Hull
    patch : Grid
        The patch grid (n_p × n_p points).
    center : array_like (2,)
        (x, y) of the patch centre in the grid frame, m.
    pose : array_like (3,)
        (x, y, heading) of the hull, m, m, rad.

    Returns
    -------
    jax.Array (n_p, n_p), complex
        ``fft2`` of f, multiplied by exp(−k²·blur²/2) when ``hull.blur`` > 0; dimensionless
        (DFT convention).

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 2 (docs/physics.md §1.3).
    """
    x, y = patch.mesh()
    dxp, dyp = pose[0] - center[0], pose[1] - center[1]
    c, s = jnp.cos(pose[2]), jnp.sin(pose[2])
    u = c * (x - dxp) + s * (y - dyp)
    v = -s * (x - dxp) + c * (y - dyp)
    spec = jnp.fft.fft2(hull.evaluate(u, v))
    if hull.blur > 0:
        spec = spec * jnp.exp(-0.5 * patch.wavenumber_magnitude() ** 2 * hull.blur**2)
    return spec


@validate(patch=GRID, water=WATER, f0_hat=field_of("patch", complex_ok=True), f1_hat=field_of("patch", complex_ok=True),
          velocity=_VELOCITY, dt=_DT)
def ship_waves_kernels(f0_hat, f1_hat, patch: Grid, water: Water, velocity, dt):
    """New waves F⁻¹[f̂_t·M1 + f̂_{t+Δt}·M2] per unit strength (Loviscach 2003, eq. 2), m²/s per m²/s.

    ``f0_hat``, ``f1_hat``: FFTs of the hull at the step's start and end on ``patch``;
    ``velocity`` (m/s, (vx, vy)) its straight motion over the step, ``dt`` the step (s).

    Parameters
    ----------
    f0_hat, f1_hat : array_like (2M, 2M), complex
        FFTs of the hull at the step's start and end on ``patch`` (:func:`hull_spectrum`),
        dimensionless (DFT convention).
    patch : Grid
        The 2M × 2M patch grid.
    water : Water
    velocity : array_like (2,)
        (vx, vy), the hull's straight motion over the step, m/s, each in [−1e4, 1e4].
    dt : float
        Δt, s, in (0, 1e4].

    Returns
    -------
    jax.Array (2M, 2M), complex
        The new waves per unit strength, m²/s per m²/s.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 2 (docs/physics.md §1.3).
    """
    kv, omega = _k_dot_v_omega(patch, water, velocity)
    m1, m2 = _multipliers(kv, omega, dt, resonance_quotients)
    return jnp.fft.ifft2(f0_hat * m1 + f1_hat * m2)


@validate(patch=GRID, water=WATER, f0_hat=field_of("patch", complex_ok=True), f1_hat=field_of("patch", complex_ok=True),
          velocity=_VELOCITY, dt=_DT)
def ship_waves_impulses(f0_hat, f1_hat, patch: Grid, water: Water, velocity, dt):
    """The naive way: the change f_{t+Δt} − f_t added at once, a row of dropped stones
    without the time integration (the paper's warning; documented failure).

    Parameters
    ----------
    f0_hat, f1_hat : array_like (2M, 2M), complex
        FFTs of the hull at the step's start and end on ``patch`` (:func:`hull_spectrum`),
        dimensionless (DFT convention).
    patch : Grid
        The 2M × 2M patch grid.
    water : Water
    velocity : array_like (2,)
        (vx, vy), the hull's straight motion over the step, m/s, each in [−1e4, 1e4].
    dt : float
        Δt, s, in (0, 1e4]. ``water``, ``velocity`` and ``dt`` are checked but not used: the
        signature is that of :func:`ship_waves_kernels`.

    Returns
    -------
    jax.Array (2M, 2M), complex
        F⁻¹[f̂_{t+Δt} − f̂_t], per unit strength.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 2 (docs/physics.md §1.3).
    """
    return jnp.fft.ifft2(f1_hat - f0_hat)


SHIP_METHODS = Methods("ship waves", kernels=ship_waves_kernels, impulses=ship_waves_impulses)
"""How a moving hull makes waves, by name."""


def _patch_place(ship: Ship, grid: Grid, t: float, dt: float, half: int):
    """Poses at t and t + Δt, and the patch (row0, col0, centre) that holds the hull's motion."""
    p0, p1 = ship.path(t), ship.path(t + dt)
    length = float(grid.length)
    for label, (x, y, _) in (("t", p0), ("t + dt", p1)):
        if abs(x) > length or abs(y) > length:
            raise ValueError(f"the ship's path puts it at ({x:.4g}, {y:.4g}) m at {label} = "
                             f"{t if label == 't' else t + dt:.4g} s, more than a grid length L = {length:.4g} m "
                             f"from the centre")
    reach = 0.5 * math.hypot(p1[0] - p0[0], p1[1] - p0[1]) + ship.hull.radius
    if reach > half * float(grid.dx):
        raise ValueError(f"the hull and its motion over dt reach {reach:.3g} m from the patch centre, more than "
                         f"the patch half-size {half * float(grid.dx):.3g} m: use a larger patch or a smaller dt")
    if 2 * half > grid.n:
        raise ValueError(f"the patch (2·half = {2 * half}) must not be larger than the grid ({grid.n})")
    r0, c0, center = grid.window(0.5 * (p0[0] + p1[0]), 0.5 * (p0[1] + p1[1]), half)
    return p0, p1, r0, c0, center


@validate(ship=_SHIP, grid=GRID, water=WATER, t=REAL, dt=_DT, half=Int(lo=2), method=Choice(("kernels", "impulses")))
def ship_patch_waves(ship: Ship, grid: Grid, water: Water, t: float, dt: float, half: int,
                     method: str = "kernels"):
    """Complex waves the ship adds over [t, t + Δt], on its 2M × 2M patch (M = ``half``).

    ``method`` is a name in :data:`SHIP_METHODS`.

    Parameters
    ----------
    ship : Ship
    grid : Grid
    water : Water
    t : float
        Start of the step, s.
    dt : float
        Δt, s, in (0, 1e4].
    half : int
        M, the patch's half-size, points, ≥ 2 (2M ≤ n).
    method : {"kernels", "impulses"}
        A name in :data:`SHIP_METHODS`.

    Returns
    -------
    (waves, (row0, col0))
        The ``(2M, 2M)`` complex field (m²/s) and the grid index of its first row and column
        (wrap them modulo n to add it to the field).

    Raises
    ------
    ValueError
        If the ship is more than a grid length from the centre, or the hull and its motion
        over Δt do not fit in the patch.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 2 (docs/physics.md §1.3).
    """
    p0, p1, r0, c0, center = _patch_place(ship, grid, t, dt, half)
    kernel = _kernels(ship.hull, half, float(grid.dx), water, method)[0]
    waves = kernel(jnp.asarray(center), jnp.asarray(p0), jnp.asarray(p1), dt, ship.strength)
    return waves, (r0, c0)


@validate(ship=_SHIP, grid=GRID, water=WATER, t=REAL, dt=_DT, half=Int(lo=2), method=Choice(("kernels", "impulses")),
          fields=Array(shape=lambda a: (2, a["grid"].n, a["grid"].n), min_ndim=3))
def add_ship_waves(fields, ship: Ship, grid: Grid, water: Water, t: float, dt: float, half: int,
                   method: str = "kernels", interior=None, mirror=(False, False)):
    """Add the ship's new waves over [t, t + Δt] to a stacked (Re ψ, Im ψ) field in one program.

    ``fields`` is donated (updated in place): do not use the array passed in afterwards.
    The same waves as :func:`ship_patch_waves`, computed and added (indices wrapping)
    without a round trip through Python; ``interior`` = (lo, hi) restricts the patch to
    rows and columns in [lo, hi) (ValueError otherwise).

    Parameters
    ----------
    fields : jax.Array (..., 2, n, n)
        Stacked (Re ψ, Im ψ) = (φ, χ), m²/s; donated.
    ship : Ship
    grid : Grid
    water : Water
    t : float
        Start of the step, s.
    dt : float
        Δt, s, in (0, 1e4].
    half : int
        M, the patch's half-size, points, ≥ 2 (2M ≤ n).
    method : {"kernels", "impulses"}
        A name in :data:`SHIP_METHODS`.
    interior : (int, int) or ((lo, hi), (lo, hi)), optional
        (lo, hi): the rows and columns the patch must stay within; or one (lo, hi) for the
        rows and one for the columns, where None leaves that end unchecked (a wall).
    mirror : (bool, bool)
        (x, y): fold the patch's part beyond the domain's ends back in, mirrored, along these
        axes (reflecting walls at both ends: the image method, docs/physics.md §1.11) instead
        of wrapping it (periodic).

    Returns
    -------
    jax.Array
        ``fields`` with the waves added, same shape and dtype, m²/s.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 2 (docs/physics.md §1.3).
    """
    p0, p1, r0, c0, center = _patch_place(ship, grid, t, dt, half)
    if not isinstance(mirror, (tuple, list)) or not all(isinstance(m, (bool, np.bool_)) for m in mirror):
        raise TypeError(f"mirror must be a pair (x, y) of bools, got {mirror!r}")
    if len(mirror) != 2:
        raise ValueError(f"mirror must be a pair (x, y) of bools, got {len(mirror)} values")
    mirror = tuple(bool(m) for m in mirror)
    if interior is not None:
        rows, cols = _interior(interior)
        for name, start, (lo, hi) in (("rows", r0, rows), ("columns", c0, cols)):
            if (lo is not None and start < lo) or (hi is not None and start + 2 * half > hi):
                raise ValueError(f"the ship patch at {name} {start}…{start + 2 * half} leaves the visible interior "
                                 f"[{lo}, {hi}): keep ships inside it")
    add = _kernels(ship.hull, half, float(grid.dx), water, method, mirror)[1]
    return add(fields, jnp.asarray(center), jnp.asarray(p0), jnp.asarray(p1), dt, ship.strength, r0, c0)


def _interior(interior):
    """((row lo, row hi), (col lo, col hi)) from one (lo, hi) pair or a pair of them (None: unchecked end)."""
    ok = lambda v: v is None or (isinstance(v, (int, np.integer)) and not isinstance(v, bool))
    pair = lambda p: isinstance(p, (tuple, list)) and len(p) == 2 and all(ok(v) for v in p)
    if pair(interior) and all(v is not None for v in interior):
        return tuple(interior), tuple(interior)
    if isinstance(interior, (tuple, list)) and len(interior) == 2 and all(pair(p) for p in interior):
        return tuple(interior[0]), tuple(interior[1])
    raise TypeError(f"interior must be (lo, hi) or ((row lo, row hi), (column lo, column hi)) of ints or None, "
                    f"got {interior!r}")


def _kernels(hull, half, dx, water, method, mirror=(False, False)):
    try:
        return _patch_kernel(hull, half, dx, water, method, mirror)
    except TypeError:  # unhashable values (arrays in Water): compile for this call only
        return _patch_kernel.__wrapped__(hull, half, dx, water, method, mirror)


def _fold(index, n: int, mirror: bool):
    """Indices wrapped into [0, n) (periodic), or folded back in, mirrored (walls at both ends)."""
    if not mirror:
        return index % n
    index = index % (2 * n)
    return jnp.where(index < n, index, 2 * n - 1 - index)


@lru_cache(maxsize=64)
def _patch_kernel(hull: Hull, half: int, dx: float, water: Water, method: str, mirror=(False, False)):
    """The compiled patch computation for one hull and patch (shared by equal hulls)."""
    patch = Grid(2 * half, 2 * half * dx)
    make = SHIP_METHODS[method]

    @jax.jit
    def kernel(center, p0, p1, dt, strength):
        f0, f1 = hull_spectrum(hull, patch, center, p0), hull_spectrum(hull, patch, center, p1)
        return make(f0, f1, patch, water, (p1[:2] - p0[:2]) / dt, dt) * strength

    @partial(jax.jit, donate_argnums=0)  # update the field in place, no 2·n² copy
    def add(fields, center, p0, p1, dt, strength, r0, c0):
        waves = kernel(center, p0, p1, dt, strength)
        n, m = fields.shape[-1], waves.shape[-1]
        rows = _fold(r0 + jnp.arange(m), n, mirror[1])
        cols = _fold(c0 + jnp.arange(m), n, mirror[0])
        both = jnp.stack([waves.real, waves.imag]).astype(fields.dtype)
        return fields.at[..., rows[:, None], cols[None, :]].add(both)

    return kernel, add


@validate(ship=_SHIP, grid=GRID, water=WATER, t=REAL, dt=_DT, half=Int(lo=2), method=Choice(("kernels", "impulses")))
def patch_leak(ship: Ship, grid: Grid, water: Water, t: float, dt: float, half: int,
               method: str = "kernels") -> float:
    """Fraction of one step's new waves a 2M × 2M patch gets wrong.

    The relative energy of the difference from the same waves computed on a patch twice as
    large (4M × 4M; the whole grid when 4M > n, and 0 when the patch already is the whole
    grid).

    Parameters
    ----------
    ship : Ship
    grid : Grid
    water : Water
    t : float
        Start of the step, s.
    dt : float
        Δt, s, in (0, 1e4].
    half : int
        M, the patch's half-size, points, ≥ 2 (2M ≤ n).
    method : {"kernels", "impulses"}
        A name in :data:`SHIP_METHODS`.

    Returns
    -------
    float
        Relative energy, dimensionless, ≥ 0; 1 when the hull itself does not fit the patch.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 2 (docs/physics.md §1.3).
    """
    try:
        small, (r0, c0) = ship_patch_waves(ship, grid, water, t, dt, half, method)
    except ValueError:
        return 1.0  # the hull itself does not fit: everything is missed
    big_half = min(2 * half, grid.n // 2)
    if big_half <= half:
        return 0.0  # the patch is the whole periodic grid: nothing falls outside it
    big, (r1, c1) = ship_patch_waves(ship, grid, water, t, dt, big_half, method)
    big_on_small = big[r0 - r1:r0 - r1 + 2 * half, c0 - c1:c0 - c1 + 2 * half]
    total = float(jnp.sum(jnp.abs(big) ** 2))
    inside = float(jnp.sum(jnp.abs(small - big_on_small) ** 2))
    outside = total - float(jnp.sum(jnp.abs(big_on_small) ** 2))
    return (inside + max(outside, 0.0)) / total if total > 0 else 0.0


@validate(ship=_SHIP, grid=GRID, water=WATER, half=Int(lo=2), tolerance=Real(lo=0.0, hi=1.0, lo_open=True, hi_open=True),
          lo=Real(lo=0.0, hi=1e4, lo_open=True), hi=Real(lo=0.0, hi=1e4, lo_open=True), iterations=Int(lo=1, hi=60))
def max_patch_dt(ship: Ship, grid: Grid, water: Water, half: int, tolerance: float = 1e-3,
                 lo: float = 1e-4, hi: float = 10.0, iterations: int = 20) -> float:
    """The largest Δt (s) whose :func:`patch_leak` stays below ``tolerance`` (bisection in log Δt).

    The leak is measured at t = 0 with the ``"kernels"`` method.

    Parameters
    ----------
    ship : Ship
    grid : Grid
    water : Water
    half : int
        M, the patch's half-size, points, ≥ 2.
    tolerance : float
        Largest leak, in (0, 1).
    lo, hi : float
        The bracket of Δt searched, s, each in (0, 1e4], hi > lo.
    iterations : int
        Bisection steps, 1 … 60.

    Returns
    -------
    float
        Δt, s; ``hi`` if the leak stays below ``tolerance`` there.

    Raises
    ------
    ValueError
        If the patch leaks more than ``tolerance`` even at Δt = ``lo``.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 2 (docs/physics.md §1.3).
    """
    if hi <= lo:
        raise ValueError(f"hi must be larger than lo = {lo} s, got {hi}")
    if patch_leak(ship, grid, water, 0.0, lo, half) > tolerance:
        raise ValueError(f"the patch of half-size {half} leaks more than {tolerance} even at Δt = {lo} s")
    if patch_leak(ship, grid, water, 0.0, hi, half) <= tolerance:
        return hi
    a, b = math.log(lo), math.log(hi)
    for _ in range(iterations):
        m = 0.5 * (a + b)
        a, b = (m, b) if patch_leak(ship, grid, water, 0.0, math.exp(m), half) <= tolerance else (a, m)
    return math.exp(a)
