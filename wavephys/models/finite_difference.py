r"""Peer method: the explicit finite-difference wave equation (Kass & Miller 1990).

.. math::

    \eta^{n+1} = (2 - d)\,\eta^n - (1 - d)\,\eta^{n-1} + C^2\,\Delta_h \eta^n,
    \qquad C = c\,\Delta t/\Delta x

with the periodic 5-point Laplacian Δ_h (grid units) and an optional damping d ∈ [0, 1)
(d = 0: the undamped scheme of Gomez 2000, used by Baboud & Décoret 2006). Every
wavelength moves at the single speed c (plus the scheme's own numerical dispersion),
so it cannot make capillary ripples or a Kelvin wake: the physics is wrong for deep
water whatever the step. Its discrete dispersion relation is

.. math::

    \sin^2(\omega\Delta t/2) = C^2\left[\sin^2(k_x\Delta x/2) + \sin^2(k_y\Delta x/2)\right],

so it is stable only for C ≤ 1/√2 (the checkerboard mode has the bracket equal to 2);
:func:`find_stability_limit` measures the boundary by bisection.
"""

from __future__ import annotations

import math

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.inputs import Array, Real, Spec, check_array, check_bool, check_int, check_scalar, validate
from wavephys.core.stepper import TwoLevelState, _TwoLevel
from wavephys.core.aliases import deprecated_function
from wavephys.models.two_level import check_levels
from wavephys.core.grid import Grid

__all__ = ["FiniteDifferenceStepper", 
    "STABILITY_LIMIT",
    "courant_number",
    "laplacian",
    "fd_step",
    "fd_run",
    "fd_angular_frequency",
    "find_stability_limit",
    "fd_moving_source",
]

MAX_STEPS = 10**6
"""Most steps :func:`fd_moving_source` runs (a bound, so that no input makes it run for days)."""

STABILITY_LIMIT = 1.0 / math.sqrt(2.0)
"""Largest stable Courant number c·Δt/Δx of the explicit 2-D 5-point scheme."""


def courant_number(speed, dt, dx):
    """C = c·Δt/Δx (dimensionless) for wave speed c (m/s), step Δt (s), spacing Δx (m).

    Parameters
    ----------
    speed : float
        c, m/s, > 0.
    dt : float
        Δt, s, > 0.
    dx : float
        Δx, m, > 0.

    Returns
    -------
    float
        C, dimensionless (the scheme is stable for C ≤ :data:`STABILITY_LIMIT`).
    """
    check_scalar("speed", speed, lo=0.0, lo_open=True)
    check_scalar("dt", dt, lo=0.0, lo_open=True)
    check_scalar("dx", dx, lo=0.0, lo_open=True)
    return speed * dt / dx


class _Level(Spec):
    """A height field (..., ny, nx) with ny, nx ≥ 3 (the 5-point stencil); with ``like``, the
    shape of that other argument."""

    def __init__(self, like=None):
        self.like = like

    def __call__(self, name, value, arguments):
        check_array(name, value, min_ndim=2)
        shape = np.shape(value)
        if min(shape[-2:]) < 3:
            raise ValueError(f"{name} must be at least 3 x 3 on its last two axes, got shape {shape}")
        if self.like is not None and shape != np.shape(arguments[self.like]):
            raise ValueError(f"{name} must have the shape of {self.like} {np.shape(arguments[self.like])}, got {shape}")
        return value


_COURANT = Real(lo=0.0, hi=10.0, lo_open=True)
_DAMPING = Real(lo=0.0, hi=1.0, hi_open=True)
_POSITIVE = Real(lo=0.0, lo_open=True)


@validate(eta=_Level())
def laplacian(eta):
    """Periodic 5-point Laplacian on the last two axes, in grid units (1/Δx² omitted).

    NumPy in → NumPy out (float64 measurements), JAX in → JAX out
    (:func:`wavephys.core.spectral.central_laplacian` at unit spacing).

    Parameters
    ----------
    eta : array_like (..., ny, nx)
        Height field, m, periodic, ny, nx ≥ 3.

    Returns
    -------
    numpy.ndarray or jax.Array (..., ny, nx)
        Δ_h η, m (per grid cell², the 1/Δx² omitted).
    """
    from wavephys.core.spectral import central_laplacian

    return central_laplacian(eta, 1.0)


