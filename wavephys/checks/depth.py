"""Validations of waves over a varying floor (docs/physics.md §1.12): a packet's shoaling up a ramp by
each stepper against the mild-slope reference, and Lamb's standing wave on a plane beach."""

from __future__ import annotations

import math
from typing import Optional

import numpy as np

from wavephys.core.grid import Grid
from wavephys.core.water import Water
from wavephys.harness.checks import Check, bound

__all__ = ["travelling_packet", "packet_potential", "measure_shoaling", "lamb_beach_error", "lamb_shoreline_errors", "check_depth"]

G = 9.81


def travelling_packet(grid: Grid, analytic, method: str, depth: float):
    """(η, φ) of a packet travelling along its wave vectors: η = Re a, φ̂ = −i(g/ω(k))·â per Fourier mode, ω the
    method's own (full dispersion at ``depth`` for ``"levels"``, the grid's √(gh) for ``"shallow"``).

    Parameters
    ----------
    grid : Grid
    analytic : array_like (n, n), complex
        The packet's analytic field a (envelope × e^{i k·x}), m.
    method : {"levels", "shallow"}
    depth : float
        m, > 0.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        η, m, and φ, m²/s.
    """
    from wavephys.physics.dispersion import angular_frequency

    dx = float(grid.dx)
    ky, kx = (np.asarray(a) for a in grid.wavenumbers())
    k = np.hypot(kx, ky)
    if method == "levels":
        omega = np.asarray(angular_frequency(k, Water(sigma=0.0, depth=depth)))
    else:
        omega = 2 * math.sqrt(G * depth) / dx * np.sqrt(np.sin(kx * dx / 2) ** 2 + np.sin(ky * dx / 2) ** 2)
    spec = np.fft.fft2(np.asarray(analytic))
    phi = np.fft.ifft2(np.where(omega > 0, -1j * G / np.where(omega > 0, omega, 1.0), 0.0) * spec).real
    return np.real(np.asarray(analytic)), phi


def packet_potential(k, analytic, omega):
    """φ of a packet travelling along its wave vectors: φ̂ = −i(g/ω(k))·â per Fourier mode (1-D or 2-D).

    Parameters
    ----------
    k : array_like
        |k| on the FFT's modes of ``analytic`` (rad/m), broadcastable to it.
    analytic : array_like, complex
        The packet's analytic field a (envelope × e^{ik·x}), m.
    omega : callable
        ω(|k|), rad/s (the stepper's own dispersion).

    Returns
    -------
    numpy.ndarray
        φ, m²/s, real, the shape of ``analytic``.
    """
    from wavephys.core.inputs import check_array

    check_array("analytic", analytic, complex_ok=True, min_ndim=1)
    check_array("k", k, lo=0.0)
    if not callable(omega):
        raise TypeError(f"omega must be a function of |k| (rad/m → rad/s), got {type(omega).__name__}")
    a = np.asarray(analytic)
    try:
        np.broadcast_shapes(np.shape(k), a.shape)
    except ValueError:
        raise ValueError(f"k must broadcast to analytic's shape {a.shape}, got {np.shape(k)}") from None
    w = np.asarray(omega(np.asarray(k)))
    spec = np.fft.fftn(a)
    return np.fft.ifftn(np.where(w > 0, -1j * G / np.where(w > 0, w, 1.0), 0.0) * spec).real


