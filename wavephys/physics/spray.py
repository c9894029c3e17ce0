r"""Spray and splash drops in flight: gravity and the drag of the air (docs/physics.md §1.16).

A drop of radius r leaves the surface with the water's velocity and flies under gravity and the drag of the air
moving past it (the wind w; u = v − w the drop's speed through the air, s = |u|),

.. math::

    \dot{\mathbf x} = \mathbf v, \qquad \dot{\mathbf v} = \mathbf g - k(s)\,\mathbf u, \qquad
    k(s) = \frac{3\,\rho_a\,C_d(\mathrm{Re})\,s}{8\,\rho_w\,r}, \qquad \mathrm{Re} = \frac{2 r s \rho_a}{\mu_a},

the drag force ½ρ_a C_d πr² s u over the drop's mass (4/3)πr³ρ_w; k is the drag's rate, 1/s. The drag
coefficient of a sphere by ``law`` (:data:`DRAG_LAWS`): Schiller & Naumann's (1933) 24/Re (1 + 0.15 Re^0.687)
up to Re = 1000 and 0.44 above (the default: Stokes's law for mist, the Newton regime for rain-sized drops), or
the constant 0.44 (``"newton"``, the quadratic drag engines write). Still air gives the terminal speed
(:func:`terminal_speed`), where k(s)·s = g. Without drag the path is the parabola (:func:`drops_ballistic`).

Two ways to step it (:data:`ADVANCE_DROPS`, the dispatcher :func:`advance_drops`):

* ``"exponential"`` (ours): the rate k frozen over the step and the rest exact — the linear ODE
  v̇ = g − k(v − w) integrated in closed form (φ-functions of z = k·Δt) — with k taken at the step's midpoint,
  predicted by the same formula over Δt/2. Second order; finite for any Δt (each step relaxes towards w + g/k
  of its own frozen rate, never past it), though a step far longer than 1/k lands near, not on, the terminal
  velocity, and one of seconds can overshoot it (docs/physics.md §1.16).
* ``"euler"``: what engines write, v += Δt·(g − k(s)u), then x += Δt·v (semi-implicit Euler). First order;
  unstable past Δt = 2/λ, λ = d(k(s)s)/ds (:func:`euler_stable_dt`): fine drops (mist) at 30–60 Hz.

Every position and velocity is (..., 3), m and m/s, z up; gravity acts along −z. Neglected: a drop's flattening
(above 3 mm across it falls slower than a sphere: Gunn & Kinzer 1949), evaporation, break-up, and the drop's
effect on the air.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.inputs import check_array, check_scalar, is_traced
from wavephys.core.methods import Methods
from wavephys.core.water import DENSITY, GRAVITY

__all__ = ["AIR_DENSITY", "AIR_VISCOSITY", "NEWTON_DRAG", "drag_coefficient_schiller_naumann",
           "drag_coefficient_newton", "DRAG_LAWS", "drag_rate", "terminal_speed", "euler_stable_dt",
           "drops_ballistic", "advance_drops_exponential", "advance_drops_euler", "ADVANCE_DROPS", "advance_drops"]

AIR_DENSITY = 1.204
"""kg/m³, dry air at 20 °C and 1013.25 hPa."""

AIR_VISCOSITY = 1.81e-5
"""Pa·s, the dynamic viscosity of air at 20 °C."""

NEWTON_DRAG = 0.44
"""A sphere's drag coefficient in the Newton regime (Re 10³–2·10⁵), dimensionless."""

_SERIES_BELOW = 0.1  # z below which φ₂ comes from its series (its closed form cancels in float32)
_RE_FLOOR = 1e-30  # Re^0.687 is taken at least here (its derivative at rest is infinite; its limit is 0)


_DRAG_NUMBERS = {  # C_d·Re of each law, unchecked (inside steps); Re^0.687's slope at rest taken as 0, its limit
    "schiller_naumann": lambda re: jnp.where(re <= 1000.0, 24.0 * (1.0 + 0.15 * jnp.maximum(re, _RE_FLOOR) ** 0.687),
                                             NEWTON_DRAG * re),
    "newton": lambda re: NEWTON_DRAG * re,
}


