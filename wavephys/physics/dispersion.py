r"""Dispersion relation of linear capillary-gravity waves, deep and finite depth.

.. math::

    \omega(k)^2 = \left(g k + \frac{\sigma}{\rho} k^3\right)\tanh(k h)

(docs/physics.md §1.1; Lamb, *Hydrodynamics*, §267; Loviscach 2003 uses the deep-water form). Phase
speed c = ω/k, group speed c_g = dω/dk in closed form, the inverse k(ω) by a safeguarded
Newton iteration, and the capillary-gravity minima of c and c_g.

All functions are pure ``jnp`` code: they broadcast over any shape, work under
``jit``/``vmap``/``grad`` and keep the dtype of ``k`` (float32 by default).
"""

from __future__ import annotations

import functools
import math

import jax
import jax.numpy as jnp
import numpy as np
from jax import lax

from wavephys.core.inputs import Array, Int, check_array, is_traced, validate
from wavephys.core.specs import WATER
from wavephys.core.water import Water

__all__ = [
    "K_MAX",
    "OMEGA_MAX",
    "angular_frequency",
    "phase_speed",
    "group_speed",
    "wavenumber",
    "min_phase_speed",
    "min_group_speed",
    "depth_factor",
    "surface_operator",
    "restoring_acceleration",
]

_TANH1 = math.tanh(1.0)

K_MAX = 1e9
"""Largest wavenumber accepted, rad/m (λ ≈ 6 nm: far past where continuum capillarity holds;
float32 overflows ω² near 1e13 rad/m)."""
OMEGA_MAX = 1e12
"""Largest angular frequency accepted, rad/s (ω at k = K_MAX is about 3e11)."""

_K = Array(lo=0.0, hi=K_MAX)
_OMEGA = Array(lo=0.0, hi=OMEGA_MAX)


def _compiled(fn=None, *, static=()):
    """``fn(k, water, *static)`` as one compiled program per power-of-two bucket of the size of a float32 ``k``
    (:func:`_by_bucket`; per shape and dtype where it is float64, traced, a scalar, or on a GPU).

    The water's four numbers are traced arguments (its checks pass tracers), so one program
    serves every water, fitted ones included; ``static`` names arguments that select a program
    (``iterations``). Called eagerly, each of the dozen operations of a formula would otherwise
    be compiled by itself for every new shape, about 40 ms each on a CPU. Under an outer
    ``jit``, ``vmap`` or ``grad`` the program is traced inline as before.
    """
    if fn is None:
        return functools.partial(_compiled, static=static)

    def traced(k, numbers, *rest):
        return fn(k, Water(*numbers), *rest)

    compiled = jax.jit(traced, static_argnums=tuple(range(2, 2 + len(static))))

    @functools.wraps(fn)
    def call(k, water, *rest):
        k = k if isinstance(k, jax.Array) else jnp.asarray(k)  # a list is one array, not a tree of numbers
        numbers = tuple(float(v) if isinstance(v, (int, float, np.number)) else v  # weak-typed, as eagerly
                        for v in (water.g, water.rho, water.sigma, water.depth))
        if _bucketed(k, numbers):
            return _by_bucket(compiled, k, numbers, rest)
        return compiled(k, numbers, *rest)

    return call


_BUCKET_MIN = 64


def _bucketed(k, numbers) -> bool:
    """Whether a call runs through a power-of-two bucket (:func:`_by_bucket`): concrete float32 arrays of one or
    more dimensions on a CPU (a scalar keeps its weak type; a GPU keeps its arrays on the device; float64 keeps
    its own program per shape, bit for bit what it was: the split's tables are float64)."""
    if is_traced(k) or is_traced(numbers) or k.ndim == 0 or k.size == 0 or getattr(k, "weak_type", False):
        return False
    if k.dtype != np.float32:
        return False
    return all(d.platform == "cpu" for d in k.devices())


