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
capillarity and finite depth all enter through ω(k) and K(k) (docs/physics.md §1.1). At U = 0 it
reduces to the hydrostatic depression η = −p/(ρg) for a broad source.

Kelvin's result for deep water, gravity only: the wake is confined to a wedge of
half-angle arcsin(1/3) = 19.47° whose edge (the cusp line) carries the largest
amplitude for a point source; transverse waves on the track have wavelength 2πU²/g.
For sources that are not small against 2πU²/g the angle of maximum amplitude shrinks
(Rabaud & Moisy 2013: ∝ 1/Fr at large Froude number). Measuring angles from any height
field is the harness's job: :func:`wavephys.harness.wake.wake_angle`.

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
shape of the source; that is what ``wake_angle(..., method="cusp")`` measures.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import partial

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.inputs import check_array, check_choice, check_instance, check_int, check_scalar
from wavephys.physics.dispersion import (K_MAX, angular_frequency, group_speed, min_phase_speed, phase_speed,
                                         surface_operator)
from wavephys.physics.heights import height_multiplier
from wavephys.core.grid import Grid
from wavephys.core.water import Water

__all__ = ["GaussianPressure", "HullSource", "steady_wake", "KELVIN_ANGLE", "transverse_wavelength", "CuspLine",
           "cusp_line", "stationary_wavenumber", "froude_number", "gaussian_size", "wake_envelope", "wake_surface",
           "mach_like_angle"]

KELVIN_ANGLE = math.degrees(math.asin(1.0 / 3.0))
"""Kelvin's wake half-angle for deep-water gravity waves, degrees (19.47°)."""


def transverse_wavelength(speed, water: Water = Water(sigma=0.0)):
    """Deep-water gravity wavelength of the transverse waves on the track, 2πU²/g, m.

    Parameters
    ----------
    speed : float
        U, m/s, > 0.
    water : Water
        Uses g (default: gravity only, σ = 0).

    Returns
    -------
    float
        2πU²/g, m.
    """
    check_scalar("speed", speed, lo=0.0, lo_open=True)
    check_instance("water", water, Water, "wavephys.Water")
    return 2 * math.pi * speed**2 / float(water.g)


@dataclass(frozen=True)
class CuspLine:
    """The outer edge of a steady wake, as found by :func:`cusp_line`.

    Ray ``angle`` (degrees) behind the source, carried by waves of wavenumber ``wavenumber``
    (rad/m) whose crests make ``wave_angle`` (degrees, between wavevector and track).

    Parameters
    ----------
    angle : float
        φ, the half-angle of the wake's edge behind the source, degrees.
    wavenumber : float
        k_c of the waves along it, rad/m.
    wave_angle : float
        θ between their wavevector and the track, degrees.
    """

    angle: float
    wavenumber: float
    wave_angle: float


def stationary_wavenumber(target_speed, water: Water):
    """Gravity-branch k (rad/m) with phase speed c(k) = ``target_speed``.

    ``target_speed`` in m/s (array; NaN where none exists): the waves that stand still behind a
    source whose speed along their wavevector is the target. Bisection in log k, 80 steps
    (float64).

    Parameters
    ----------
    target_speed : array_like
        c, m/s, ≥ 0.
    water : Water
        Any depth and surface tension.

    Returns
    -------
    numpy.ndarray
        k, rad/m, float64, shape of ``target_speed``; NaN where no gravity-branch wave has that
        speed (at or below c_min, at or above the long-wave speed, or past :data:`K_MAX`).
    """
    check_array("target_speed", target_speed, lo=0.0)
    check_instance("water", water, Water, "wavephys.Water")
    target = np.asarray(target_speed, np.float64)
    g = float(water.g)
    if float(water.sigma) > 0:
        c_min, k_hi = min_phase_speed(water)
        k_hi = k_hi if k_hi > 0 else None
    else:
        c_min, k_hi = 0.0, None
    if k_hi is None:  # no capillary minimum: the speed falls without bound (or to c_min at k = 0)
        k_hi = np.minimum(1e6 * g / np.maximum(target, 1e-12) ** 2, K_MAX)
    lo = np.full(target.shape, math.log(min(1e-9 * g / max(float(np.max(target)), 1e-12) ** 2, 1e-3 * K_MAX)))
    hi = np.log(np.broadcast_to(k_hi, target.shape).astype(np.float64))
    k = _bisect_log_k(lo, hi, target, water)
    c_long = phase_speed(jnp.asarray(0.0), water)
    none = (target <= c_min) | (target >= float(c_long)) | (k >= 0.999 * K_MAX)  # past the continuum limit
    return np.where(none, np.nan, k)