def measure_shoaling(method: str, depth0: float, depth1: float, k0: float, per: int, ramp: float = 10.0,
                     sigma: float = 2.0, levels: int = 4, bulk_length: Optional[float] = None):
    """A packet (carrier k₀, envelope σ wavelengths) from depth h₀ up (or down) a ramp of ``ramp`` wavelengths to
    h₁, plane waves along x: (amplitude over the far plateau / incident amplitude, ω).

    Plane waves on one periodic row (:class:`~wavephys.simulation.depth.ProfileStepper`), (50 + max(0, ramp − 10))·σ/2
    wavelengths long; the packet starts 5σ from the left end and 4σ + 1 before the ramp, and the run ends when
    its centre is 2.5σ past the ramp. A packet spreads as it travels (its carrier disperses): over this run a σ =
    2 packet's peak falls by about 5 % at kh = 1–3 by that alone, a σ = 6 packet's by 0.2 %; measure dispersive
    cases with σ ≥ 6.

    Parameters
    ----------
    method : {"levels", "shallow", "symmetric", "split"}
        A stepper of :data:`~wavephys.simulation.depth.DEPTH_METHODS`, or ``"split"``: the split model
        (:mod:`wavephys.simulation.split`, levels at both depths, its default bulk length and taper; it steps
        (h, q) with its own adaptive Δt, float64).
    depth0, depth1 : float
        m, > 0.
    k0 : float
        rad/m, > 0.
    per : int
        Samples per incident wavelength, ≥ 4.
    ramp : float
        Ramp length in incident wavelengths, > 0.
    sigma : float
        Envelope in incident wavelengths, > 0.
    levels : int
        Depth levels of ``"levels"`` and ``"symmetric"``, 1 … 16.
    bulk_length : float, optional
        The split's bulk length, m (default: its own, the deepest level and at least 8 cells); only with
        ``method="split"``.

    Returns
    -------
    (float, float)
        Amplitude ratio, and the carrier's ω (rad/s, the method's own).
    """
    from scipy.signal import hilbert

    from wavephys.core.inputs import check_int, check_scalar
    from wavephys.physics.dispersion import angular_frequency, group_speed, wavenumber
    from wavephys.simulation.depth import DEPTH_METHODS, ProfileState, ProfileStepper

    if method != "split":
        DEPTH_METHODS.check(method, "method")
        if bulk_length is not None:
            raise ValueError(f"bulk_length is the split's (method='split'), got method={method!r}")
    elif bulk_length is not None:
        bulk_length = check_scalar("bulk_length", bulk_length, lo=0.0, lo_open=True)
    depth0 = check_scalar("depth0", depth0, lo=0.0, lo_open=True)
    depth1 = check_scalar("depth1", depth1, lo=0.0, lo_open=True)
    k0 = check_scalar("k0", k0, lo=0.0, lo_open=True)
    per = check_int("per", per, lo=4)
    ramp = check_scalar("ramp", ramp, lo=0.0, lo_open=True)
    sigma = check_scalar("sigma", sigma, lo=0.0, lo_open=True)
    s = sigma / 2
    lam = 2 * math.pi / k0
    waves = 50 * s + max(0.0, ramp - 10)
    n = 2 * int(round(waves * per / 2))
    length = n * lam / per
    dx = length / n
    x = -length / 2 + (np.arange(n) + 0.5) * dx
    xc = -length / 2 + 10 * s * lam
    x0 = xc + 8 * s * lam
    x1 = x0 + ramp * lam
    h = np.clip(depth0 + (depth1 - depth0) * (x - x0) / (x1 - x0), min(depth0, depth1), max(depth0, depth1))
    water = Water(sigma=0.0, depth=depth0)
    k = np.abs(2 * np.pi * np.fft.fftfreq(n, dx))
    if method == "shallow":  # the grid's own ω and group speed ≈ √(gh)
        omega, cg0, cg1 = k0 * math.sqrt(G * depth0), math.sqrt(G * depth0), math.sqrt(G * depth1)
        disp = lambda q: 2 * math.sqrt(G * depth0) / dx * np.abs(np.sin(q * dx / 2))
    else:
        w1 = Water(sigma=0.0, depth=depth1)
        omega = float(angular_frequency(k0, water))
        cg0, cg1 = float(group_speed(k0, water)), float(group_speed(float(wavenumber(omega, w1)), w1))
        disp = lambda q: np.asarray(angular_frequency(q, water))
    dt = 2 * math.pi / omega / 16
    a = 1e-3 * np.exp(-(x - xc) ** 2 / (2 * (sigma * lam) ** 2)) * np.exp(1j * k0 * (x - xc))
    phi = packet_potential(k, a, disp)
    travel = (x0 - xc) / cg0 + (x1 - x0) / (0.5 * (cg0 + cg1)) + 5 * s * lam / cg1
    if method == "split":
        eta = _split_profile(h, dx, a, k, disp, travel, depth0, depth1, bulk_length)
        return float(np.abs(hilbert(eta))[x > x1 + lam].max() / 1e-3), omega
    eta = ProfileStepper(h, dx, water, dt, method, levels).advance(ProfileState(a.real, phi), int(travel / dt)).eta
    return float(np.abs(hilbert(np.asarray(eta)))[x > x1 + lam].max() / 1e-3), omega