def drag_coefficient_schiller_naumann(reynolds):
    """A sphere's drag coefficient by Schiller & Naumann (1933): 24/Re (1 + 0.15 Re^0.687) up to Re = 1000,
    :data:`NEWTON_DRAG` above.

    Parameters
    ----------
    reynolds : float or array_like
        Re = 2rs ρ_a/μ_a, dimensionless, > 0.

    Returns
    -------
    float or array
        C_d, dimensionless.

    References
    ----------
    L. Schiller & A. Naumann (1933). Über die grundlegenden Berechnungen bei der Schwerkraftaufbereitung.
    *Z. Ver. Dtsch. Ing.* 77, 318–320.
    """
    check_array("reynolds", reynolds, lo=0.0, lo_open=True)
    re = jnp.asarray(reynolds)
    return _DRAG_NUMBERS["schiller_naumann"](re) / re


def drag_coefficient_newton(reynolds):
    """The constant drag coefficient :data:`NEWTON_DRAG` (quadratic drag), whatever the Reynolds number.

    Parameters
    ----------
    reynolds : float or array_like
        Re, dimensionless, > 0 (it sets only the shape).

    Returns
    -------
    float or array
        C_d, dimensionless.
    """
    check_array("reynolds", reynolds, lo=0.0, lo_open=True)
    re = jnp.asarray(reynolds)
    return _DRAG_NUMBERS["newton"](re) / re


DRAG_LAWS = Methods("drop drag coefficient", schiller_naumann=drag_coefficient_schiller_naumann,
                    newton=drag_coefficient_newton)
"""A sphere's drag coefficient C_d(Re), by name."""



def _rate(speed, radius, law, air_density, air_viscosity, water_density):
    """k(s), 1/s (unchecked; shapes broadcast): 3μ·(C_d Re) / (16 ρ_w r²), written with the product C_d·Re, which
    stays finite as the drop comes to rest in the air (Stokes: 24)."""
    re = 2.0 * radius * speed * air_density / air_viscosity
    return 3.0 * air_viscosity * _DRAG_NUMBERS[law](re) / (16.0 * water_density * radius * radius)


def _finite(result, what, **settings):
    """``result``, unchanged; a ValueError naming every setting when a concrete result is not finite (it overflowed
    its float type: a setting far out of range)."""
    leaves = jax.tree_util.tree_leaves(result)
    if any(is_traced(a) for a in leaves) or all(bool(jnp.isfinite(a).all()) for a in leaves):
        return result
    shown = ", ".join(f"{k}={v!r}" if np.ndim(v) == 0 else f"{k} (shape {np.shape(v)})" for k, v in settings.items())
    raise ValueError(f"the {what} overflow {leaves[0].dtype}: one of {shown} is out of range")


def _check_air(law, air_density, air_viscosity, water_density):
    DRAG_LAWS.check(law, "law")
    check_scalar("air_density", air_density, lo=0.0, lo_open=True)
    check_scalar("air_viscosity", air_viscosity, lo=0.0, lo_open=True)
    check_scalar("water_density", water_density, lo=0.0, lo_open=True)


def drag_rate(speed, radius, *, law="schiller_naumann", air_density=AIR_DENSITY, air_viscosity=AIR_VISCOSITY,
              water_density=DENSITY):
    """The drag's rate k(s) = 3ρ_a C_d(Re) s / (8ρ_w r), 1/s: a drop moving through the air at u slows by k·u.

    Parameters
    ----------
    speed : float or array_like
        s, the drop's speed through the air, m/s, ≥ 0.
    radius : float or array_like
        r, m, > 0.
    law : str, optional
        The drag coefficient's law (:data:`DRAG_LAWS`).
    air_density, air_viscosity, water_density : float, optional
        ρ_a (kg/m³), μ_a (Pa·s), ρ_w (kg/m³), > 0.

    Returns
    -------
    float or array
        k, 1/s, ``speed`` and ``radius`` broadcast (at s = 0: Stokes's 9μ_a/(2ρ_w r²) by Schiller & Naumann, 0
        by the constant law).

    Examples
    --------
    >>> round(float(drag_rate(0.0, 1e-4)), 3)   # Stokes: 9μ/(2ρ_w r²)
    8.145
    """
    check_array("speed", speed, lo=0.0)
    check_array("radius", radius, lo=0.0, lo_open=True)
    _check_air(law, air_density, air_viscosity, water_density)
    k = _rate(jnp.asarray(speed), jnp.asarray(radius), law, air_density, air_viscosity, water_density)
    return _finite(k, "drag rates", speed=speed, radius=radius, air_density=air_density, air_viscosity=air_viscosity,
                   water_density=water_density)