def _by_bucket(compiled, k, numbers, rest):
    """An elementwise formula's program run on ``k`` flattened and padded to a power-of-two length (with its
    first value), and cut back: one program per bucket and dtype instead of one per shape (the test suite
    compiled 324 of them, 28 s, one per shape met; each bucket's element is the same formula on the same
    number)."""
    size = k.size
    bucket = max(_BUCKET_MIN, 1 << (size - 1).bit_length())
    flat = np.asarray(k).reshape(-1)
    padded = np.concatenate([flat, np.full(bucket - size, flat[0], flat.dtype)])
    out = np.asarray(compiled(jnp.asarray(padded), numbers, *rest))
    return jnp.asarray(out[:size].reshape(k.shape))


def _deep(water: Water):
    return jnp.isinf(water.depth)


@validate(k=_K, water=WATER)
@_compiled
def depth_factor(k, water: Water):
    """tanh(k h), with the deep-water limit 1 exactly when ``water.depth`` is infinite.

    Parameters
    ----------
    k : array_like
        Angular wavenumber magnitude, rad/m, in [0, 1e9] (:data:`K_MAX`).
    water : Water
        Supplies the depth h, m.

    Returns
    -------
    jax.Array
        tanh(k h), dimensionless, in [0, 1], shape of ``k``.

    References
    ----------
    H. Lamb (1932). *Hydrodynamics*, 6th ed., §267. J. Loviscach (2003). Complex water effects at
    interactive frame rates. *WSCG* (deep water). docs/physics.md §1.1.
    """
    deep = _deep(water)
    h = jnp.where(deep, 1.0, water.depth)
    return jnp.where(deep, 1.0, jnp.tanh(k * h))


@validate(k=_K, water=WATER)
@_compiled
def surface_operator(k, water: Water):
    """K(k) = k·tanh(k h), rad/m: the Fourier symbol of ∂φ/∂z at the surface.

    Linear kinematic condition: η̂_t = K(k)·φ̂ (docs/physics.md §1.2). Deep water: K = |k|.

    Parameters
    ----------
    k : array_like
        Angular wavenumber magnitude, rad/m, in [0, 1e9] (:data:`K_MAX`), any shape.
    water : Water
        g (m/s²), ρ (kg/m³), σ (N/m), depth h (m, ``inf`` for deep water).

    Returns
    -------
    jax.Array
        K(k), rad/m, same shape as ``k``.

    References
    ----------
    H. Lamb (1932). *Hydrodynamics*, 6th ed., §267. J. Loviscach (2003). Complex water effects at
    interactive frame rates. *WSCG* (deep water). docs/physics.md §1.1.
    """
    return k * depth_factor(k, water)


@validate(k=_K, water=WATER)
@_compiled
def restoring_acceleration(k, water: Water):
    """g + (σ/ρ)k², m/s²: gravity plus the capillary restoring term of mode k.

    Linear dynamic condition: φ̂_t = −(g + (σ/ρ)k²)·η̂, so ω² = K·(g + (σ/ρ)k²).

    Parameters
    ----------
    k : array_like
        Angular wavenumber magnitude, rad/m, in [0, 1e9] (:data:`K_MAX`), any shape.
    water : Water
        g (m/s²), ρ (kg/m³), σ (N/m), depth h (m, ``inf`` for deep water).

    Returns
    -------
    jax.Array
        g + (σ/ρ)k², m/s², same shape as ``k``.

    References
    ----------
    H. Lamb (1932). *Hydrodynamics*, 6th ed., §267. J. Loviscach (2003). Complex water effects at
    interactive frame rates. *WSCG* (deep water). docs/physics.md §1.1.
    """
    return water.g + (water.sigma / water.rho) * k * k


def _omega_squared(k, water):
    return surface_operator(k, water) * restoring_acceleration(k, water)


def _safe_sqrt(x):
    """sqrt with a finite (zero) gradient at 0, via the double-``where`` trick."""
    pos = x > 0
    return jnp.where(pos, jnp.sqrt(jnp.where(pos, x, 1.0)), 0.0)