@validate(eta=_Level(), eta_prev=_Level(like="eta"), courant=_COURANT, damping=_DAMPING)
def fd_step(eta, eta_prev, courant, damping=0.0):
    """One explicit step: returns η^{n+1} from η^n (``eta``) and η^{n−1} (``eta_prev``), m.

    ``courant`` C = cΔt/Δx in (0, 10] (stable up to 1/√2), ``damping`` d in [0, 1).

    Parameters
    ----------
    eta : array_like (..., ny, nx)
        η^n, m, ny, nx ≥ 3.
    eta_prev : array_like (..., ny, nx)
        η^{n−1}, m, the shape of ``eta``.
    courant : float
        C = cΔt/Δx, in (0, 10] (stable up to :data:`STABILITY_LIMIT` = 1/√2).
    damping : float
        d, in [0, 1) (0: undamped).

    Returns
    -------
    array_like (..., ny, nx)
        η^{n+1}, m.

    References
    ----------
    Kass & Miller (1990); Gomez (2000), the undamped scheme, as used by L. Baboud & X. Décoret (2006).
    Realistic water volumes in real-time. *Eurographics Workshop on Natural Phenomena*
    (docs/physics.md §1.7).
    """
    return (2.0 - damping) * eta - (1.0 - damping) * eta_prev + courant**2 * laplacian(eta)


def _fd_history(eta, eta_prev, courant, steps: int, damping=0.0, check_stability: bool = True):
    """Run ``steps`` steps; returns (η^{N}, η^{N−1}, stacked heights of every step).

    Parameters
    ----------
    eta, eta_prev : array_like
        Heights at the last two times, m, same shape ``(..., ny, nx)``.
    courant : float
        C = cΔt/Δx, > 0. With ``check_stability`` (default) C > 1/√2 is rejected; pass
        ``check_stability=False`` to explore the unstable side (it blows up).
    steps : int
        ≥ 1.
    damping : float
        d in [0, 1).
    check_stability : bool
        Reject C > 1/√2 (:data:`STABILITY_LIMIT`), default True.

    Returns
    -------
    (eta, eta_prev, history)
        η^N and η^{N−1}, m, shape of ``eta``, and the heights of every step, m, stacked on a
        leading axis of length ``steps``.

    References
    ----------
    Kass & Miller (1990); Gomez (2000), the undamped scheme, as used by L. Baboud & X. Décoret (2006).
    Realistic water volumes in real-time. *Eurographics Workshop on Natural Phenomena*
    (docs/physics.md §1.7).
    """
    eta, eta_prev = check_levels(eta, eta_prev)
    check_bool("check_stability", check_stability)
    steps = check_int("steps", steps, lo=1)
    stepper = FiniteDifferenceStepper(courant, 1.0, damping, check_stability=check_stability)
    end, states = stepper.trajectory(TwoLevelState(eta, eta_prev), steps)
    return end.eta, end.eta_prev, jnp.concatenate([states.eta[1:], end.eta[None]])


fd_run = deprecated_function(
    _fd_history, "fd_run", "FiniteDifferenceStepper(courant, dt).run / .advance, or .trajectory for every step")


