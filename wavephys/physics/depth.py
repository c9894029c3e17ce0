r"""Linear waves over a floor of varying depth h(x): the laws the steppers are checked against
(docs/physics.md §1.12).

Over a slowly varying floor a wave keeps its frequency ω and takes, at each place, the
wavenumber the local depth gives it, ω = ω(k, h(x)). Its energy flux E·c_g is conserved
along a ray when nothing is reflected, so at normal incidence the amplitude grows as the
group speed falls: A/A₀ = K_s = √(c_g,0/c_g) (:func:`shoaling_coefficient`; Green's law
h^(−1/4) in shallow water). Over straight, parallel depth contours the wavenumber along the
contours is conserved, so sin θ/c is constant (Snell's law, :func:`refraction_angle`). On a
plane beach h = x·tan β the linear shallow-water equation η_tt = g∇·(h∇η) has the standing
wave η = A·J₀(2ω√(x/(g tan β))) (Lamb 1932, §186; :func:`lamb_beach`), a full reflection at
the shoreline.

:func:`depth_levels` and :func:`depth_weights` give the levels and the per-location blend
weights of the spectral method that propagates at a few depths (Jeschke & Wojtan 2023
blend surface waves this way).

References
----------
H. Lamb (1932). *Hydrodynamics*, 6th ed., §§186, 187; G. Green (1838), on the motion of waves
in a variable canal; R. G. Dean & R. A. Dalrymple (1991). *Water Wave Mechanics for Engineers
and Scientists*, ch. 4; S. Jeschke & C. Wojtan (2023). Generalizing shallow water simulations
with dispersive surface waves. *ACM TOG* 42(4), 83.
"""

from __future__ import annotations

import math

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.inputs import check_array, check_instance, check_int, check_scalar, is_traced
from wavephys.core.water import Water

__all__ = ["shoaling_coefficient", "refraction_angle", "lamb_beach", "depth_levels", "depth_weights",
           "mild_slope_transmission"]


def _water(water: Water, depth: float) -> Water:
    from dataclasses import replace

    return replace(water, depth=float(depth))


def _k_and_cg(omega: float, water: Water, depth: float):
    from wavephys.physics.dispersion import group_speed, wavenumber

    with jax.enable_x64(True):
        w = _water(water, depth)
        k = float(wavenumber(jnp.asarray(omega, jnp.float64), w))
        return k, float(group_speed(jnp.asarray(k, jnp.float64), w))


def _k_cg_traced(omega, water, depth):
    from wavephys.physics.dispersion import group_speed, wavenumber

    w = Water(water.g, water.rho, water.sigma, depth)
    k = wavenumber(jnp.asarray(omega, jnp.float64), w)
    return k, group_speed(k, w)


def shoaling_coefficient(omega, depth0, depth, water: Water = Water(sigma=0.0)):
    """K_s = A/A₀ = √(c_g(h₀)/c_g(h)) at frequency ω: a wave's amplitude over depth h relative to
    depth h₀ when its energy flux is conserved (no reflection, normal incidence).

    Parameters
    ----------
    omega : float
        Angular frequency, rad/s, > 0.
    depth0 : float
        Still-water depth h₀, m, > 0 (inf: deep water).
    depth : float or array_like
        Still-water depth(s) h, m, > 0 (inf: deep water); an array gives an array, in one vectorized call.
    water : Water
        g, ρ, σ (its depth is ignored).

    Returns
    -------
    float or numpy.ndarray
        K_s, dimensionless (the shape of ``depth``).

    Examples
    --------
    >>> round(shoaling_coefficient(0.2, 1.0, 0.0625), 3)  # Green's law in shallow water: (1/0.0625)^(1/4) = 2
    1.998
    """
    omega = check_scalar("omega", omega, lo=0.0, lo_open=True)
    check_scalar("depth0", depth0, lo=0.0, lo_open=True, allow_inf=True)
    check_instance("water", water, Water, "wavephys.Water")
    if np.ndim(depth) == 0:
        check_scalar("depth", depth, lo=0.0, lo_open=True, allow_inf=True)
    else:
        check_array("depth", depth, allow_inf=True)
        if not np.all(np.asarray(depth) > 0):
            raise ValueError("depth must be > 0 everywhere")
    hs = np.atleast_1d(np.asarray(depth, np.float64))
    with jax.enable_x64(True):
        cg0 = float(_k_cg_traced(omega, water, jnp.asarray(float(depth0)))[1])
        cg = np.asarray(jax.vmap(lambda h: _k_cg_traced(omega, water, h)[1])(jnp.asarray(hs)))
    ks = np.sqrt(cg0 / cg)
    return float(ks[0]) if np.ndim(depth) == 0 else ks.reshape(np.shape(depth))