def terminal_speed(radius, *, g=GRAVITY, law="schiller_naumann", air_density=AIR_DENSITY,
                   air_viscosity=AIR_VISCOSITY, water_density=DENSITY):
    """The speed at which drag balances gravity in still air, k(s)·s = g, m/s (bisection to rounding).

    Parameters
    ----------
    radius : float or array_like
        r, m, > 0.
    g : float, optional
        Gravity, m/s², > 0.
    law, air_density, air_viscosity, water_density : optional
        As :func:`drag_rate`'s.

    Returns
    -------
    float or array
        m/s, shaped as ``radius``.

    Examples
    --------
    >>> round(float(terminal_speed(1e-3)), 2)   # 2 mm across (Gunn & Kinzer 1949 measured 6.49 m/s)
    6.94
    """
    check_array("radius", radius, lo=0.0, lo_open=True)
    check_scalar("g", g, lo=0.0, lo_open=True)
    _check_air(law, air_density, air_viscosity, water_density)
    r = jnp.asarray(radius)
    r = r.astype(jnp.result_type(r, float))
    lo = jnp.zeros_like(r)
    hi = jnp.sqrt(8.0 * water_density * r * g / (3.0 * air_density * 0.4))  # C_d ≥ 0.4 by both laws

    def halve(_, bounds):
        a, b = bounds
        m = 0.5 * (a + b)
        below = _rate(m, r, law, air_density, air_viscosity, water_density) * m < g
        return jnp.where(below, m, a), jnp.where(below, b, m)

    lo, hi = jax.lax.fori_loop(0, 64, halve, (lo, hi))
    return _finite(0.5 * (lo + hi), "terminal speeds", radius=radius, g=g, air_density=air_density,
                   air_viscosity=air_viscosity, water_density=water_density)


def euler_stable_dt(radius, speed=None, *, law="schiller_naumann", g=GRAVITY, air_density=AIR_DENSITY,
                    air_viscosity=AIR_VISCOSITY, water_density=DENSITY):
    """The longest step the engines' Euler (:func:`advance_drops_euler`) takes without growing: 2/λ, s.

    λ = d(k(s)s)/ds, the drag's rate along the drop's path through the air (at least k(s), across it): Euler's
    factor 1 − λΔt leaves [−1, 1] past Δt = 2/λ.

    Parameters
    ----------
    radius : float or array_like
        r, m, > 0.
    speed : float or array_like, optional
        The drop's speed through the air, m/s, ≥ 0 (default: its terminal speed, where a drop ends up).
    law, g, air_density, air_viscosity, water_density : optional
        As :func:`terminal_speed`'s.

    Returns
    -------
    float or array
        s, ``radius`` and ``speed`` broadcast.

    Examples
    --------
    >>> round(float(euler_stable_dt(1e-5)), 5)   # mist, 20 µm across: Euler at 60 Hz (0.0167 s) grows
    0.00242
    """
    check_array("radius", radius, lo=0.0, lo_open=True)
    check_scalar("g", g, lo=0.0, lo_open=True)
    if speed is None:
        speed = terminal_speed(radius, g=g, law=law, air_density=air_density, air_viscosity=air_viscosity,
                               water_density=water_density)
    check_array("speed", speed, lo=0.0)
    _check_air(law, air_density, air_viscosity, water_density)
    s, r = jnp.broadcast_arrays(jnp.asarray(speed, float), jnp.asarray(radius, float))
    limit = _euler_limit(s, r, law, (air_density, air_viscosity, water_density))
    _finite(jnp.where(jnp.isposinf(limit) & (s == 0), 0.0, limit), "steps", radius=radius, speed=speed, g=g,
            air_density=air_density, air_viscosity=air_viscosity, water_density=water_density)
    return limit


