r"""Exact solutions of the nonlinear shallow-water equations, and the solitary-wave run-up law.

These are what the finite-volume solver (:mod:`wavephys.simulation.shallow_water`) and the
virtual pipes (:mod:`wavephys.models.pipes`) are measured against (docs/physics.md §1.13; the
SWASHES compilation of Delestre et al. 2013 lists them):

* :func:`ritter` — a dam of depth h₀ released on a dry flat bed: the front runs at 2√(gh₀);
* :func:`stoker` — the same on a wet bed of depth h_r: a rarefaction, a flat middle state and a
  bore whose speed follows from the depth ratio (Rankine–Hugoniot);
* :func:`thacker` — a planar surface rocking in a paraboloid bowl, with a moving shoreline
  (a wet/dry front), periodic in time;
* :func:`carrier_greenspan` — a periodic standing wave on a plane beach, exact at finite amplitude
  (Carrier & Greenspan's hodograph transform, in the form of Mungkasi & Roberts 2012);
  its maximum run-up is the linear theory's;
* :func:`solitary_runup` — Synolakis' law R/d = 2.831 √(cot β) (H/d)^{5/4} for non-breaking
  solitary waves on a plane beach (asymptotic: for a beach long against the wave), and
  :func:`solitary_runup_linear`, the exact linear run-up it approximates (which the nonlinear
  maximum run-up equals, Carrier & Greenspan's result); :func:`solitary_wave`, the wave.

References
----------
A. Ritter (1892). Die Fortpflanzung der Wasserwellen. *Z. Ver. Deutsch. Ing.* 36, 947–954.
J. J. Stoker (1957). *Water Waves*, ch. 10. W. C. Thacker (1981). Some exact solutions to the
nonlinear shallow-water wave equations. *J. Fluid Mech.* 107, 499–508. G. F. Carrier &
H. P. Greenspan (1958). Water waves of finite amplitude on a sloping beach. *J. Fluid Mech.* 4,
97–109. S. Mungkasi & S. G. Roberts (2012). *Int. J. Numer. Meth. Fluids* 69(4), 763–780.
C. E. Synolakis (1987). The runup of solitary waves. *J. Fluid Mech.* 185, 523–545.
O. Delestre et al. (2013). SWASHES: a compilation of shallow water analytic solutions.
*Int. J. Numer. Meth. Fluids* 72(3), 269–300.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq
from scipy.special import j0, j1

from wavephys.core.inputs import check_array, check_int, check_scalar

__all__ = ["water_depth", "ritter", "stoker", "stoker_middle", "thacker", "thacker_period", "carrier_greenspan",
           "carrier_greenspan_runup", "solitary_wave", "solitary_potential", "solitary_runup", "solitary_runup_linear", "solitary_rundown_linear", "solitary_breaking_limit"]


def water_depth(bed, eta=None, depth=None):
    """The depth of water over a bed, from its surface (h = max(η − b, 0): land above η is dry) or given directly.

    Parameters
    ----------
    bed : array_like (ny, nx)
        Bed elevation b, m.
    eta : float or array_like (ny, nx), optional
        Surface elevation, m.
    depth : array_like (ny, nx), optional
        Depth, m, ≥ 0, instead of ``eta``.

    Returns
    -------
    numpy.ndarray (ny, nx)
        m, float64.

    Examples
    --------
    >>> water_depth([[0.0, 1.0]], 0.5).tolist()
    [[0.5, 0.0]]
    """
    check_array("bed", bed, ndim=2)
    shape = np.shape(bed)
    if (eta is None) == (depth is None):
        raise ValueError("give exactly one of eta (surface elevation) and depth")
    if depth is not None:
        return np.asarray(check_array("depth", depth, ndim=2, shape_tail=shape, lo=0.0), np.float64)
    check_array("eta", eta)
    if np.ndim(eta) not in (0, 2) or (np.ndim(eta) == 2 and np.shape(eta) != shape):
        raise ValueError(f"eta must be a number or have the bed's shape {shape}, got shape {np.shape(eta)}")
    return np.maximum(np.asarray(eta, np.float64) - np.asarray(bed, np.float64), 0.0)


def ritter(x, t: float, h0: float, g: float = 9.81):
    """Ritter's dam break on a dry bed: depth and velocity at x (dam at x = 0, water at x < 0).

    h = h₀ for x ≤ −c₀t; h = (4/9g)(c₀ − x/2t)², u = (2/3)(c₀ + x/t) in the fan −c₀t < x < 2c₀t; dry
    beyond the front x = 2c₀t (c₀ = √(gh₀)).

    Parameters
    ----------
    x : array_like
        m.
    t : float
        s, > 0.
    h0 : float
        Depth behind the dam, m, > 0.
    g : float
        m/s².

    Returns
    -------
    (h, u) : ndarray
        m and m/s.

    Examples
    --------
    >>> h, u = ritter([-10.0, 0.0, 100.0], 1.0, 1.0)
    >>> [round(float(v), 4) for v in h]
    [1.0, 0.4444, 0.0]
    """
    x = np.asarray(check_array("x", x), np.float64)
    check_scalar("t", t, lo=0.0, lo_open=True)
    check_scalar("h0", h0, lo=0.0, lo_open=True)
    check_scalar("g", g, lo=0.0, lo_open=True)
    c0 = math.sqrt(g * h0)
    fan = (x > -c0 * t) & (x < 2 * c0 * t)
    h = np.where(x <= -c0 * t, h0, np.where(fan, (4.0 / (9.0 * g)) * (c0 - x / (2.0 * t)) ** 2, 0.0))
    u = np.where(fan, (2.0 / 3.0) * (c0 + x / t), 0.0)
    return h, u


def stoker_middle(hl: float, hr: float, g: float = 9.81):
    """The middle state of Stoker's dam break: (depth h_m, velocity u_m, bore speed s).

    Solves 2(c_l − c_m) = (h_m − h_r)·√(g(h_m + h_r)/(2 h_m h_r)) (the rarefaction's Riemann
    invariant meets the bore's Rankine–Hugoniot condition); s = h_m u_m / (h_m − h_r).

    Parameters
    ----------
    hl, hr : float
        Depths behind and ahead of the dam, m, hl > hr > 0.
    g : float
        m/s².

    Returns
    -------
    (float, float, float)
        m, m/s, m/s.
    """
    check_scalar("hl", hl, lo=0.0, lo_open=True)
    check_scalar("hr", hr, lo=0.0, lo_open=True)
    check_scalar("g", g, lo=0.0, lo_open=True)
    if not hr < hl:
        raise ValueError(f"hr must be below hl (the dam holds the deeper water on the left), got hl={hl}, hr={hr}")
    cl = math.sqrt(g * hl)

    def gap(hm):
        return 2 * (cl - math.sqrt(g * hm)) - (hm - hr) * math.sqrt(g * (hm + hr) / (2 * hm * hr))

    hm = brentq(gap, hr, hl, xtol=1e-15 * hl, rtol=1e-15)
    um = 2 * (cl - math.sqrt(g * hm))
    return hm, um, hm * um / (hm - hr)


def stoker(x, t: float, hl: float, hr: float, g: float = 9.81):
    """Stoker's dam break on a wet bed: depth and velocity at x (dam at x = 0).

    Parameters
    ----------
    x : array_like
        m.
    t : float
        s, > 0.
    hl, hr : float
        Depths behind (x < 0) and ahead of the dam, m, hl > hr > 0.
    g : float
        m/s².

    Returns
    -------
    (h, u) : ndarray

    Examples
    --------
    >>> h, u = stoker([-10.0, 10.0], 1.0, 1.0, 0.1)
    >>> [float(v) for v in h]
    [1.0, 0.1]
    """
    x = np.asarray(check_array("x", x), np.float64)
    check_scalar("t", t, lo=0.0, lo_open=True)
    hm, um, s = stoker_middle(hl, hr, g)
    cl, cm = math.sqrt(g * hl), math.sqrt(g * hm)
    fan = (x > -cl * t) & (x <= (um - cm) * t)
    mid = (x > (um - cm) * t) & (x <= s * t)
    h = np.where(x <= -cl * t, hl, np.where(fan, (4.0 / (9.0 * g)) * (cl - x / (2.0 * t)) ** 2,
                                            np.where(mid, hm, hr)))
    u = np.where(fan, (2.0 / 3.0) * (cl + x / t), np.where(mid, um, 0.0))
    return h, u


def thacker_period(h0: float, a: float, g: float = 9.81) -> float:
    """Period 2π/ω of Thacker's planar oscillation, ω = √(2 g h₀)/a.

    Parameters
    ----------
    h0 : float
        Depth at the bowl's centre, m, > 0.
    a : float
        Radius where the bowl reaches the still level, m, > 0.
    g : float
        m/s².

    Returns
    -------
    float
        s.
    """
    check_scalar("h0", h0, lo=0.0, lo_open=True)
    check_scalar("a", a, lo=0.0, lo_open=True)
    check_scalar("g", g, lo=0.0, lo_open=True)
    return 2 * math.pi * a / math.sqrt(2 * g * h0)


def thacker(x, y, t: float, h0: float = 0.1, a: float = 1.0, shift: float = 0.5, g: float = 9.81):
    """Thacker's planar surface in a paraboloid bowl b = h₀(r²/a² − 1), centred at the origin.

    The surface ζ = (η₀h₀/a²)(2x cos ωt + 2y sin ωt − η₀) stays a plane and turns around the bowl;
    the water is where ζ > b (a disc whose shoreline moves), with the uniform velocity
    u = −η₀ω sin ωt, v = η₀ω cos ωt (η₀ = ``shift``).

    Parameters
    ----------
    x, y : array_like
        m (broadcast together).
    t : float
        s.
    h0 : float
        Depth at the centre of the bowl, m, > 0.
    a : float
        Radius where the bowl reaches the still level, m, > 0.
    shift : float
        η₀, m, > 0: the surface's tilt and the wet disc's orbit grow with it (SWASHES uses 0.5 m with
        a = 1 m; the disc stays inside the bowl while η₀ < a).
    g : float
        m/s².

    Returns
    -------
    (bed, h, u, v) : ndarray
        m, m, m/s, m/s (u, v zero where dry).

    Examples
    --------
    >>> b, h, u, v = thacker(0.0, 0.0, 0.0)
    >>> round(float(h), 6)
    0.075
    """
    x = np.asarray(check_array("x", x), np.float64)
    y = np.asarray(check_array("y", y), np.float64)
    check_scalar("t", t)
    check_scalar("shift", shift, lo=0.0, lo_open=True)
    w = 2 * math.pi / thacker_period(h0, a, g)
    bed = h0 * ((x * x + y * y) / (a * a) - 1.0)
    zeta = shift * h0 / (a * a) * (2 * x * math.cos(w * t) + 2 * y * math.sin(w * t) - shift)
    h = np.maximum(zeta - bed, 0.0)
    wet = h > 0
    u = np.where(wet, -shift * w * math.sin(w * t), 0.0)
    v = np.where(wet, shift * w * math.cos(w * t), 0.0)
    return bed, h, u, v


def _cg_constants(h0, length, amplitude, period, g):
    check_scalar("h0", h0, lo=0.0, lo_open=True)
    check_scalar("length", length, lo=0.0, lo_open=True)
    check_scalar("amplitude", amplitude)
    check_scalar("period", period, lo=0.0, lo_open=True)
    check_scalar("g", g, lo=0.0, lo_open=True)
    tp = period * math.sqrt(g * h0) / length  # dimensionless period
    zero = j0(4 * math.pi / tp)
    if abs(zero) < 1e-3:
        raise ValueError("the offshore end sits on a node of the standing wave (J0(4π/T) ≈ 0): change period or length")
    return tp, amplitude / h0 / zero


def carrier_greenspan_runup(h0: float, length: float, amplitude: float, period: float, g: float = 9.81) -> float:
    """Maximum run-up (shoreline elevation above still water) of :func:`carrier_greenspan`.

    Equals |A|·h₀, the linear standing wave's shoreline amplitude (Carrier & Greenspan 1958).

    Parameters
    ----------
    h0, length, amplitude, period, g : float
        As :func:`carrier_greenspan`.

    Returns
    -------
    float
        m.
    """
    _, big_a = _cg_constants(h0, length, amplitude, period, g)
    return abs(big_a) * h0


def carrier_greenspan(x, t: float, h0: float, length: float, amplitude: float, period: float,
                      g: float = 9.81, samples: int = 4001):
    """Carrier & Greenspan's periodic standing wave on a plane beach, exact for the nonlinear equations.

    The bed is b(x) = h₀(x/L − 1): depth h₀ at x = 0, still shoreline at x = L; the surface at x = 0
    oscillates (to first order) as ``amplitude``·cos(2πt/T). In the hodograph variables (σ, λ),
    u = −A J₁(4πσ/T)·sin(2πλ/T)/σ, w = A J₀(4πσ/T)·cos(2πλ/T) − u²/2, x = 1 + w − σ², t = λ − u
    (dimensionless: x by L, w by h₀, u by √(gh₀), t by L/√(gh₀); A = ε/J₀(4π/T), ε = amplitude/h₀).

    Parameters
    ----------
    x : array_like
        m (dry where beyond the shoreline).
    t : float
        s.
    h0, length, amplitude, period : float
        Depth at x = 0 (m), distance to the still shoreline (m), surface amplitude at x = 0 (m), period (s).
    g : float
        m/s².
    samples : int
        Points in σ (the solution is tabulated and interpolated).

    Returns
    -------
    (eta, u, shoreline) : ndarray, ndarray, float
        Surface elevation (m; the bed where dry), velocity (m/s, towards the shore), and the
        shoreline's position, m.

    Raises
    ------
    ValueError
        If the wave breaks (the hodograph map folds: the nonlinear solution stops being single valued).

    Examples
    --------
    >>> eta, u, xs = carrier_greenspan([0.0], 0.0, 500.0, 5e4, 1.0, 900.0)
    >>> round(float(eta[0]), 3)  # 1 m to first order, plus the nonlinear correction
    1.002
    """
    x = np.asarray(check_array("x", x), np.float64)
    check_scalar("t", t)
    samples = check_int("samples", samples, lo=16)
    tp, big_a = _cg_constants(h0, length, amplitude, period, g)
    tt = t * math.sqrt(g * h0) / length
    k = 4 * math.pi / tp
    om = 2 * math.pi / tp
    sigma = np.linspace(0.0, 1.5 + 2 * abs(big_a), int(samples))
    ratio = np.where(sigma > 0, j1(k * sigma) / np.where(sigma > 0, sigma, 1.0), k / 2)
    lam = np.full_like(sigma, tt)
    for _ in range(200):  # λ = t + u(σ, λ): a contraction while the wave does not break
        lam_new = tt - big_a * ratio * np.sin(om * lam)
        if np.max(np.abs(lam_new - lam)) < 1e-14:
            lam = lam_new
            break
        lam = lam_new
    u = -big_a * ratio * np.sin(om * lam)
    w = big_a * j0(k * sigma) * np.cos(om * lam) - 0.5 * u * u
    xs = 1.0 + w - sigma * sigma
    if np.any(np.diff(xs) >= 0):
        raise ValueError("the Carrier–Greenspan wave breaks at these parameters (the solution folds): lower amplitude")
    # xs decreases with σ: interpolate on the reversed arrays
    xd = x / length
    shore = xs[0]
    eta = np.interp(xd, xs[::-1], w[::-1])
    vel = np.interp(xd, xs[::-1], u[::-1])
    dry = xd > shore
    bed = xd - 1.0
    eta = np.where(dry, bed, eta) * h0
    vel = np.where(dry, 0.0, vel) * math.sqrt(g * h0)
    return eta, vel, shore * length


def solitary_wave(x, h: float, d: float, x0: float, g: float = 9.81):
    """A solitary wave of height H on depth d centred at x0, travelling towards −x: (η, u) (its potential for the
    linear steppers: :func:`solitary_potential`).

    η = H sech²(γ(x − x₀)/d), γ = √(3H/4d); u = −√(g/d)·η (the long-wave relation the run-up
    benchmarks start from; Synolakis 1987).

    Parameters
    ----------
    x : array_like
        m.
    h : float
        Height H, m, > 0.
    d : float
        Depth, m, > 0.
    x0 : float
        Crest position, m.
    g : float
        m/s².

    Returns
    -------
    (eta, u) : ndarray
    """
    x, gamma = _solitary_inputs(x, h, d, x0, g)
    eta = h / np.cosh(gamma * (x - x0) / d) ** 2
    return eta, -math.sqrt(g / d) * eta


def _solitary_inputs(x, h, d, x0, g):
    """The solitary wave's inputs checked by name, and x as float64 with γ = √(3H/4d)."""
    x = np.asarray(check_array("x", x), np.float64)
    check_scalar("h", h, lo=0.0, lo_open=True)
    check_scalar("d", d, lo=0.0, lo_open=True)
    check_scalar("x0", x0)
    check_scalar("g", g, lo=0.0, lo_open=True)
    return x, math.sqrt(3 * h / (4 * d))


def solitary_potential(x, h: float, d: float, x0: float, g: float = 9.81):
    """The surface potential of :func:`solitary_wave` for the linear depth steppers, whose state is (η, φ) with
    u = ∂φ/∂x: φ = −√(g/d)·H·(d/γ)·tanh(γ(x − x₀)/d), m²/s (u = −√(g/d)·η integrated exactly; φ's constant
    is free, chosen so that φ is odd about the crest).

    With ``solitary_wave``'s η it starts a wave that runs towards −x alone (the long-wave relation; the linear
    dispersive steppers shed a tail of order (γ)² from it).

    Parameters
    ----------
    x, h, d, x0, g
        As :func:`solitary_wave` (m; H, d > 0; crest position; m/s²).

    Returns
    -------
    ndarray
        φ at ``x``, m²/s.

    Examples
    --------
    >>> import numpy as np
    >>> x = np.linspace(-40.0, 40.0, 8001)
    >>> eta, u = solitary_wave(x, 0.02, 1.0, 0.0)
    >>> phi = solitary_potential(x, 0.02, 1.0, 0.0)
    >>> bool(np.abs(np.gradient(phi, x) - u).max() < 1e-6)
    True
    """
    x, gamma = _solitary_inputs(x, h, d, x0, g)
    return -math.sqrt(g / d) * h * (d / gamma) * np.tanh(gamma * (x - x0) / d)


def solitary_breaking_limit(cot_beta: float) -> float:
    """The largest H/d that runs up a beach of slope 1/cot β without breaking: 0.818 (cot β)^(−10/9) (Synolakis 1987).

    Parameters
    ----------
    cot_beta : float
        > 0.

    Returns
    -------
    float
        Dimensionless.
    """
    check_scalar("cot_beta", cot_beta, lo=0.0, lo_open=True)
    return 0.818 * cot_beta ** (-10.0 / 9.0)


def solitary_runup(h: float, d: float, cot_beta: float) -> float:
    """Maximum run-up R of a non-breaking solitary wave on a plane beach: R = 2.831 d √(cot β) (H/d)^{5/4}, m.

    Parameters
    ----------
    h : float
        Wave height H, m, > 0, with H/d below :func:`solitary_breaking_limit`.
    d : float
        Depth of the flat floor before the beach, m, > 0.
    cot_beta : float
        Beach slope as cot β (19.85: the NTHMP benchmark), > 0.

    Returns
    -------
    float
        m.

    Examples
    --------
    >>> round(solitary_runup(0.0185, 1.0, 19.85), 4)
    0.0861
    """
    check_scalar("h", h, lo=0.0, lo_open=True)
    check_scalar("d", d, lo=0.0, lo_open=True)
    check_scalar("cot_beta", cot_beta, lo=0.0, lo_open=True)
    if h / d > solitary_breaking_limit(cot_beta):
        raise ValueError(f"h / d = {h / d:.4g} breaks on a beach of cot_beta = {cot_beta} (the limit there is "
                         f"{solitary_breaking_limit(cot_beta):.4g}): the law holds for non-breaking waves only")
    return 2.831 * d * math.sqrt(cot_beta) * (h / d) ** 1.25


def solitary_runup_linear(h: float, d: float, cot_beta: float, samples: int = 65536) -> float:
    """Maximum run-up of a solitary wave on a plane beach joined to a flat floor, by the exact linear theory, m.

    Each frequency ω of the wave arriving at the toe (x₀ = d·cot β from the shoreline) reaches the
    shoreline multiplied by 2/(J₀(2kx₀) + i J₁(2kx₀)), k = ω/√(gd) (the standing wave J₀(2k√(x₀x))
    on the beach matched to the flat floor; Synolakis 1987, eq. 2.10). The run-up is the maximum
    over time of that sum. For γx₀ ≫ 1 (γ = √(3H/4d)) it tends to :func:`solitary_runup`; on
    shorter beaches the law underestimates it (measured: −11 % at cot β = 10, H/d = 0.005).

    Parameters
    ----------
    h, d, cot_beta : float
        Wave height and depth (m, > 0), beach slope as cot β (> 0).
    samples : int
        FFT length in time (≥ 1024).

    Returns
    -------
    float
        m.

    Examples
    --------
    >>> round(solitary_runup_linear(0.0185, 1.0, 19.85), 4)
    0.0883
    """
    return float(_linear_shoreline(h, d, cot_beta, samples).max())


def solitary_rundown_linear(h: float, d: float, cot_beta: float, samples: int = 65536) -> float:
    """Maximum run-down (the shoreline's lowest elevation, ≤ 0) of a solitary wave on a plane beach joined to a
    flat floor, by the exact linear theory, m: the minimum over time of the shoreline series whose maximum is
    :func:`solitary_runup_linear` (Synolakis 1987). By Carrier & Greenspan's transform the shoreline's extreme
    excursions of the nonlinear solution are the linear ones (where the shoreline stops, u = 0, the transform's
    shift u²/2 vanishes), so a non-breaking wave's nonlinear run-down is this value too.

    Parameters
    ----------
    h, d, cot_beta, samples
        As :func:`solitary_runup_linear` (m, m, cot β; FFT length in time, ≥ 1024).

    Returns
    -------
    float
        m, ≤ 0.

    Examples
    --------
    >>> round(solitary_rundown_linear(0.01, 1.0, 19.85), 4) < 0
    True
    """
    return float(_linear_shoreline(h, d, cot_beta, samples).min())


def _linear_shoreline(h, d, cot_beta, samples):
    """The shoreline's elevation over time by the exact linear theory (module doc of the run-up), m."""
    check_scalar("h", h, lo=0.0, lo_open=True)
    check_scalar("d", d, lo=0.0, lo_open=True)
    check_scalar("cot_beta", cot_beta, lo=0.0, lo_open=True)
    n = check_int("samples", samples, lo=1024)
    g = 9.81  # the run-up in units of d does not depend on g; any value gives the same R
    gamma = math.sqrt(3 * h / (4 * d))
    c = math.sqrt(g * d)
    x0 = d * cot_beta
    span = 400 * d / (gamma * c) + 8 * x0 / c
    t = (np.arange(n) - n // 2) * span / n
    eta = h / np.cosh(gamma * c * t / d) ** 2
    w = 2 * np.pi * np.fft.fftfreq(n, span / n)
    z = 2 * np.abs(w) / c * x0
    transfer = 2.0 / (j0(z) + 1j * np.sign(w) * j1(z))
    return np.fft.ifft(np.fft.fft(eta) * transfer).real