@validate(k=_K, water=WATER)
@_compiled
def angular_frequency(k, water: Water):
    r"""Angular frequency ω(k) of a linear capillary-gravity wave, rad/s.

    .. math:: \omega^2 = (g k + (\sigma/\rho) k^3)\tanh(k h)

    Parameters
    ----------
    k : array_like
        Angular wavenumber magnitude |k|, rad/m, in [0, 1e9] (:data:`K_MAX`), any shape.
    water : Water
        g (m/s²), ρ (kg/m³), σ (N/m), depth h (m, ``inf`` for deep water).

    Returns
    -------
    jax.Array
        ω, rad/s, same shape and floating dtype as ``k``. ω(0) = 0.

    Notes
    -----
    Valid for small-amplitude (linear) waves on inviscid water: kA ≪ 1.
    Source: docs/physics.md §1.1; Loviscach (2003), below eq. 1 (deep water).

    References
    ----------
    H. Lamb (1932). *Hydrodynamics*, 6th ed., §267. J. Loviscach (2003). Complex water effects at
    interactive frame rates. *WSCG* (deep water).

    Examples
    --------
    >>> from wavephys import Water
    >>> round(float(angular_frequency(1.0, Water(sigma=0.0))), 4)   # sqrt(g k)
    3.1321
    """
    k = jnp.asarray(k, dtype=jnp.result_type(float, k))
    return _safe_sqrt(_omega_squared(k, water))


def _long_wave_speed(water: Water, dtype):
    """Limit of c and c_g as k → 0: sqrt(g h), or inf in deep water."""
    deep = _deep(water)
    h = jnp.where(deep, 1.0, water.depth)
    return jnp.where(deep, jnp.inf, jnp.sqrt(water.g * h)).astype(dtype)


def _positive(k):
    """k as a float array, the mask k > 0, and k with zeros replaced by 1."""
    k = jnp.asarray(k, dtype=jnp.result_type(float, k))
    pos = k > 0
    return k, pos, jnp.where(pos, k, 1.0)


@validate(k=_K, water=WATER)
@_compiled
def phase_speed(k, water: Water):
    """Phase speed c = ω/k, m/s.

    Parameters
    ----------
    k : array_like
        Angular wavenumber magnitude, rad/m, in [0, 1e9] (:data:`K_MAX`).
    water : Water

    Returns
    -------
    jax.Array
        c, m/s. At k = 0: sqrt(g h) for finite depth, ``inf`` for deep water.

    Limits: deep gravity c = sqrt(g/k); shallow (kh ≪ 1) c = sqrt(g h); pure capillary
    c = sqrt(σ k / ρ).

    References
    ----------
    H. Lamb (1932). *Hydrodynamics*, 6th ed., §267. J. Loviscach (2003). Complex water effects at
    interactive frame rates. *WSCG* (deep water). docs/physics.md §1.1.
    """
    k, pos, ks = _positive(k)
    c = jnp.sqrt(restoring_acceleration(ks, water) * depth_factor(ks, water) / ks)
    return jnp.where(pos, c, _long_wave_speed(water, k.dtype))


@validate(k=_K, water=WATER)
@_compiled
def group_speed(k, water: Water):
    r"""Group speed c_g = dω/dk in closed form, m/s.

    .. math::

        c_g = \frac{(T + k h (1 - T^2))(g + s k^2) + 2 s k^2 T}{2\,\omega/k},
        \quad T = \tanh(k h),\ s = \sigma/\rho

    Parameters
    ----------
    k : array_like
        Angular wavenumber magnitude, rad/m, in [0, 1e9] (:data:`K_MAX`).
    water : Water

    Returns
    -------
    jax.Array
        c_g, m/s. At k = 0: sqrt(g h) for finite depth, ``inf`` for deep water.

    Limits: deep gravity c_g = c/2; pure capillary c_g = 3c/2; shallow c_g = c.

    References
    ----------
    H. Lamb (1932). *Hydrodynamics*, 6th ed., §267. J. Loviscach (2003). Complex water effects at
    interactive frame rates. *WSCG* (deep water). docs/physics.md §1.1.
    """
    k, pos, ks = _positive(k)
    deep = _deep(water)
    h = jnp.where(deep, 1.0, water.depth)
    t = depth_factor(ks, water)
    dtdk_k = jnp.where(deep, 0.0, ks * h * (1.0 - t * t))  # k·d(tanh kh)/dk
    s = water.sigma / water.rho
    r = restoring_acceleration(ks, water)
    # ω²/k = t·r ; d(ω²)/dk = (t + k·dt/dk)·r + 2 s k² t ; c_g = d(ω²)/dk / (2ω)
    num = (t + dtdk_k) * r + 2.0 * s * ks * ks * t
    c = jnp.sqrt(t * r / ks)
    return jnp.where(pos, num / (2.0 * c * ks), _long_wave_speed(water, k.dtype))