def _euler_limit(s, r, law, air):
    """2/λ, λ = max(d(k(s)s)/ds, k(s)), elementwise (unchecked)."""
    _, slope = jax.jvp(lambda q: _rate(q, r, law, *air) * q, (s,), (jnp.ones_like(s),))
    lam = jnp.maximum(slope, _rate(s, r, law, *air))
    return jnp.where(lam > 0, 2.0 / jnp.where(lam > 0, lam, 1.0), jnp.inf)  # no drag at all (constant C_d at rest)


def _checked(positions, velocities, radius, wind, g, law, air):
    """The drops' arrays in one float dtype, checked by name: (x, v, r (..., 1), w, dtype)."""
    check_array("positions", positions, min_ndim=1)
    check_array("velocities", velocities, min_ndim=1)
    for name, a in (("positions", positions), ("velocities", velocities)):
        if np.shape(a)[-1] != 3:
            raise ValueError(f"{name} must hold 3 components (x, y, z) in its last axis, got shape {np.shape(a)}")
    if np.shape(positions) != np.shape(velocities):
        raise ValueError(f"velocities must have the shape of positions {np.shape(positions)}, got "
                         f"{np.shape(velocities)}")
    check_array("radius", radius, lo=0.0, lo_open=True)
    check_array("wind", wind, min_ndim=1)
    if np.shape(wind)[-1] != 3:
        raise ValueError(f"wind must hold 3 components (x, y, z), m/s, got shape {np.shape(wind)}")
    check_scalar("g", g, lo=0.0, lo_open=True)
    _check_air(law, *air)
    x = jnp.asarray(positions)
    dtype = x.dtype if jnp.issubdtype(x.dtype, jnp.floating) else jnp.result_type(float)
    r = jnp.asarray(radius, dtype)
    drops = x.shape[:-1]
    try:
        fits = jnp.broadcast_shapes(r.shape, drops) == drops
    except ValueError:
        fits = False
    if not fits:
        raise ValueError(f"radius must be one number or one per drop (shape {drops}), got shape {r.shape}")
    try:
        fits = jnp.broadcast_shapes(np.shape(wind), x.shape) == x.shape
    except ValueError:
        fits = False
    if not fits:
        raise ValueError(f"wind must be one velocity (3,) or one per drop {x.shape}, got shape {np.shape(wind)}")
    return x.astype(dtype), jnp.asarray(velocities, dtype), r[..., None], jnp.asarray(wind, dtype), dtype


def _speed(u):
    """|u| over the last axis, kept (..., 1), with the gradient 0 (not NaN) where u = 0: a drop at rest in the air."""
    squared = jnp.sum(u * u, axis=-1, keepdims=True)
    moving = squared > 0
    return jnp.where(moving, jnp.sqrt(jnp.where(moving, squared, 1.0)), 0.0)


def _gravity(g, dtype):
    return jnp.asarray([0.0, 0.0, -g], dtype)


def drops_ballistic(positions, velocities, t, *, g=GRAVITY):
    """Drops without drag after a time t: the parabola x + vt + ½gt², v + gt.

    Parameters
    ----------
    positions, velocities : array_like (..., 3)
        m and m/s at t = 0.
    t : float
        s, ≥ 0.
    g : float, optional
        Gravity, m/s², > 0, along −z.

    Returns
    -------
    (positions, velocities) : tuple of arrays (..., 3)
        m and m/s at t.
    """
    check_scalar("t", t, lo=0.0)
    x, v, _, _, dtype = _checked(positions, velocities, 1.0, (0.0, 0.0, 0.0), g, "newton",
                                 (AIR_DENSITY, AIR_VISCOSITY, DENSITY))
    a = _gravity(g, dtype)
    return _finite((x + v * t + 0.5 * a * t * t, v + a * t), "drops' positions or velocities", positions=positions,
                   velocities=velocities, t=t, g=g)


