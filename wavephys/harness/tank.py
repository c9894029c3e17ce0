"""A user's tank measured against its seiches: the cosine modes of a record whose edges are walls.

A record that spans the water between four reflecting walls, with samples at cell centres (the
texel convention: walls half a sample outside the first and last samples), is a sum of the
tank's modes cos(mπx'/Lx)·cos(qπy'/Ly), each oscillating at its own seiche frequency ω(k_mq),
k_mq = π√((m/Lx)² + (q/Ly)²), Lx = n_x·dx (docs/physics.md §1.11). :func:`measure_seiches`
projects every frame on these modes (the type-II cosine transform) and fits each strong mode's
time series by a damped cosine: its frequency and its decay rate. :func:`seiche_check` compares
the frequencies with theory and, when they disagree, names the likeliest cause (a periodic wrap,
walls on the first and last samples, a non-dispersive solver, a constant factor on ω, or fields
that are not tank modes at all); :func:`wall_reflection_check` turns the decay rates into the
amplitude kept per reflection, R = exp(−γ/ν), ν the rate at which the mode's waves meet a wall.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from wavephys.core.inputs import check_array, check_instance, check_int, check_scalar
from wavephys.core.spectral import cosine_transform
from wavephys.core.water import Water

__all__ = ["Seiches", "measure_seiches", "seiche_check", "wall_reflection_check", "looks_like_tank"]

MIN_PERIODS = 2.0
"""A mode is fitted only when the record holds at least this many of its periods."""
MAX_RESIDUAL = 0.05
"""Largest rms misfit of a damped cosine (relative to the mode's rms) for a mode to count as a tank mode."""


@dataclass(frozen=True)
class Seiches:
    """The strong modes of a tank record, each fitted by a damped cosine.

    Attributes
    ----------
    m, q : numpy.ndarray of int
        Mode numbers along x and y.
    k : numpy.ndarray
        k_mq, rad/m.
    omega : numpy.ndarray
        Fitted angular frequency, rad/s.
    gamma : numpy.ndarray
        Fitted amplitude decay rate, 1/s (negative: growing).
    share : numpy.ndarray
        Each mode's share of the record's mean η² (all modes but the mean).
    residual : numpy.ndarray
        rms misfit of the fit over the mode's rms, dimensionless.
    length : (float, float)
        (Lx, Ly) = (n_x·dx, n_y·dx), m.
    dx : float
        Sample spacing, m.
    """

    m: np.ndarray
    q: np.ndarray
    k: np.ndarray
    omega: np.ndarray
    gamma: np.ndarray
    share: np.ndarray
    residual: np.ndarray
    length: tuple
    dx: float = 0.0


def _fit(series, dt):
    """(ω, γ, residual) of a·e^{−γt}cos(ωt) + b·e^{−γt}sin(ωt) + c fitted to ``series``."""
    from scipy.optimize import least_squares

    nt = series.size
    t = np.arange(nt) * dt
    centred = series - series.mean()
    pad = 16 * nt
    spectrum = np.abs(np.fft.rfft(centred * np.hanning(nt), pad))
    spectrum[0] = 0.0
    peak = int(np.argmax(spectrum))
    omega0 = 2 * math.pi * peak / (pad * dt)
    if not omega0 > 0:
        return math.nan, math.nan, math.inf

    def misfit(p):
        w, g, a, b, c = p
        e = np.exp(-g * t)
        return e * (a * np.cos(w * t) + b * np.sin(w * t)) + c - series

    scale = float(np.sqrt(np.mean(centred ** 2))) or 1.0
    basis = np.stack([np.cos(omega0 * t), np.sin(omega0 * t), np.ones_like(t)], 1)
    a, b, c = np.linalg.lstsq(basis, series, rcond=None)[0]  # the amplitudes at the spectrum's peak, undamped
    fit = least_squares(misfit, [omega0, 0.0, a, b, c], x_scale=[omega0, 1.0 / t[-1], scale, scale, scale])
    w, g = fit.x[:2]
    return abs(float(w)), float(g), float(np.sqrt(np.mean(fit.fun ** 2)) / scale)


def measure_seiches(eta, dx: float, dt: float, modes: int = 8) -> Seiches:
    """The ``modes`` strongest tank modes of a record, each fitted by a damped cosine in time.

    Parameters
    ----------
    eta : array_like (n_t, n_y, n_x)
        Heights, m, of water between four walls, samples at cell centres (any n_x, n_y ≥ 2), n_t ≥ 8.
    dx : float
        Sample spacing, m, > 0.
    dt : float
        Time between frames, s, > 0.
    modes : int
        How many of the strongest modes to fit, ≥ 1 (those holding at least 1e-3 of the power and at least
        :data:`MIN_PERIODS` periods within the record; fewer if fewer do).

    Returns
    -------
    Seiches
    """
    check_array("eta", eta, ndim=3)
    eta = np.asarray(eta, np.float64)
    if eta.ndim != 3 or eta.shape[0] < 8 or min(eta.shape[1:]) < 2:
        raise ValueError(f"eta must be frames (n_t >= 8, n_y >= 2, n_x >= 2), got shape {eta.shape}")
    dx = check_scalar("dx", dx, lo=0.0, lo_open=True)
    dt = check_scalar("dt", dt, lo=0.0, lo_open=True)
    modes = check_int("modes", modes, lo=1)
    nt, ny, nx = eta.shape
    peak = float(np.max(np.abs(eta)))
    eta = eta / peak if peak > 0 else eta  # frequencies, decay and shares do not depend on the scale
    coeff = cosine_transform(cosine_transform(eta, -1), -2)
    weight = np.where(np.arange(ny) == 0, 1.0, 2.0)[:, None] * np.where(np.arange(nx) == 0, 1.0, 2.0)[None, :]
    power = weight * np.mean(coeff ** 2, axis=0)
    power[0, 0] = 0.0
    total = power.sum()
    lx, ly = nx * dx, ny * dx
    q_all, m_all = np.meshgrid(np.arange(ny), np.arange(nx), indexing="ij")
    k_all = math.pi * np.hypot(m_all / lx, q_all / ly)
    order = np.argsort(power, axis=None)[::-1]
    rows = []
    duration = (nt - 1) * dt
    for flat in order:
        if len(rows) >= modes or not total > 0 or power.flat[flat] < 1e-3 * total:
            break
        q, m = np.unravel_index(flat, power.shape)
        omega, gamma, residual = _fit(coeff[:, q, m], dt)
        if not (omega * duration >= 2 * math.pi * MIN_PERIODS and omega * dt < math.pi):
            continue
        rows.append((m, q, k_all[q, m], omega, gamma, power[q, m] / total, residual))
    cols = list(zip(*rows)) if rows else [[]] * 7
    arr = [np.asarray(c, dtype=float) for c in cols]
    return Seiches(arr[0].astype(int), arr[1].astype(int), arr[2], arr[3], arr[4], arr[5], arr[6], (lx, ly), dx)


def _theory(k, water):
    import jax
    import jax.numpy as jnp

    from wavephys.physics.dispersion import angular_frequency, group_speed

    with jax.enable_x64(True):
        kk = jnp.asarray(np.maximum(k, 1e-12), jnp.float64)
        return np.asarray(angular_frequency(kk, water)), np.asarray(group_speed(kk, water))


def _error(measured, expected, share):
    rel = measured / expected - 1.0
    return float(rel[np.argmax(np.abs(rel))]), float(np.sum(share * np.abs(rel)) / np.sum(share))


def _speed_and_depth(s: Seiches, water: Water, misfit) -> list:
    """Fitted explanations: one speed for every mode (a non-dispersive solver: which depth √(g h) that speed is,
    against the claimed one), and water of another depth (the dispersive relation at a fitted h)."""
    from dataclasses import replace

    from wavephys.harness.dispersion import _refine

    found = []
    g = float(water.g)
    depth = float(water.depth)
    claimed = f"{depth:.4g} m" if math.isfinite(depth) else "deep water"
    weights = s.share / s.share.sum()
    c = float(np.sum(weights * s.omega / s.k))
    h = c * c / g
    same = math.isfinite(depth) and abs(h / depth - 1) < 0.02
    found.append((misfit(c * s.k), f"every mode has omega = c k with one speed c = {c:.4g} m/s: a non-dispersive "
                                   f"solver (shallow water, virtual pipes, a wave equation) where theory's waves are "
                                   f"dispersive (k h up to {float(s.k.max() * h):.3g}); c = sqrt(g h) for h = "
                                   f"{h:.4g} m" + (f", the claimed depth" if same else f", where the claimed depth is "
                                                   f"{claimed} (sqrt(g h) = {math.sqrt(g * depth):.4g} m/s)"
                                                   if math.isfinite(depth) else ", and the water is claimed deep")))
    best, fitted = _refine(lambda d: misfit(_theory(s.k, replace(water, depth=d))[0]), 0.05 / float(s.k.max()),
                           20.0 / float(s.k.min()))
    if not (math.isfinite(depth) and abs(fitted / depth - 1) < 0.02):
        found.append((best, f"the modes ring as water {fitted:.4g} m deep, not the claimed {claimed}: claim that "
                            f"depth (depth=, --depth), or the solver's depth is off"))
    return found


def _seiche_cause(s: Seiches, water: Water, rtol: float) -> str:
    """The explanation of measured seiche frequencies that fits best, in words."""
    k_periodic = 2 * s.k
    lx, ly = s.length
    ratio = s.omega / _theory(s.k, water)[0]
    candidates = []
    if float(s.share[s.residual <= MAX_RESIDUAL].sum()) < 0.5 * float(s.share.sum()):
        return (f"the modes do not oscillate at one frequency each (median misfit {np.median(s.residual):.2g} of "
                f"a damped cosine): the record is not a sum of a tank's standing modes (edges that wrap around "
                f"periodically, clamp the height, or absorb)")
    misfit = lambda w: float(np.sum(s.share * np.abs(s.omega / w - 1.0)) / np.sum(s.share))  # power-weighted
    candidates.append((misfit(_theory(k_periodic, water)[0]),
                       "the frequencies are those of modes twice as short, 2k: the record's edges wrap around "
                       "(a periodic domain) instead of reflecting"))
    k_nodes = math.pi * np.hypot(s.m / (lx - s.dx), s.q / (ly - s.dx))
    candidates.append((misfit(_theory(k_nodes, water)[0]),
                       f"the frequencies are those of a tank {s.dx:.4g} m shorter: the walls sit on the first and "
                       f"last samples (vertex-centred grid), not half a sample outside them; give the record's "
                       f"frames cell-centred, or check it as a tank of (n - 1) dx"))
    candidates += _speed_and_depth(s, water, misfit)
    if np.ptp(ratio) <= 0.2 * rtol * max(1.0, float(np.mean(ratio))) and abs(float(np.mean(ratio)) - 1) > rtol:
        f = float(np.mean(ratio))
        candidates.append((0.0, f"every mode's frequency is off by the same factor {f:.5g} (= {f * f:.5g}^(1/2)): "
                                f"gravity, the time step or the length unit is off (f^2 = {f * f:.4g} times g)"))
    best = min(candidates, key=lambda c: c[0])
    if best[0] <= rtol and best[1]:
        return best[1]
    return "the frequencies fit neither theory nor a periodic wrap, a non-dispersive solver or a constant factor"


def seiche_check(record, water: Water, *, rtol: float = 0.01, modes: int = 8):
    """A :class:`~wavephys.harness.Check` that a tank record's standing modes ring at their seiche frequencies.

    The record's edges are taken as reflecting walls half a sample outside the first and last samples
    (:func:`measure_seiches`). The row is the worst relative error of the fitted frequencies against
    ω(k_mq) of linear theory for the record's water; on failure the note names the likeliest cause.

    Parameters
    ----------
    record : Record
        The frames (:class:`wavephys.harness.Record`), at least 8, covering 2 periods of the modes checked.
    water : Water
        The water of the theory (g, σ, ρ and the tank's depth).
    rtol : float, optional, keyword-only
        Largest relative frequency error, > 0 (default 0.01).
    modes : int, optional, keyword-only
        Strongest modes fitted, ≥ 1 (default 8).

    Returns
    -------
    Check
        A ``"~="`` row of the worst relative error against 0 (absolute tolerance ``rtol``).

    References
    ----------
    H. Lamb (1932). *Hydrodynamics*, §191 (docs/physics.md §1.11).
    """
    from wavephys.harness.checks import compare
    from wavephys.harness.record import Record

    check_instance("record", record, Record, "wavephys.harness.Record")
    check_instance("water", water, Water, "wavephys.Water")
    check_scalar("rtol", rtol, lo=0.0, lo_open=True)
    s = measure_seiches(record.eta, record.dx, record.dt, modes)
    quantity = "worst relative error of the tank's seiche frequencies against omega(k_mn)"
    if s.k.size == 0:
        return compare(quantity, math.nan, 0.0, atol=rtol,
                       note="no mode holds 1e-3 of the power and 2 periods within the record: record longer, or "
                            "excite the tank")
    good = s.residual <= MAX_RESIDUAL
    modes_text = ", ".join(f"({m},{q})" for m, q in zip(s.m[good], s.q[good]))
    note = (f"{int(good.sum())} of the {s.k.size} strongest modes ring at one frequency ({modes_text or 'none'}) "
            f"in a {s.length[0]:.4g} x {s.length[1]:.4g} m tank, {float(s.share[good].sum()):.3g} of the power")
    if float(s.share[good].sum()) < 0.5 * float(s.share.sum()):
        return compare(quantity, math.nan, 0.0, atol=rtol, note=f"{note}; likely cause: {_seiche_cause(s, water, rtol)}")
    s = Seiches(*(a[good] for a in (s.m, s.q, s.k, s.omega, s.gamma, s.share, s.residual)), s.length, s.dx)
    worst, _ = _error(s.omega, _theory(s.k, water)[0], s.share)
    row = compare(quantity, worst, 0.0, atol=rtol, note=note)
    if not row.ok:
        row = compare(quantity, worst, 0.0, atol=rtol, note=f"{note}; likely cause: {_seiche_cause(s, water, rtol)}")
    return row


def wall_reflection_check(record, water: Water, *, tolerance: float = 0.01, modes: int = 8):
    """A :class:`~wavephys.harness.Check` that a tank's walls reflect all of a wave's amplitude.

    A standing mode (m, q) is made of plane waves that meet a wall ν = |c_g,x|/Lx + |c_g,y|/Ly times a
    second (c_g from theory); a mode whose amplitude decays at γ keeps R = exp(−γ/ν) per reflection. The
    row is the smallest R of the fitted modes against 1. Damping inside the water is counted as loss at
    the walls here (the energy row tells them apart: it names damping that depends on k alone).

    Parameters
    ----------
    record : Record
        The frames of water between four walls.
    water : Water
        The water of the theory.
    tolerance : float, optional, keyword-only
        Largest amplitude lost per reflection, 1 − R, > 0 (default 0.01).
    modes : int, optional, keyword-only
        Strongest modes fitted, ≥ 1 (default 8).

    Returns
    -------
    Check
        A ``"~="`` row of the smallest R against 1 (absolute tolerance ``tolerance``).
    """
    from wavephys.harness.checks import compare
    from wavephys.harness.record import Record

    check_instance("record", record, Record, "wavephys.harness.Record")
    check_instance("water", water, Water, "wavephys.Water")
    check_scalar("tolerance", tolerance, lo=0.0, lo_open=True)
    s = measure_seiches(record.eta, record.dx, record.dt, modes)
    quantity = "smallest amplitude reflection coefficient R of the tank's walls"
    if s.k.size == 0:
        return compare(quantity, math.nan, 1.0, atol=tolerance, note="no mode to measure (see the seiche row)")
    good = s.residual <= MAX_RESIDUAL
    if not good.any():
        return compare(quantity, math.nan, 1.0, atol=tolerance,
                       note="no mode rings at one frequency: not a tank's standing modes (see the seiche row)")
    s = Seiches(*(a[good] for a in (s.m, s.q, s.k, s.omega, s.gamma, s.share, s.residual)), s.length, s.dx)
    _, cg = _theory(s.k, water)
    lx, ly = s.length
    kx, ky = math.pi * s.m / lx, math.pi * s.q / ly
    nu = cg * (np.abs(kx) / lx + np.abs(ky) / ly) / np.maximum(s.k, 1e-300)
    r = np.exp(-s.gamma / nu)
    worst = int(np.argmin(r))
    note = (f"{s.k.size} modes; the weakest reflection at mode ({s.m[worst]},{s.q[worst]}): decay "
            f"{s.gamma[worst]:.3g} 1/s over {nu[worst]:.3g} wall hits per second")
    row = compare(quantity, float(r[worst]), 1.0, atol=tolerance, note=note)
    if not row.ok and r[worst] < 1:
        row = compare(quantity, float(r[worst]), 1.0, atol=tolerance,
                      note=f"{note}; likely cause: the walls absorb part of each wave (a sponge or cutoff at the "
                           f"edges, clamped heights) or the water damps it (see the energy row)")
    elif not row.ok:
        row = compare(quantity, float(r[worst]), 1.0, atol=tolerance,
                      note=f"{note}; likely cause: the modes grow (an unstable scheme or a forcing)")
    return row


def looks_like_tank(record, water: Water) -> str:
    """Why ``record`` looks like water between four reflecting walls, in words, or "" if it does not: its
    strongest cosine modes each ring at one frequency (median misfit ≤ :data:`MAX_RESIDUAL`) and its edges
    are antinodes (η² in the edge rows and columns at least 1.5 times the interior's, as walls make).

    Parameters
    ----------
    record : Record
        The frames.
    water : Water
        The water of the theory (unused by the signatures, kept for the checks' common signature).

    Returns
    -------
    str
        The signatures found, in words; "" when the record does not look like a tank.
    """
    from wavephys.harness.record import Record

    check_instance("record", record, Record, "wavephys.harness.Record")
    check_instance("water", water, Water, "wavephys.Water")
    eta = np.asarray(record.eta, np.float64)
    if eta.shape[0] < 8 or min(eta.shape[1:]) < 8:
        return ""
    inner = float(np.mean(eta[:, 2:-2, 2:-2] ** 2))
    edges = [float(np.mean(e ** 2)) for e in (eta[:, 0, 2:-2], eta[:, -1, 2:-2], eta[:, 2:-2, 0], eta[:, 2:-2, -1])]
    if not inner > 0 or min(edges) < 1.5 * inner:
        return ""
    s = measure_seiches(eta, record.dx, record.dt, 8)
    if s.k.size == 0 or float(np.median(s.residual)) > MAX_RESIDUAL:
        return ""
    return (f"its edges are antinodes, {min(edges) / inner:.2g}x the interior's eta^2, and its {s.k.size} strongest "
            f"cosine modes each ring at one frequency")