def _bracket(omega2, water: Water):
    """Positive bounds k_lo ≤ k(ω) ≤ k_hi valid for every ω > 0 and h > 0.

    Lower: ω² ≤ g k + s k³, so g k ≥ ω²/2 or s k³ ≥ ω²/2.
    Upper: ω² ≥ g k tanh(k h) ≥ g k tanh(1) min(k h, 1) (capillarity only lowers k).
    """
    g, s = water.g, water.sigma / water.rho
    s_safe = jnp.where(s > 0, s, 1.0)
    k_cap = jnp.where(s > 0, jnp.cbrt(omega2 / (2.0 * s_safe)), jnp.inf)
    k_lo = jnp.minimum(omega2 / (2.0 * g), k_cap)
    deep = _deep(water)
    h = jnp.where(deep, 1.0, water.depth)
    k_shallow = jnp.where(deep, 0.0, jnp.sqrt(omega2 / (g * h * _TANH1)))
    k_hi = jnp.maximum(omega2 / (g * _TANH1), k_shallow)
    return k_lo, k_hi


@validate(omega=_OMEGA, water=WATER, iterations=Int(lo=8, hi=1000))
@_compiled(static=("iterations",))
def wavenumber(omega, water: Water, iterations: int = 60):
    r"""Inverse dispersion relation: the k ≥ 0 with ω(k) = ``omega``, rad/m.

    Solves G(u) = log ω²(eᵘ) − log ω_target² = 0 for u = log k by Newton's method
    (G is increasing and nearly linear in u: slope 1 for deep gravity, 2 shallow,
    3 capillary), safeguarded by a bracket [k_lo, k_hi] that is valid for every ω > 0
    and h > 0 and by bisection whenever a Newton step leaves it. A fixed number of
    iterations keeps it ``jit``/``vmap``-able and branch-free.

    Parameters
    ----------
    omega : array_like
        Angular frequency, rad/s, in [0, 1e12] (:data:`OMEGA_MAX`), any shape.
    water : Water
    iterations : int
        Newton/bisection iterations, 8 to 1000 (default 60; quadratic convergence typically
        needs fewer than 8, the bracket guarantees convergence of the rest).

    Returns
    -------
    jax.Array
        k, rad/m, same shape as ``omega``; k(0) = 0.

    References
    ----------
    H. Lamb (1932). *Hydrodynamics*, 6th ed., §267. J. Loviscach (2003). Complex water effects at
    interactive frame rates. *WSCG* (deep water). docs/physics.md §1.1.

    Examples
    --------
    >>> from wavephys import Water
    >>> w = Water(sigma=0.0)
    >>> round(float(wavenumber(angular_frequency(2.0, w), w)), 5)
    2.0
    """
    omega = jnp.asarray(omega, dtype=jnp.result_type(float, omega))
    pos = omega > 0
    om = jnp.where(pos, omega, 1.0)
    target = 2.0 * jnp.log(om)
    k_lo, k_hi = _bracket(om * om, water)
    lo, hi = jnp.log(k_lo), jnp.log(k_hi)

    def body(_, carry):
        u, lo, hi = carry
        k = jnp.exp(u)
        w2 = _omega_squared(k, water)
        g_val = jnp.log(w2) - target
        cg = group_speed(k, water)
        slope = 2.0 * k * cg / jnp.sqrt(w2)  # dG/du = k·(dω²/dk)/ω²
        lo = jnp.where(g_val < 0, u, lo)
        hi = jnp.where(g_val > 0, u, hi)
        step = u - g_val / slope
        inside = (step > lo) & (step < hi)
        return jnp.where(inside, step, 0.5 * (lo + hi)), lo, hi

    u0 = 0.5 * (lo + hi)
    u, _, _ = lax.fori_loop(0, iterations, body, (u0, lo, hi))
    return jnp.where(pos, jnp.exp(u), 0.0)