def _split_profile(h, dx, analytic, k, omega, until, depth0, depth1, bulk_length=None):
    """η after the split model carries the packet (discharge q̂ = (ω/k)·η̂ per mode: travelling along +x) to
    ``until`` on a periodic strip of two rows."""
    from wavephys.simulation.shallow_water import ShallowWater, sw_state
    from wavephys.simulation.split import Split, _split_run

    w = np.asarray(omega(k))
    c = np.where(k > 0, w / np.where(k > 0, k, 1.0), 0.0)
    q = np.fft.ifft(c * np.fft.fft(analytic)).real
    eta = np.real(analytic)
    rows = lambda f: np.broadcast_to(f, (2, f.size)).copy()
    bed = rows(-h)
    import jax.numpy as jnp

    # float64 where x64 is on (as the docs of measure_shoaling say; the state's own default is float32)
    state = sw_state(bed, rows(eta), u=rows(q / (h + eta)), dtype=jnp.result_type(float))
    split = Split(ShallowWater(dx, sides="periodic"), levels=tuple(sorted({depth0, depth1})), bulk_length=bulk_length)
    end, _ = _split_run(split, bed, state, until=until)
    return np.asarray(end.h)[0] - h


def lamb_beach_error(n: int = 128, periods: int = 3, method: str = "shallow") -> float:
    """Max error / amplitude of the shallow-water stepper on Lamb's standing wave (a 10 m beach of slope 0.1,
    third mode, a wall where dη/dx = 0) after ``periods`` periods on ``n`` samples.

    Parameters
    ----------
    n : int
        Samples per side, even, ≥ 16.
    periods : int
        ≥ 1.
    method : {"shallow", "symmetric"}
        A stepper of :data:`~wavephys.simulation.depth.DEPTH_METHODS` that takes dry land.

    Returns
    -------
    float
        Dimensionless.
    """
    from scipy.special import jn_zeros

    from wavephys.core.inputs import check_int
    from wavephys.physics.depth import lamb_beach
    from wavephys.simulation import Model
    from wavephys.simulation.depth import Floor, depth_state
    from wavephys.simulation.steppers import DepthStepper

    n = check_int("n", n, lo=16, even=True)
    periods = check_int("periods", periods, lo=1)
    length, slope = 10.0, 0.1
    grid = Grid(n, length)
    x = np.asarray(grid.mesh()[0]) + length / 2
    omega = jn_zeros(1, 3)[2] / (2 * math.sqrt(length / (G * slope)))
    model = Model(grid, Water(sigma=0.0), dt=2 * math.pi / omega / 40, walls="x", dtype=np.dtype(float).name)
    eta0 = lamb_beach(x, omega, slope, 1e-3)
    state = DepthStepper(model, Floor(slope * x), method).advance(depth_state(model, eta0), 40 * periods)
    return float(np.abs(np.asarray(state.eta) - eta0 * math.cos(omega * 40 * periods * model.dt)).max() / 1e-3)


def lamb_shoreline_errors(wet_cells: int = 64, slope: float = 0.1, offset: float = 0.0, periods: int = 3,
                          mode: int = 1) -> dict:
    """Lamb's standing wave on a plane beach whose still shoreline lies inside the grid, ``offset`` of a cell
    past a face, with dry land beyond (a quarter of the grid) and a wall at the offshore end: the linear
    shallow-water stepper's errors after ``periods`` periods (float64).

    The exact mode is η = A J₀(2ω√((x − x_s)/(g tan β))), ω = j₁,ₘ / (2√(L/(g tan β))) with L the wet length
    (Lamb 1932, §186); a cell whose centre is dry but whose face is wet holds the shoreline's value A.

    Parameters
    ----------
    wet_cells : int
        Cells across the wet part (rounded: the shoreline lies ``offset`` past a face), ≥ 8.
    slope : float
        tan β, > 0.
    offset : float
        Where the shoreline lies inside its cell, a fraction of dx in [0, 1).
    periods : int
        ≥ 1.
    mode : int
        Which zero of J₁ (1: the gravest mode with a node offshore), ≥ 1.

    Returns
    -------
    dict
        ``omega`` (fitted ω over the exact one, − 1), ``amplitude`` (fitted amplitude − 1), ``max`` and
        ``l2`` (the field's error at the end over A, max and root-mean-square over the wet cells).
    """
    from scipy.optimize import curve_fit
    from scipy.special import j0, jn_zeros

    import jax

    from wavephys.core.inputs import check_int, check_scalar
    from wavephys.simulation import Model
    from wavephys.simulation.depth import Floor, depth_state
    from wavephys.simulation.steppers import DepthStepper

    wet_cells = check_int("wet_cells", wet_cells, lo=8)
    slope = check_scalar("slope", slope, lo=0.0, lo_open=True)
    offset = check_scalar("offset", offset, lo=0.0, hi=1.0, hi_open=True)
    periods = check_int("periods", periods, lo=1)
    mode = check_int("mode", mode, lo=1)
    n = int(math.ceil(wet_cells * 4 / 3 / 2)) * 2
    dx, amplitude, per = 1.0, 1e-3, 40
    grid = Grid(n, n * dx)
    x = np.asarray(grid.mesh()[0])
    shore = n * dx / 2 - (wet_cells - offset) * dx
    omega = jn_zeros(1, mode)[-1] / (2 * math.sqrt((n * dx / 2 - shore) / (G * slope)))
    with jax.enable_x64(True):
        model = Model(grid, Water(sigma=0.0), dt=2 * math.pi / omega / per, walls="x", dtype="float64")
        eta0 = np.where(x + dx / 2 > shore + 1e-9,
                        amplitude * j0(2 * omega * np.sqrt(np.maximum(x - shore, 0.0) / (G * slope))), 0.0)
        state, states = DepthStepper(model, Floor(np.maximum(slope * (x - shore), 0.0)), "shallow").trajectory(
            depth_state(model, eta0), per * periods)
        frames = np.asarray(states.fields)[:, 0]
        end = np.asarray(state.eta)
    t = np.arange(len(frames)) * model.dt
    proj = np.tensordot(frames, eta0, axes=([1, 2], [0, 1])) / np.sum(eta0 * eta0)
    (a, w, _), _ = curve_fit(lambda t, a, w, p: a * np.cos(w * t + p), t, proj, p0=[1.0, omega, 0.0])
    err = (end - eta0 * math.cos(omega * per * periods * model.dt))[eta0 != 0] / amplitude
    return dict(omega=float(w / omega - 1), amplitude=float(abs(a) - 1), max=float(np.abs(err).max()),
                l2=float(np.sqrt(np.mean(err ** 2))))


