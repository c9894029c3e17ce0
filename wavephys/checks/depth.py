"""Validations of waves over a varying floor (docs/physics.md §1.12): a packet's shoaling up a ramp by
each stepper against the mild-slope reference, and Lamb's standing wave on a plane beach."""

from __future__ import annotations

import math

import numpy as np

from wavephys.core.grid import Grid
from wavephys.core.water import Water
from wavephys.harness.checks import Check, bound

__all__ = ["travelling_packet", "measure_shoaling", "lamb_beach_error", "check_depth"]

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


def measure_shoaling(method: str, depth0: float, depth1: float, k0: float, per: int, ramp: float = 10.0,
                     sigma: float = 2.0):
    """A packet (carrier k₀, envelope σ wavelengths) from depth h₀ up (or down) a ramp of ``ramp`` wavelengths to
    h₁, plane waves along x: (amplitude over the far plateau / incident amplitude, ω).

    Parameters
    ----------
    method : {"levels", "shallow"}
    depth0, depth1 : float
        m, > 0.
    k0 : float
        rad/m, > 0.
    per : int
        Samples per incident wavelength, ≥ 4 (the grid is 50 wavelengths, 50·per samples, square).
    ramp : float
        Ramp length in incident wavelengths, > 0.
    sigma : float
        Envelope in incident wavelengths, > 0.

    Returns
    -------
    (float, float)
        Amplitude ratio, and the carrier's ω (rad/s, the method's own).
    """
    from scipy.signal import hilbert

    from wavephys.physics.dispersion import angular_frequency, group_speed, wavenumber
    from wavephys.simulation import Model
    from wavephys.simulation.depth import Floor, depth_state, run_depth

    lam = 2 * math.pi / k0
    n, length = int(50 * per), 50 * lam
    grid = Grid(n, length)
    x = np.asarray(grid.mesh()[0])
    x0, x1 = -7 * lam, -7 * lam + ramp * lam
    h = np.clip(depth0 + (depth1 - depth0) * (x - x0) / (x1 - x0), min(depth0, depth1), max(depth0, depth1))
    if method == "shallow":
        omega, cg0, cg1 = k0 * math.sqrt(G * depth0), math.sqrt(G * depth0), math.sqrt(G * depth1)
    else:
        w0, w1 = Water(sigma=0.0, depth=depth0), Water(sigma=0.0, depth=depth1)
        omega = float(angular_frequency(k0, w0))
        cg0, cg1 = float(group_speed(k0, w0)), float(group_speed(float(wavenumber(omega, w1)), w1))
    dt = 2 * math.pi / omega / 16
    model = Model(grid, Water(sigma=0.0, depth=depth0), dt=dt, dtype="float64")
    xc = -15 * lam
    env = np.exp(-(x - xc) ** 2 / (2 * (sigma * lam) ** 2))
    eta, phi = travelling_packet(grid, 1e-3 * env * np.exp(1j * k0 * (x - xc)), method, depth0)
    travel = (x0 - xc) / cg0 + (x1 - x0) / (0.5 * (cg0 + cg1)) + (8 * lam - x1) / cg1
    state, _ = run_depth(model, Floor(h), depth_state(model, eta, phi), int(travel / dt), method)
    row = np.asarray(state.eta)[n // 2]
    return float(np.abs(hilbert(row))[x[0] > x1 + lam].max() / 1e-3), omega


def lamb_beach_error(n: int = 128, periods: int = 3) -> float:
    """Max error / amplitude of the shallow-water stepper on Lamb's standing wave (a 10 m beach of slope 0.1,
    third mode, a wall where dη/dx = 0) after ``periods`` periods on ``n`` samples.

    Parameters
    ----------
    n : int
        Samples per side, even, ≥ 16.
    periods : int
        ≥ 1.

    Returns
    -------
    float
        Dimensionless.
    """
    from scipy.special import jn_zeros

    from wavephys.core.inputs import check_int
    from wavephys.physics.depth import lamb_beach
    from wavephys.simulation import Model
    from wavephys.simulation.depth import Floor, depth_state, run_depth

    n = check_int("n", n, lo=16, even=True)
    periods = check_int("periods", periods, lo=1)
    length, slope = 10.0, 0.1
    grid = Grid(n, length)
    x = np.asarray(grid.mesh()[0]) + length / 2
    omega = jn_zeros(1, 3)[2] / (2 * math.sqrt(length / (G * slope)))
    model = Model(grid, Water(sigma=0.0), dt=2 * math.pi / omega / 40, walls="x", dtype=np.dtype(float).name)
    eta0 = lamb_beach(x, omega, slope, 1e-3)
    state, _ = run_depth(model, Floor(slope * x), depth_state(model, eta0), 40 * periods, "shallow")
    return float(np.abs(np.asarray(state.eta) - eta0 * math.cos(omega * 40 * periods * model.dt)).max() / 1e-3)


def check_depth() -> list[Check]:
    """The shallow-water stepper shoals by Green's law and keeps Lamb's beach mode; the depth levels do not
    shoal (their measured failure).

    Returns
    -------
    list of Check
        Three rows: shallow water's amplitude up a 10-wavelength ramp (1 → 0.25 m, kh ≤ 0.1) extrapolated
        from 12 and 16 samples per wavelength against Green's law (≤ 1 %); its error on Lamb's standing wave
        after three periods at n = 128 (≤ 1.2 % of the amplitude); the levels' amplitude on the same ramp
        at kh₀ = 0.3 over the shoaling coefficient (≤ 0.7: their failure, so beaches go to shallow water).
    """
    import jax

    from wavephys.physics.depth import shoaling_coefficient

    with jax.enable_x64(True):
        a12, _ = measure_shoaling("shallow", 1.0, 0.25, 0.1, 12)
        a16, _ = measure_shoaling("shallow", 1.0, 0.25, 0.1, 16)
        green = 4.0 ** 0.25
        extrapolated = a16 + (a16 - a12) * 12 ** 2 / (16 ** 2 - 12 ** 2)
        lamb = lamb_beach_error(128)
        levels, w = measure_shoaling("levels", 1.0, 0.25, 0.3, 6)
        ks = shoaling_coefficient(w, 1.0, 0.25)
    return [bound("shallow water up a 10-wavelength ramp, kh <= 0.1: |A/A0 / Green's law - 1| (dx^2-extrapolated)",
                  abs(extrapolated / green - 1), 0.01,
                  note=f"{a12:.4f} at 12 and {a16:.4f} at 16 samples per wavelength, Green {green:.4f}"),
            bound("shallow water on Lamb's plane beach: max error / amplitude after 3 periods, n = 128", lamb, 0.012),
            bound("depth levels up the same ramp at kh0 = 0.3: A/A0 over the shoaling coefficient (their failure)",
                  levels / ks, 0.7, note=f"measured {levels:.3f}, theory {ks:.3f}")]