def refraction_angle(theta0, omega, depth0, depth, water: Water = Water(sigma=0.0)) -> float:
    """The direction θ (radians from the depth gradient) a wave takes over depth h when it had θ₀ over
    h₀, straight parallel contours: sin θ / c(h) = sin θ₀ / c(h₀) (Snell), i.e. k·sin θ conserved.

    Parameters
    ----------
    theta0 : float
        Direction over h₀, rad, in [0, π/2).
    omega : float
        Angular frequency, rad/s, > 0.
    depth0, depth : float
        Depths, m, > 0 (inf: deep water).
    water : Water
        g, ρ, σ.

    Returns
    -------
    float
        θ, rad (NaN beyond total internal reflection, which waves going shallower never reach).
    """
    theta0 = check_scalar("theta0", theta0, lo=0.0, hi=0.5 * math.pi)
    omega = check_scalar("omega", omega, lo=0.0, lo_open=True)
    check_scalar("depth0", depth0, lo=0.0, lo_open=True, allow_inf=True)
    check_scalar("depth", depth, lo=0.0, lo_open=True, allow_inf=True)
    check_instance("water", water, Water, "wavephys.Water")
    k0, _ = _k_and_cg(omega, water, depth0)
    k, _ = _k_and_cg(omega, water, depth)
    s = k0 * math.sin(theta0) / k
    return math.asin(s) if s <= 1 else math.nan


def lamb_beach(x, omega, slope, amplitude=1.0, g: float = 9.81):
    """Lamb's standing wave on a plane beach h = x·tan β: η = A·J₀(2ω√(x/(g tan β))) at t = 0 (times cos ωt).

    Parameters
    ----------
    x : array_like
        Distance from the still shoreline, m, ≥ 0.
    omega : float
        Angular frequency, rad/s, > 0.
    slope : float
        tan β, > 0.
    amplitude : float
        A, m, > 0 (the height at the shoreline).
    g : float
        Gravity, m/s², > 0.

    Returns
    -------
    numpy.ndarray
        η, m, shape of ``x``.

    References
    ----------
    H. Lamb (1932). *Hydrodynamics*, §186.
    """
    from scipy.special import j0

    check_array("x", x, lo=0.0)
    omega = check_scalar("omega", omega, lo=0.0, lo_open=True)
    slope = check_scalar("slope", slope, lo=0.0, lo_open=True)
    amplitude = check_scalar("amplitude", amplitude, lo=0.0, lo_open=True)
    g = check_scalar("g", g, lo=0.0, lo_open=True)
    return amplitude * j0(2.0 * omega * np.sqrt(np.asarray(x, np.float64) / (g * slope)))


def depth_levels(depth, count: int = 4):
    """``count`` depths spanning a floor's range, geometrically spaced (the blend's levels), m.

    Parameters
    ----------
    depth : array_like
        The floor's still-water depth h(x), m, > 0 everywhere (finite).
    count : int
        Levels, 1 … 16 (1: the mean depth).

    Returns
    -------
    numpy.ndarray (count,)
        Increasing depths, m, from min h to max h.
    """
    check_array("depth", depth, lo=0.0)
    count = check_int("count", count, lo=1, hi=16)
    h = np.asarray(depth, np.float64)
    lo, hi = float(h.min()), float(h.max())
    if not lo > 0:
        raise ValueError(f"depth must be > 0 everywhere for the depth levels (no dry land), got min {lo:g} m")
    if count == 1 or hi <= lo * (1 + 1e-9):
        return np.full(1, float(h.mean()) if count == 1 else lo)
    return np.geomspace(lo, hi, count)


def depth_weights(depth, levels):
    """Weights w_j(x) of each level at each place: linear in h between the two levels around h(x),
    clamped outside them; they sum to 1 everywhere.

    Parameters
    ----------
    depth : array_like
        h(x), m.
    levels : array_like (J,)
        Increasing depths, m (:func:`depth_levels`).

    Returns
    -------
    jax.Array (J, *depth.shape)
        The weights, dimensionless, in [0, 1].
    """
    check_array("depth", depth)
    check_array("levels", levels, ndim=1, lo=0.0)
    lev, h = jnp.asarray(levels), jnp.asarray(depth)
    if lev.shape[0] == 1:
        return jnp.ones((1,) + h.shape, jnp.result_type(h, lev))
    if not is_traced(levels) and bool(np.any(np.diff(np.asarray(levels, np.float64)) <= 0)):
        raise ValueError(f"levels must increase, got {np.asarray(levels)}")
    return _level_weights(h, lev)


@jax.jit
def _level_weights(depth, lev):
    """:func:`depth_weights` past its checks: one program."""
    h = jnp.clip(depth, lev[0], lev[-1])
    j = jnp.clip(jnp.searchsorted(lev, h, side="right") - 1, 0, lev.shape[0] - 2)
    t = (h - lev[j]) / (lev[j + 1] - lev[j])
    idx = jnp.arange(lev.shape[0]).reshape((-1,) + (1,) * h.ndim)
    return jnp.where(idx == j, 1.0 - t, 0.0) + jnp.where(idx == j + 1, t, 0.0)