def _phi(z):
    """φ₁(z) = (1 − e^{−z})/z and φ₂(z) = (1 − φ₁)/z = (z − 1 + e^{−z})/z², z ≥ 0: φ₁ closed (expm1 does not cancel),
    φ₂ by its series below z = 0.1, where 1 − φ₁ cancels (series error z⁵/5040)."""
    positive = z > 0
    zp = jnp.where(positive, z, 1.0)  # no 0/0, and no NaN gradient, at z = 0
    phi1 = jnp.where(positive, -jnp.expm1(-zp) / zp, 1.0)
    small = z < _SERIES_BELOW
    zs = jnp.where(small, 1.0, z)
    phi2 = jnp.where(small, 0.5 - z / 6.0 + z * z / 24.0 - z ** 3 / 120.0 + z ** 4 / 720.0, (1.0 - phi1) / zs)
    return phi1, phi2


def _frozen_drag_step(x, v, dt, k, w, a):
    """x, v after dt of v̇ = a − k(v − w), k held: exact (v' = e^{−z}v + (1 − e^{−z})w + a·Δt·φ₁(z), z = kΔt)."""
    z = k * dt
    phi1, phi2 = _phi(z)
    v_new = jnp.exp(-z) * v - jnp.expm1(-z) * w + a * dt * phi1  # finite for z = inf too
    x_new = x + dt * phi1 * v + dt * (1.0 - phi1) * w + a * dt * dt * phi2
    return x_new, v_new


def advance_drops_exponential(positions, velocities, dt, *, radius, wind=(0.0, 0.0, 0.0), g=GRAVITY,
                              law="schiller_naumann", air_density=AIR_DENSITY, air_viscosity=AIR_VISCOSITY,
                              water_density=DENSITY):
    """One step of flying drops, the drag's rate frozen at the step's midpoint and the rest exact (module doc).

    Second order in Δt; finite for any Δt (steps of seconds land near, not on, the terminal velocity); the
    parabola when the drag vanishes.

    Parameters
    ----------
    positions, velocities : array_like (..., 3)
        m and m/s.
    dt : float
        s, > 0.
    radius : float or array_like (...)
        The drops' radius, m, > 0: one for all or one per drop.
    wind : array_like (3,) or (..., 3), optional
        The air's velocity, m/s.
    g : float, optional
        Gravity, m/s², > 0, along −z.
    law : str, optional
        The drag coefficient's law (:data:`DRAG_LAWS`).
    air_density, air_viscosity, water_density : float, optional
        ρ_a (kg/m³), μ_a (Pa·s), ρ_w (kg/m³), > 0.

    Returns
    -------
    (positions, velocities) : tuple of arrays (..., 3)
        After Δt, m and m/s, in the inputs' float dtype.
    """
    check_scalar("dt", dt, lo=0.0, lo_open=True)
    air = (air_density, air_viscosity, water_density)
    x, v, r, w, dtype = _checked(positions, velocities, radius, wind, g, law, air)
    a = _gravity(g, dtype)

    def rate(u):
        return _rate(_speed(u), r, law, *air).astype(dtype)

    _, v_half = _frozen_drag_step(x, v, 0.5 * dt, rate(v - w), w, a)
    return _finite(_frozen_drag_step(x, v, dt, rate(v_half - w), w, a), "drops' positions or velocities",
                   positions=positions, velocities=velocities, dt=dt, radius=radius, wind=wind, g=g,
                   air_density=air_density, air_viscosity=air_viscosity, water_density=water_density)