@validate(kx=Array(), ky=Array(), speed=_POSITIVE, dt=_POSITIVE, dx=_POSITIVE)
def fd_angular_frequency(kx, ky, speed, dt, dx):
    """The scheme's own ω(k), rad/s, from its discrete dispersion relation (module doc).

    ``kx``, ``ky`` (rad/m) broadcast together. The result is NaN, by design, where the
    scheme is unstable for that mode (right-hand side > 1): there the scheme has no real ω.

    Parameters
    ----------
    kx, ky : array_like
        Wavenumber components, rad/m (broadcastable).
    speed : float
        c, m/s, > 0.
    dt : float
        Δt, s, > 0.
    dx : float
        Δx, m, > 0.

    Returns
    -------
    jax.Array
        ω, rad/s, of the broadcast shape; NaN where the mode is unstable.

    References
    ----------
    Kass & Miller (1990); Gomez (2000), the undamped scheme, as used by L. Baboud & X. Décoret (2006).
    Realistic water volumes in real-time. *Eurographics Workshop on Natural Phenomena*
    (docs/physics.md §1.7).
    """
    try:
        np.broadcast_shapes(np.shape(kx), np.shape(ky))
    except ValueError:
        raise ValueError(f"kx and ky must broadcast together, got shapes {np.shape(kx)} and {np.shape(ky)}") from None
    c2 = (speed * dt / dx) ** 2
    rhs = c2 * (jnp.sin(kx * dx / 2) ** 2 + jnp.sin(ky * dx / 2) ** 2)
    return 2.0 / dt * jnp.arcsin(jnp.sqrt(jnp.where(rhs <= 1.0, rhs, jnp.nan)))


def find_stability_limit(n: int = 32, steps: int = 400, growth: float = 10.0,
                         tolerance: float = 1e-4, seed: int = 0):
    """Measure the largest stable Courant number by bisection on a random field.

    A run is unstable when max|η| grows by more than ``growth`` in ``steps`` steps
    (random initial data excite every mode, the checkerboard included). Bisection on
    [0.5, 1] to ``tolerance`` in [1e-7, 0.1] (a bounded number of steps). Returns the
    measured boundary C* (compare with :data:`STABILITY_LIMIT` = 1/√2).

    Parameters
    ----------
    n : int
        Grid points per side, ≥ 4.
    steps : int
        Steps per trial run, ≥ 10.
    growth : float
        Growth of max|η| that counts as unstable, > 1.
    tolerance : float
        Width of the final bracket in C, in [1e-7, 0.1].
    seed : int
        Seed of the random initial field, ≥ 0.

    Returns
    -------
    float
        C*, dimensionless.

    Raises
    ------
    RuntimeError
        If C in [0.5, 1.0] does not bracket the boundary.

    References
    ----------
    Kass & Miller (1990); Gomez (2000), the undamped scheme, as used by L. Baboud & X. Décoret (2006).
    Realistic water volumes in real-time. *Eurographics Workshop on Natural Phenomena*
    (docs/physics.md §1.7).
    """
    n = check_int("n", n, lo=4)
    steps = check_int("steps", steps, lo=10)
    check_scalar("growth", growth, lo=1.0, lo_open=True)
    check_scalar("tolerance", tolerance, lo=1e-7, hi=0.1)
    seed = check_int("seed", seed, lo=0)
    eta0 = jax.random.normal(jax.random.PRNGKey(seed), (n, n))
    amp0 = float(jnp.max(jnp.abs(eta0)))

    state = TwoLevelState(eta0, eta0)

    def unstable(c):
        a = FiniteDifferenceStepper(c, 1.0, check_stability=False).trajectory(state, steps)[0].eta
        amp = float(jnp.max(jnp.abs(a)))
        return not math.isfinite(amp) or amp > growth * amp0

    lo, hi = 0.5, 1.0
    if unstable(lo) or not unstable(hi):
        raise RuntimeError("stability boundary not bracketed by C in [0.5, 1.0]")
    for _ in range(math.ceil(math.log2(0.5 / tolerance))):  # bounded: each step halves hi − lo
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if unstable(mid) else (mid, hi)
    return 0.5 * (lo + hi)