def mild_slope_transmission(omega, x, depth, water: Water = Water(sigma=0.0)):
    """Amplitude transmission and reflection of a monochromatic wave crossing a depth profile, by the
    time-harmonic mild-slope equation (Berkhoff 1972) integrated as an ODE: the reference the steppers'
    shoaling is measured against (docs/physics.md §1.12).

    d/dx(C c_g dη/dx) + k² C c_g η = 0 (C = ω/k, c_g the group speed, k = k(ω, h(x))), with h piecewise
    linear through (``x``, ``depth``) and constant beyond its ends. Only a transmitted wave leaves the far
    end: η = e^{ik₁x} there; integrating back to the near end and splitting the field into incident and
    reflected waves gives T (transmitted amplitude per unit incident amplitude) and R. Solved by SciPy's
    DOP853 at rtol 1e-10, atol 1e-12. In shallow water (C = c_g = √(gh)) it is the linear shallow-water
    equation exactly; it conserves energy flux (|R|² + |T|² c_g,1/c_g,0 = 1) and holds for bottom slopes
    up to about 1:3 (Booij 1983). With no reflection, T is the shoaling coefficient.

    Parameters
    ----------
    omega : float
        Angular frequency, rad/s, > 0.
    x : array_like (m,)
        Increasing positions, m (m ≥ 2).
    depth : array_like (m,)
        Depths at ``x``, m, > 0.
    water : Water
        g, ρ, σ (its depth is ignored).

    Returns
    -------
    (float, float)
        |T| and |R|, dimensionless.

    References
    ----------
    J. C. W. Berkhoff (1972). Computation of combined refraction–diffraction. *Proc. 13th Coastal
    Engineering Conf.*, 471–490; N. Booij (1983). A note on the accuracy of the mild-slope equation.
    *Coastal Engineering* 7, 191–203.
    """
    from scipy.integrate import solve_ivp

    from wavephys.physics.dispersion import group_speed, wavenumber

    omega = check_scalar("omega", omega, lo=0.0, lo_open=True)
    check_array("x", x, ndim=1)
    check_array("depth", depth, ndim=1, lo=0.0)
    if np.shape(x)[0] > 10000:
        raise ValueError(f"x: at most 10000 points for the piecewise-linear profile, got {np.shape(x)[0]}")
    check_instance("water", water, Water, "wavephys.Water")
    xs, hs = np.asarray(x, np.float64), np.asarray(depth, np.float64)
    if xs.shape != hs.shape or xs.size < 2 or np.any(np.diff(xs) <= 0):
        raise ValueError("x must increase and depth must match it (at least 2 points)")
    if not np.all(hs > 0):
        raise ValueError("depth must be > 0 (the mild-slope reference needs water everywhere)")
    table_h = np.geomspace(hs.min(), hs.max(), 400) if hs.max() > hs.min() else np.array([hs.min()])
    with jax.enable_x64(True):  # one vectorized call over the table of depths
        ks, cgs = (np.asarray(a) for a in jax.vmap(lambda h: _k_cg_traced(omega, water, h))(jnp.asarray(table_h)))

    def local(xq):
        h = np.interp(xq, xs, hs)
        k = np.interp(h, table_h, ks) if table_h.size > 1 else ks[0]
        cg = np.interp(h, table_h, cgs) if table_h.size > 1 else cgs[0]
        return k, (omega / k) * cg

    def rhs(xq, y):  # y = (η, P η'), complex as 4 reals
        k, p = local(xq)
        eta, q = y[0] + 1j * y[1], y[2] + 1j * y[3]
        d_eta, d_q = q / p, -k * k * p * eta
        return [d_eta.real, d_eta.imag, d_q.real, d_q.imag]

    k0, p0 = local(xs[0])
    k1, p1 = local(xs[-1])
    start = np.exp(1j * k1 * xs[-1])
    y1 = [start.real, start.imag, (1j * k1 * p1 * start).real, (1j * k1 * p1 * start).imag]
    sol = solve_ivp(rhs, (xs[-1], xs[0]), y1, method="DOP853", rtol=1e-10, atol=1e-12)
    eta0 = sol.y[0, -1] + 1j * sol.y[1, -1]
    deta0 = (sol.y[2, -1] + 1j * sol.y[3, -1]) / p0
    incident = 0.5 * (eta0 + deta0 / (1j * k0)) * np.exp(-1j * k0 * xs[0])
    reflected = 0.5 * (eta0 - deta0 / (1j * k0)) * np.exp(1j * k0 * xs[0])
    return float(1.0 / abs(incident)), float(abs(reflected) / abs(incident))