def advance_drops_euler(positions, velocities, dt, *, radius, wind=(0.0, 0.0, 0.0), g=GRAVITY,
                        law="schiller_naumann", air_density=AIR_DENSITY, air_viscosity=AIR_VISCOSITY,
                        water_density=DENSITY):
    """One semi-implicit Euler step, as engines write it: v += Δt·(g − k(s)(v − w)), then x += Δt·v.

    First order; grows past :func:`euler_stable_dt` (module doc), which shrinks as a drop speeds up: a concrete
    ``dt`` past it for any of the drops, at the faster of its speed through the air and its terminal speed (the
    fastest it will fall), is refused (ValueError); under ``jit`` it is not checked, and the drops' velocities
    grow without bound.

    Parameters
    ----------
    positions, velocities : array_like (..., 3)
        m and m/s.
    dt : float
        s, > 0.
    radius : float or array_like (...)
        The drops' radius, m, > 0: one for all or one per drop.
    wind : array_like (3,) or (..., 3), optional
        The air's velocity, m/s.
    g : float, optional
        Gravity, m/s², > 0, along −z.
    law : str, optional
        The drag coefficient's law (:data:`DRAG_LAWS`).
    air_density, air_viscosity, water_density : float, optional
        ρ_a (kg/m³), μ_a (Pa·s), ρ_w (kg/m³), > 0.

    Returns
    -------
    (positions, velocities) : tuple of arrays (..., 3)
        After Δt, m and m/s.
    """
    check_scalar("dt", dt, lo=0.0, lo_open=True)
    air = (air_density, air_viscosity, water_density)
    x, v, r, w, dtype = _checked(positions, velocities, radius, wind, g, law, air)
    u = v - w
    speed = _speed(u)
    if not any(map(is_traced, (x, v, r, w, dt, g))):  # λ grows with the speed: the faster of now and terminal
        fastest = jnp.maximum(speed, terminal_speed(jnp.broadcast_to(r, speed.shape), g=g, law=law,
                                                    air_density=air_density, air_viscosity=air_viscosity,
                                                    water_density=water_density))
        limit = float(jnp.min(_euler_limit(fastest, jnp.broadcast_to(r, speed.shape), law, air)))
        if dt > limit:
            raise ValueError(f"dt {dt:.3g} s is past the longest step Euler takes without growing for these drops, "
                             f"{limit:.3g} s (2/λ at their speed through the air or their terminal speed, whichever is "
                             f"faster: euler_stable_dt, set by their radius, g={g!r}, law={law!r}, air_density="
                             f"{air_density!r}, air_viscosity={air_viscosity!r}, water_density={water_density!r}); use "
                             f"method='exponential', or shorter steps")
    k = _rate(speed, r, law, *air).astype(dtype)
    v_new = v + dt * (_gravity(g, dtype) - k * u)
    return _finite((x + dt * v_new, v_new), "drops' positions or velocities", positions=positions,
                   velocities=velocities, dt=dt, radius=radius, wind=wind, g=g, air_density=air_density,
                   air_viscosity=air_viscosity, water_density=water_density)


ADVANCE_DROPS = Methods("spray drop step", exponential=advance_drops_exponential, euler=advance_drops_euler)
"""The ways to step flying drops, by name."""


def advance_drops(positions, velocities, dt, *, radius, wind=(0.0, 0.0, 0.0), g=GRAVITY, method="exponential",
                  **options):
    """One step of flying drops by ``method`` (:data:`ADVANCE_DROPS`).

    Parameters
    ----------
    positions, velocities : array_like (..., 3)
        m and m/s.
    dt : float
        s, > 0.
    radius : float or array_like (...)
        The drops' radius, m, > 0.
    wind : array_like (3,) or (..., 3), optional
        The air's velocity, m/s.
    g : float, optional
        Gravity, m/s², > 0.
    method : str, optional
        ``"exponential"`` (second order, bounded for any Δt) or ``"euler"`` (engines' semi-implicit Euler).
    **options
        ``law``, ``air_density``, ``air_viscosity``, ``water_density`` (:func:`advance_drops_exponential`).

    Returns
    -------
    (positions, velocities) : tuple of arrays (..., 3)
        After Δt.

    Examples
    --------
    >>> x, v = advance_drops([[0.0, 0.0, 0.0]], [[5.0, 0.0, 5.0]], 0.1, radius=1e-3)
    >>> [round(float(q), 3) for q in x[0]]
    [0.468, 0.0, 0.421]
    """
    return ADVANCE_DROPS(method, positions, velocities, dt, radius=radius, wind=wind, g=g, **options)