def _bisect_log_k(lo, hi, target, water: Water):
    """80 bisection steps in log k for c(k) = target (c falling with k): one compiled loop, float64.

    Flattened inputs are padded to a power-of-two length (at least 64) so that calls of
    many sizes share a handful of compilations; one compilation per distinct ``water``.
    """
    shape = target.shape
    size = max(64, 1 << (max(int(target.size), 1) - 1).bit_length())
    pad = lambda a, fill: np.concatenate([np.ravel(a), np.full(size - a.size, fill, np.float64)])
    with jax.enable_x64(True):
        lo_, hi_ = _bisect_steps(pad(lo, 0.0), pad(hi, 1.0), pad(target, 1.0), water)
        k = np.exp(0.5 * (np.asarray(lo_) + np.asarray(hi_)))
    return k[:target.size].reshape(shape)


@partial(jax.jit, static_argnames=("water",))
def _bisect_steps(lo, hi, target, water: Water):
    def step(_, bounds):
        lo, hi = bounds
        mid = 0.5 * (lo + hi)
        faster = phase_speed(jnp.exp(mid), water) > target  # on the gravity branch c falls with k
        return jnp.where(faster, mid, lo), jnp.where(faster, hi, mid)

    return jax.lax.fori_loop(0, 80, step, (lo, hi))


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

    Returns
    -------
    CuspLine
        The edge's ray angle φ (degrees), its wavenumber k_c (rad/m) and wave angle θ (degrees).

    Raises
    ------
    ValueError
        If no stationary gravity wave exists at ``speed`` (below c_min): there is no wake.

    References
    ----------
    Havelock (finite depth widens the wedge), as cited in docs/physics.md §1.3.
    """
    check_scalar("speed", speed, lo=0.0, lo_open=True)
    check_instance("water", water, Water, "wavephys.Water")
    samples = check_int("samples", samples, lo=3, hi=10**6)
    theta = np.linspace(0.0, math.pi / 2, samples + 2)[1:-1]
    k = stationary_wavenumber(speed * np.cos(theta), water)
    k = np.where(k <= K_MAX, k, np.nan)  # waves shorter than the continuum limit do not count
    if not np.isfinite(k).any():
        raise ValueError(f"speed {speed} m/s: no stationary gravity wave (below c_min = "
                         f"{min_phase_speed(water)[0]:.4g} m/s?), so there is no wake")
    with jax.enable_x64(True):  # the maximum is flat: float32 noise would move it
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
            kk = float(stationary_wavenumber(np.array([speed * math.cos(t)]), water)[0])
            with jax.enable_x64(True):
                cgt = float(group_speed(jnp.asarray(kk), water))
            return CuspLine(math.degrees(math.atan2(cgt * math.sin(t), speed - cgt * math.cos(t))), kk,
                            math.degrees(t))
    return CuspLine(math.degrees(float(phi[i])), float(kk), math.degrees(float(t)))


@dataclass(frozen=True)
class GaussianPressure:
    """Surface pressure p(x) = p0·exp(−|x − x_s|²/(2σ²)) (Pa), x_s at the origin (0, 0).

    Parameters
    ----------
    amplitude : float
        p0, Pa (positive pushes the surface down).
    size : float
        σ, m, > 0 (resolved: ≥ the grid spacing).

    References
    ----------
    A. Darmon, M. Benzaquen & E. Raphaël (2014). Kelvin wake pattern at large Froude numbers.
    *J. Fluid Mech.* 738, R3 (the Gaussian source, :func:`froude_number`).
    """

    amplitude: float = 100.0
    size: float = 0.1

    def __post_init__(self):
        check_scalar("amplitude", self.amplitude)
        check_scalar("size", self.size, lo=0.0, lo_open=True)

    def spectrum(self, grid: Grid):
        """DFT of p on the grid (Pa per point, DFT convention), full spectrum (n, n)."""
        check_instance("grid", grid, Grid, "wavephys.Grid")
        k2 = grid.wavenumber_magnitude() ** 2
        ky, kx = grid.wavenumbers()
        return ((self.amplitude * 2 * jnp.pi * self.size**2 / grid.dx**2) * jnp.exp(-0.5 * k2 * self.size**2)
                * grid.source_phase(0.0, 0.0))


@dataclass(frozen=True)
class HullSource:
    """The moving-hull source of Loviscach's ship kernels, as a steady-wake forcing.

    A hull f (``wavephys.ship_waves.Hull``) of strength s (m²/s) moving at U in +x feeds
    ψ at the rate ∂(s f)/∂t = −s U ∂f/∂x; as a pressure, p = ρ s U ∂f/∂x (a dipole).
    Use it to compare :class:`~wavephys.simulation.Simulation` ships with their steady wake.

    Parameters
    ----------
    hull : Hull
        A :class:`wavephys.physics.ship_waves.Hull`, the footprint f (dimensionless).
    strength : float
        s, m²/s (any real number).

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 2.
    """

    hull: object
    strength: float = 0.01

    def __post_init__(self):
        from wavephys.physics.ship_waves import Hull

        check_instance("hull", self.hull, Hull, "wavephys.physics.ship_waves.Hull")
        check_scalar("strength", self.strength)

    def forcing(self, grid: Grid, water: Water, speed: float):
        """Its source spectrum at ``speed`` (m/s, > 0) on ``grid``: ψ̂ rate, m²/s² per point."""
        from wavephys.physics.ship_waves import hull_spectrum

        check_instance("grid", grid, Grid, "wavephys.Grid")
        check_instance("water", water, Water, "wavephys.Water")
        check_scalar("speed", speed, lo=0.0, lo_open=True)
        ky, kx = grid.wavenumbers()
        # sampled on the grid's own points with the hull at (0, 0): the DFT of :meth:`Grid.source_phase`
        f_hat = hull_spectrum(self.hull, grid, (0.0, 0.0), (0.0, 0.0, 0.0))
        return -1j * kx * speed * self.strength * f_hat


def froude_number(speed, size, water: Water = Water(sigma=0.0)) -> float:
    """Froude number Fr = U/sqrt(g·b) of a :class:`GaussianPressure` of size σ moving at U.

    The length is b = π·sqrt(2)·σ, the width in p0·exp(−π²r²/b²) = p0·exp(−r²/(2σ²)), the
    form Darmon, Benzaquen & Raphaël (2014) use for an axisymmetric source (docs/physics.md
    §1.3). ``speed`` U in m/s (> 0), ``size`` σ in m (> 0).

    Parameters
    ----------
    speed : float
        U, m/s, > 0.
    size : float
        σ, m, > 0.
    water : Water
        Uses g (default: gravity only, σ = 0).

    Returns
    -------
    float
        Fr, dimensionless.

    References
    ----------
    A. Darmon, M. Benzaquen & E. Raphaël (2014). Kelvin wake pattern at large Froude numbers.
    *J. Fluid Mech.* 738, R3.
    """
    check_scalar("speed", speed, lo=0.0, lo_open=True)
    check_scalar("size", size, lo=0.0, lo_open=True)
    check_instance("water", water, Water, "wavephys.Water")
    return float(speed) / math.sqrt(float(water.g) * math.pi * math.sqrt(2.0) * float(size))


def gaussian_size(froude, speed, water: Water = Water(sigma=0.0)) -> float:
    """The size σ (m) of the :class:`GaussianPressure` that has Froude number ``froude`` at ``speed``.

    ``speed`` in m/s: the inverse of :func:`froude_number`, σ = U²/(g·Fr²·π·sqrt(2)).

    Parameters
    ----------
    froude : float
        Fr, dimensionless, > 0.
    speed : float
        U, m/s, > 0.
    water : Water
        Uses g (default: gravity only, σ = 0).

    Returns
    -------
    float
        σ, m.

    References
    ----------
    A. Darmon, M. Benzaquen & E. Raphaël (2014). Kelvin wake pattern at large Froude numbers.
    *J. Fluid Mech.* 738, R3.
    """
    check_scalar("froude", froude, lo=0.0, lo_open=True)
    check_scalar("speed", speed, lo=0.0, lo_open=True)
    check_instance("water", water, Water, "wavephys.Water")
    return float(speed) ** 2 / (float(water.g) * float(froude) ** 2 * math.pi * math.sqrt(2.0))


def mach_like_angle(froude) -> float:
    """Rabaud & Moisy's (2013) large-Froude wake angle, degrees: α = 1/(2·sqrt(2π)·Fr) rad.

    The ray of the longest divergent waves a source of length b makes (k ≈ 2π/b): for
    θ → 90°, tan φ ≈ 1/(2 tan θ) and k = g sec²θ/U², so φ ≈ sqrt(g/k)/(2U). Valid for
    Fr ≳ 0.6 (below, Kelvin's 19.47°); a scaling law, not an exact result.

    Parameters
    ----------
    froude : float
        Fr (as :func:`froude_number`), dimensionless, > 0.

    Returns
    -------
    float
        α, degrees.

    References
    ----------
    M. Rabaud & F. Moisy (2013). Ship wakes: Kelvin or Mach angle? *Phys. Rev. Lett.* 110.
    """
    check_scalar("froude", froude, lo=0.0, lo_open=True)
    return math.degrees(1.0 / (2.0 * math.sqrt(2.0 * math.pi) * float(froude)))


def _stationary_waves(speed, water: Water, t):
    """Per wave direction t = tan θ: stationary wavenumber k₀ (rad/m, NaN where none) and the
    residue weight k₀·H(k₀)/|c_g(k₀) − U cos θ| (s/m·rad/m ...) of the far-field integral."""
    cos_t = 1.0 / np.sqrt(1.0 + t * t)
    k0 = stationary_wavenumber(speed * cos_t, water)
    ok = np.isfinite(k0)
    kk = jnp.asarray(np.where(ok, k0, 1.0))
    h = np.asarray(height_multiplier(kk, water), np.float64)
    cg = np.asarray(group_speed(kk, water), np.float64)
    slip = np.abs(cg - speed * cos_t)
    weight = np.where(ok & (slip > 0), np.where(ok, k0, 0.0) * h / np.where(slip > 0, slip, 1.0), 0.0)
    return np.where(ok, k0, 0.0), weight, cos_t


def wake_envelope(distance, lateral, speed, source: "GaussianPressure", water: Water = Water(sigma=0.0),
                  damping: float = 0.0):
    r"""Amplitude envelope (m) of the far-field steady wake of a Gaussian pressure source.

    The wave part of the linear steady wake (Havelock's integral over wave directions θ,
    evaluated independently of any grid): behind a source moving at U in +x,

    .. math::

        W(x, y) = -\frac{i}{2\pi\rho}\int_{-\pi/2}^{\pi/2}
            \frac{k_0 H(k_0)\,\hat p(k_0)}{|c_g(k_0) - U\cos\theta|}
            e^{i k_0 (x\cos\theta + y\sin\theta)}\,d\theta, \qquad \eta = \mathrm{Re}\,W,

    with k₀(θ) the stationary wavenumber (c(k₀) = U cos θ), H = K/ω and p̂ the source's
    Fourier transform (2πσ²p0·e^{−k²σ²/2}); |W| is the envelope, since W holds only waves
    travelling forward. Deep water, gravity only: |W| = (1/(πρg))|∫k₀²p̂e^{ik₀ϖ}dθ|, the
    model Darmon, Benzaquen & Raphaël (2014) analyse. The local (non-wave) disturbance is
    left out, so use it a few source sizes behind the source (docs/physics.md §1.3).

    Parameters
    ----------
    distance : array_like (m,)
        Distances d behind the source, m, > 0 (x = −d).
    lateral : array_like (p,)
        Offsets y across the track, m.
    speed : float
        U, m/s, > 0.
    source : GaussianPressure
    water : Water
        Any depth and surface tension (the gravity branch of the stationary waves).
    damping : float
        Rayleigh's ε, 1/s, ≥ 0 (default 0, the physical limit): with ε > 0 each wave fades as
        exp(−ε|ϖ|/|c_g − U cos θ|), ϖ = x cos θ + y sin θ, as in :func:`steady_wake`.

    Returns
    -------
    numpy.ndarray (m, p)
        |W| at (−d, y), m.

    References
    ----------
    Havelock's integral over wave directions (docs/physics.md §1.3). A. Darmon, M. Benzaquen &
    E. Raphaël (2014). Kelvin wake pattern at large Froude numbers. *J. Fluid Mech.* 738, R3.
    """
    check_array("distance", distance, ndim=1, lo=0.0, lo_open=True)
    check_array("lateral", lateral, ndim=1)
    ds, ys = np.asarray(distance, np.float64), np.asarray(lateral, np.float64)
    k0, cos_t, sin_t, w, fade = _direction_quadrature(speed, source, water, damping, float(np.max(ds)),
                                                      float(np.max(np.abs(ys), initial=0.0)))
    rows = [_envelope_section(float(d), ys, k0, cos_t, sin_t, fade, w) for d in ds]
    return np.stack([np.abs(np.asarray(r, np.complex128)) for r in rows])


def wake_surface(x, y, speed, source: "GaussianPressure", water: Water = Water(sigma=0.0), damping: float = 0.0):
    r"""The far-field steady wake W (m, complex) of a Gaussian pressure source at points (x, y); η = Re W.

    The same direction integral as :func:`wake_envelope` (whose modulus is |W|), at any points in the
    source's frame (source at the origin moving in +x, so the wake lies at x < 0), with its phase:

    .. math::

        W(x, y) = -\frac{i}{2\pi\rho}\int_{-\pi/2}^{\pi/2}
            \frac{k_0 H(k_0)\,\hat p(k_0)}{|c_g(k_0) - U\cos\theta|}
            e^{i k_0 (x\cos\theta + y\sin\theta)}\,d\theta .

    Re W is the surface elevation of the wave part of the wake (the local disturbance under the source is left
    out): the field whose largest |ζ| on arcs behind the source defines Darmon, Benzaquen & Raphaël's angle of
    maximum amplitude (:func:`wavephys.harness.wake.darmon_angle_theory`).

    Parameters
    ----------
    x, y : array_like (m,)
        Points, m, in the source's frame (x along its travel, the source at the origin); same shape, finite.
    speed : float
        U, m/s, > 0.
    source : GaussianPressure
    water : Water, optional
        Any depth and surface tension (the gravity branch of the stationary waves); default gravity only.
    damping : float, optional
        Rayleigh's ε, 1/s, >= 0 (default 0), as in :func:`wake_envelope`.

    Returns
    -------
    numpy.ndarray (m,) complex
        W at the points, m; ``W.real`` is the height.

    Raises
    ------
    ValueError
        When x and y differ in shape, or a value is out of range.

    References
    ----------
    A. Darmon, M. Benzaquen & E. Raphaël (2014). Kelvin wake pattern at large Froude numbers.
    *J. Fluid Mech.* 738, R3.

    Examples
    --------
    >>> from wavephys.physics.wake import GaussianPressure, wake_surface
    >>> w = wake_surface([-5.0], [1.0], 1.0, GaussianPressure(100.0, 0.1))
    >>> bool(abs(w[0]) > 0)
    True
    """
    check_array("x", x, ndim=1)
    check_array("y", y, ndim=1)
    xs, ys = np.asarray(x, np.float64), np.asarray(y, np.float64)
    if xs.shape != ys.shape:
        raise ValueError(f"x and y must have one shape, got {xs.shape} and {ys.shape}")
    reach = float(np.max(np.abs(xs), initial=0.0))
    k0, cos_t, sin_t, w, fade = _direction_quadrature(speed, source, water, damping, max(reach, 1e-12),
                                                      float(np.max(np.abs(ys), initial=0.0)))
    out = np.empty(xs.shape, np.complex128)
    for lo in range(0, xs.size, 4096):
        out[lo:lo + 4096] = np.asarray(_points_sum(xs[lo:lo + 4096], ys[lo:lo + 4096], k0, cos_t, sin_t, fade, w))
    return -1j * out


def _direction_quadrature(speed, source, water: Water, damping: float, reach: float, lateral: float):
    """Directions t = tan θ, their stationary wavenumbers, weights (with p̂, dθ and 1/(2πρ)) and Rayleigh fades,
    fine enough that the phase turns < 0.2 rad between directions up to ``reach`` behind and ``lateral`` across."""
    check_scalar("speed", speed, lo=0.0, lo_open=True)
    check_instance("source", source, GaussianPressure, "wavephys.physics.wake.GaussianPressure")
    check_instance("water", water, Water, "wavephys.Water")
    check_scalar("damping", damping, lo=0.0)
    sigma, rho = float(source.size), float(water.rho)
    # directions t = tan θ where the integrand matters (p̂ falls as e^{−k²σ²/2}, k₀ ∝ 1 + t²)
    t = np.linspace(-60.0, 60.0, 4001)
    k0, weight, _ = _stationary_waves(speed, water, t)
    weight = weight * np.exp(-0.5 * (k0 * sigma) ** 2) / (1.0 + t * t)
    if not np.any(weight > 0):
        raise ValueError(f"speed {speed!r} m/s: no stationary waves behind the source (below c_min?)")
    keep = np.nonzero(weight > 1e-12 * weight.max())[0]
    t_lo, t_hi = t[max(keep[0] - 1, 0)], t[min(keep[-1] + 1, t.size - 1)]
    probe = np.linspace(t_lo, t_hi, 4001)
    k0p, _, cos_p = _stationary_waves(speed, water, probe)
    turn = max(float(np.max(np.abs(np.diff(k0p * cos_p * (-reach) + k0p * probe * cos_p * sign * lateral))))
               for sign in (-1.0, 1.0))  # largest phase change per probe step, at the far corners
    count = int(min(max(2001, 4000 * turn / 0.2), 400_001))
    t = np.linspace(t_lo, t_hi, count)
    k0, weight, cos_t = _stationary_waves(speed, water, t)
    phat = 2 * math.pi * sigma**2 * float(source.amplitude) * np.exp(-0.5 * (k0 * sigma) ** 2)
    w = weight * phat / (1.0 + t * t) * (t[1] - t[0]) / (2 * math.pi * rho)  # dθ = dt/(1 + t²)
    fade = damping / _slip(speed, water, k0, cos_t)  # 1/m along ϖ (0 without damping)
    return k0, cos_t, t * cos_t, w, fade


@jax.jit
def _points_sum(x, y, k0, cos_t, sin_t, fade, w):
    """Σ_θ w·e^{i k₀ ϖ}·e^{−fade·|ϖ|} over the waves behind (ϖ < 0), at points (x, y), float32."""
    path = x[:, None] * cos_t[None, :] + y[:, None] * sin_t[None, :]
    phase = (k0[None, :] * path).astype(jnp.float32)
    amp = jnp.where(path < 0, jnp.exp(-fade[None, :] * jnp.abs(path)), 0.0).astype(jnp.float32)
    return (amp * jnp.cos(phase)) @ w.astype(jnp.float32) + 1j * ((amp * jnp.sin(phase)) @ w.astype(jnp.float32))


@jax.jit
def _envelope_section(d, ys, k0, cos_t, sin_t, fade, w):
    """Σ_θ w·e^{i k₀ ϖ}·e^{−fade·|ϖ|} over the waves behind (ϖ < 0), for one section d behind the source."""
    return _points_sum(jnp.full(ys.shape, -d, ys.dtype), ys, k0, cos_t, sin_t, fade, w)


def _slip(speed, water: Water, k0, cos_t):
    """|c_g(k₀) − U cos θ|, m/s: how fast a stationary wave's energy leaves its phase pattern."""
    cg = np.asarray(group_speed(jnp.asarray(np.where(k0 > 0, k0, 1.0)), water), np.float64)
    return np.maximum(np.abs(cg - speed * cos_t), 1e-12)


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

    Returns
    -------
    jax.Array (n, n)
        η, m, with the source at the grid's centre.
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