def _golden_minimum(f, lo, hi, iterations=200):
    """Minimum of a unimodal f on [lo, hi] by golden-section search (jnp, fixed steps)."""
    r = (math.sqrt(5.0) - 1.0) / 2.0

    def body(_, carry):
        a, b = carry
        c = b - r * (b - a)
        d = a + r * (b - a)
        left = f(c) < f(d)
        return jnp.where(left, a, c), jnp.where(left, d, b)

    a, b = lax.fori_loop(0, iterations, body, (lo, hi))
    return 0.5 * (a + b)


def _minimum_speed(speed, water: Water, name: str):
    if is_traced(water):
        raise TypeError(f"{name} needs concrete water parameters")
    if float(water.sigma) <= 0.0:
        raise ValueError(
            f"{name}: sigma must be > 0 (without surface tension the speed decreases to 0 "
            f"as k → ∞ and has no minimum), got sigma={water.sigma!r}"
        )
    k_s = math.sqrt(float(water.g) / (float(water.sigma) / float(water.rho)))
    lo, hi = math.log(k_s * 1e-6), math.log(k_s * 1e6)
    u = _golden_minimum(lambda u: speed(jnp.exp(u), water), jnp.asarray(lo), jnp.asarray(hi))
    k = math.exp(float(u))
    c = float(speed(jnp.asarray(k), water))
    if not water.is_deep:
        c_long = math.sqrt(float(water.g) * float(water.depth))
        if c >= c_long * (1.0 - 1e-6):
            # no interior minimum: the speed rises from its long-wave limit (k → 0)
            return c_long, 0.0
    return c, k


@validate(water=WATER)
def min_phase_speed(water: Water = Water()):
    """Minimum phase speed of capillary-gravity waves and its wavenumber.

    Deep water: c_min = (4 g σ/ρ)^{1/4} ≈ 0.2312 m/s at k = sqrt(ρ g/σ) ≈ 367 rad/m
    (λ ≈ 1.71 cm). Found numerically (golden section in log k), so finite depth works
    too; when the minimum is the long-wave limit (h² < 3σ/(ρg)) it returns
    (sqrt(g h), 0).

    Parameters
    ----------
    water : Water
        g (m/s²), ρ (kg/m³), σ (N/m, must be > 0 for a minimum), depth h (m, ``inf`` for deep
        water); concrete (not traced).

    Returns
    -------
    (float, float)
        (speed in m/s, wavenumber in rad/m).

    Raises
    ------
    ValueError
        If ``water.sigma`` is 0: gravity waves have no minimum phase speed.
    TypeError
        If the water parameters are traced.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG* (deep-water form);
    H. Lamb (1932). *Hydrodynamics*, 6th ed., §267 (docs/physics.md §1.1).
    """
    return _minimum_speed(phase_speed, water, "min_phase_speed")


@validate(water=WATER)
def min_group_speed(water: Water = Water()):
    """Minimum group speed of capillary-gravity waves and its wavenumber.

    Deep clean water: c_g,min ≈ 0.1776 m/s at λ ≈ 4.35 cm (k ≈ 144 rad/m). The slowest
    energy transport; below it no wave energy keeps up with a moving source.

    Parameters
    ----------
    water : Water
        g (m/s²), ρ (kg/m³), σ (N/m, must be > 0 for a minimum), depth h (m, ``inf`` for deep
        water); concrete (not traced).

    Returns
    -------
    (float, float)
        (speed in m/s, wavenumber in rad/m); (sqrt(g h), 0) when the minimum is the long-wave
        limit.

    Raises
    ------
    ValueError
        If ``water.sigma`` is 0: gravity waves have no minimum group speed.
    TypeError
        If the water parameters are traced.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG* (deep-water form);
    H. Lamb (1932). *Hydrodynamics*, 6th ed., §267 (docs/physics.md §1.1).
    """
    return _minimum_speed(group_speed, water, "min_group_speed")