def check_depth() -> list[Check]:
    """The shallow-water stepper shoals by Green's law and keeps Lamb's beach mode; the symmetric blend shoals
    by the mild-slope reference at intermediate and deep kh; the depth levels do not shoal (their measured
    failure).

    Returns
    -------
    list of Check
        Four rows: the symmetric blend's amplitude up a 10-wavelength ramp (1 → 0.25 m) at kh₀ = 1 and 3 against
        the mild-slope reference (≤ 1 %, σ = 6 packets); shallow water's amplitude up a 10-wavelength ramp (1 → 0.25 m, kh ≤ 0.1) extrapolated
        from 12 and 16 samples per wavelength against Green's law (≤ 1 %); its error on Lamb's standing wave
        after three periods at n = 128 (≤ 1.2 % of the amplitude); the levels' amplitude on the same ramp
        at kh₀ = 0.3 over the shoaling coefficient (≤ 0.7: their failure, so beaches go to shallow water).
    """
    import jax

    from wavephys.physics.depth import mild_slope_transmission, shoaling_coefficient

    with jax.enable_x64(True):
        a12, _ = measure_shoaling("shallow", 1.0, 0.25, 0.1, 12)
        a16, _ = measure_shoaling("shallow", 1.0, 0.25, 0.1, 16)
        green = 4.0 ** 0.25
        extrapolated = a16 + (a16 - a12) * 12 ** 2 / (16 ** 2 - 12 ** 2)
        lamb = lamb_beach_error(128)
        levels, w = measure_shoaling("levels", 1.0, 0.25, 0.3, 6)
        ks = shoaling_coefficient(w, 1.0, 0.25)
        errors = []
        for kh0 in (1.0, 3.0):
            a, omega = measure_shoaling("symmetric", 1.0, 0.25, kh0, 16, 10.0, 6.0)
            errors.append(a / mild_slope_transmission(omega, [0.0, 20 * math.pi / kh0], [1.0, 0.25])[0] - 1)
    worst = max(errors, key=abs)
    return [bound("symmetric blend up a 10-wavelength ramp, kh0 = 1 and 3: |A/A0 / mild-slope reference - 1|",
                  abs(worst), 0.01, note=f"{errors[0]:+.2%} at kh0 = 1, {errors[1]:+.2%} at 3"),
            bound("shallow water up a 10-wavelength ramp, kh <= 0.1: |A/A0 / Green's law - 1| (dx^2-extrapolated)",
                  abs(extrapolated / green - 1), 0.01,
                  note=f"{a12:.4f} at 12 and {a16:.4f} at 16 samples per wavelength, Green {green:.4f}"),
            bound("shallow water on Lamb's plane beach: max error / amplitude after 3 periods, n = 128", lamb, 0.012),
            bound("depth levels up the same ramp at kh0 = 0.3: A/A0 over the shoaling coefficient (their failure)",
                  levels / ks, 0.7, note=f"measured {levels:.3f}, theory {ks:.3f}")]