def fd_moving_source(n: int = 512, length: float = 40.0, wave_speed: float = 0.5, source_speed: float = 1.0,
                     source_size: float = 0.3, duration: float = 28.0, courant: float = 0.5):
    """The FD peer driven by a Gaussian forcing moving in +x: returns (η, grid, source x).

    A non-dispersive scheme can only make a Mach cone of half-angle asin(c/U) for a
    supersonic source (none for U < c), never Kelvin's 19.47° wake: the documented
    failure of this method for moving sources.

    Parameters
    ----------
    n : int
        Grid points per side, ≥ 16.
    length : float
        Side of the periodic domain, m, > 0.
    wave_speed : float
        c, m/s, > 0.
    source_speed : float
        U, m/s, > 0 (starts at x = −0.35·length, y = 0).
    source_size : float
        Standard deviation of the Gaussian forcing, m, > 0.
    duration : float
        Simulated time, s, > 0 (at most :data:`MAX_STEPS` steps).
    courant : float
        C = cΔt/Δx, in (0, 1/√2] (:data:`STABILITY_LIMIT`).

    Returns
    -------
    (eta, grid, x) : (jax.Array (n, n), Grid, float)
        The heights at the end (m, in the units of a unit-amplitude forcing), the grid and the
        source's final x, m.

    References
    ----------
    Kass & Miller (1990); Gomez (2000), the undamped scheme, as used by L. Baboud & X. Décoret (2006).
    Realistic water volumes in real-time. *Eurographics Workshop on Natural Phenomena*
    (docs/physics.md §1.7).
    """
    n = check_int("n", n, lo=16)
    for name, v in (("length", length), ("wave_speed", wave_speed), ("source_speed", source_speed),
                    ("source_size", source_size), ("duration", duration)):
        check_scalar(name, v, lo=0.0, lo_open=True)
    check_scalar("courant", courant, lo=0.0, hi=STABILITY_LIMIT, lo_open=True)
    grid = Grid(n, length)
    dx = length / n
    dt = courant * dx / wave_speed
    x, y = grid.mesh()
    steps = duration / dt
    if steps > MAX_STEPS:
        raise ValueError(f"duration {duration!r} s at wave_speed {wave_speed!r} m/s takes {steps:.3g} steps of "
                         f"{dt:.3g} s: more than {MAX_STEPS:.0e}; shorten duration or lower wave_speed")
    steps = int(round(steps))
    x_start = -0.35 * length

    @jax.jit
    def run(eta, prev):
        def body(carry, i):
            a, b = carry
            xs = x_start + source_speed * i * dt
            force = jnp.exp(-((x - xs) ** 2 + y**2) / (2 * source_size**2))
            return (fd_step(a, b, courant) - dt * dt * force, a), None
        return jax.lax.scan(body, (eta, prev), jnp.arange(steps))[0]

    z = jnp.zeros((n, n))
    eta, _ = run(z, z)
    return eta, grid, x_start + source_speed * steps * dt


class FiniteDifferenceStepper(_TwoLevel):
    """The explicit wave equation (:mod:`wavephys.models.finite_difference`): Courant number C = cΔt/Δx ≤ 1/√2,
    damping d, on a periodic grid.

    Parameters
    ----------
    courant : float
        C in (0, 1/√2].
    dt : float
        s, > 0 (the clock; the scheme itself sees only C).
    damping : float
        d in [0, 1).
    check_stability : bool
        Refuse C > 1/√2 (default); False lets C go to 10 to watch the scheme blow up (its failure boundary).
    """

    def __init__(self, courant: float, dt: float, damping: float = 0.0, check_stability: bool = True):
        check_bool("check_stability", check_stability)
        check_scalar("courant", courant, lo=0.0, hi=STABILITY_LIMIT if check_stability else 10.0, lo_open=True)
        check_scalar("damping", damping, lo=0.0, hi=1.0, hi_open=True)
        self.courant, self.damping, self.dt = float(courant), float(damping), check_scalar("dt", dt, lo=0.0,
                                                                                         lo_open=True)

    def _parts(self):
        return None, (self.courant, self.damping, self.dt)

    @classmethod
    def _advance(cls, static, dynamic, state, dt):
        courant, damping, _ = dynamic
        new = fd_step(state.eta, state.eta_prev, courant, damping)
        return TwoLevelState(new, state.eta, state.time + dt)
