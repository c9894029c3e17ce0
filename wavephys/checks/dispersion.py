"""Validations of the dispersion relation: analytic limits, published minima, the inverse,
and ω(k) measured back from the spectral simulation and from the finite-difference peer."""

from __future__ import annotations

import math

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.checks.common import working_dtype
from wavephys.core.grid import Grid
from wavephys.core.inputs import check_int, check_scalar
from wavephys.core.water import Water
from wavephys.harness.checks import Check, bound, compare
from wavephys.harness.dispersion import dispersion_error, measure_dispersion
from wavephys.core.stepper import TwoLevelState
from wavephys.models.finite_difference import FiniteDifferenceStepper, fd_angular_frequency
from wavephys.physics import dispersion as disp

__all__ = ["check_dispersion_limits", "check_dispersion_minima", "check_inverse_dispersion", "dispersion_scene",
           "check_measured_dispersion", "check_fd_dispersion"]

_F32_RTOL = 1e-5


def check_dispersion_limits() -> list[Check]:
    """Analytic limits of c and c_g (deep, shallow, capillary); closed-form c_g against autodiff.

    Returns
    -------
    list of Check
        Seven rows: the phase speed c, m/s, against √(g/k) (deep gravity, k = 2 rad/m), √(gh) (shallow,
        kh = 1e-3) and √(σk/ρ) (capillary, k = 1e5 rad/m); the ratio c_g/c against 1/2 (deep gravity),
        3/2 (capillary, k = 1e6 rad/m) and 1 (shallow); and the largest relative difference between
        the closed-form group speed and ``jax.grad`` of ω(k) over 1e-3 to 1e4 rad/m on three waters
        (atol 1e-5).
    """
    deep, w, shallow = Water(sigma=0.0), Water(), Water(sigma=0.0, depth=1.0)
    k, kc = 2.0, 1e5
    ratio = lambda kk, water: disp.group_speed(kk, water) / disp.phase_speed(kk, water)
    rows = [compare("deep gravity c = sqrt(g/k) at k=2", disp.phase_speed(k, deep), math.sqrt(9.81 / k),
                    rtol=_F32_RTOL, unit="m/s"),
            compare("shallow c -> sqrt(g h) at kh=1e-3", disp.phase_speed(1e-3, shallow), math.sqrt(9.81),
                    rtol=_F32_RTOL, unit="m/s"),
            compare("capillary c -> sqrt(sigma k/rho) at k=1e5", disp.phase_speed(kc, w),
                    math.sqrt(0.0728 * kc / 1000.0), rtol=5e-5, unit="m/s",
                    note="gravity adds g/k to c^2: 6.7e-6 relative at k = 1e5"),
            compare("deep gravity c_g/c", ratio(k, deep), 0.5, rtol=_F32_RTOL),
            compare("capillary c_g/c at k=1e6", ratio(1e6, w), 1.5, rtol=1e-5),
            compare("shallow c_g/c at kh=1e-3", ratio(1e-3, shallow), 1.0, rtol=_F32_RTOL)]
    ks = jnp.logspace(-3, 4, 400, dtype=working_dtype())
    worst = 0.0
    for water in (w, Water(depth=0.5), Water(sigma=0.0, depth=3.0)):
        auto = jax.vmap(jax.grad(lambda x: disp.angular_frequency(x, water)))(ks)
        worst = max(worst, float(jnp.max(jnp.abs(auto / disp.group_speed(ks, water) - 1))))
    rows.append(compare("c_g closed form vs jax.grad (max rel. diff)", worst, 0.0, atol=1e-5))
    return rows


def check_dispersion_minima() -> list[Check]:
    """The capillary-gravity minima of c and c_g against their published values.

    Returns
    -------
    list of Check
        Four rows for the default :class:`~wavephys.Water`: the minimum phase speed (0.2312 m/s) and
        its wavelength (1.71 cm), the minimum group speed (0.1776 m/s) and its wavelength (4.35 cm).
    """
    w = Water()
    c_min, k_min = disp.min_phase_speed(w)
    cg_min, kg_min = disp.min_group_speed(w)
    return [compare("minimum phase speed c_min", c_min, 0.2312, atol=5e-5, unit="m/s"),
            compare("wavelength at c_min", 2 * math.pi / k_min * 100, 1.71, atol=0.005, unit="cm"),
            compare("minimum group speed c_g,min", cg_min, 0.1776, atol=5e-5, unit="m/s"),
            compare("wavelength at c_g,min", 2 * math.pi / kg_min * 100, 4.35, atol=0.005, unit="cm")]


def check_inverse_dispersion() -> list[Check]:
    """k(ω(k)) = k over 1e-2 < k < 1e4 rad/m (deep) and 1e-3 < kh < 1e3 (finite depth).

    Returns
    -------
    list of Check
        One row: the largest relative round-trip error |k(ω(k))/k − 1| over deep capillary-gravity,
        deep gravity and three depths (0.01, 1, 100 m), against 0 (atol 1e-5 in float32, 1e-10 in
        float64).
    """
    dtype = working_dtype()
    tol = 1e-10 if dtype == jnp.float64 else 1e-5
    cases = [(Water(), jnp.logspace(-2, 4, 300, dtype=dtype)),
             (Water(sigma=0.0), jnp.logspace(-2, 4, 300, dtype=dtype))]
    cases += [(Water(depth=h), jnp.logspace(-3, 3, 300, dtype=dtype) / h) for h in (0.01, 1.0, 100.0)]
    worst = 0.0
    for water, k in cases:
        back = disp.wavenumber(disp.angular_frequency(k, water), water)
        worst = max(worst, float(jnp.max(jnp.abs(back / k - 1))))
    return [compare(f"k(omega(k)) round trip, max rel. error ({jnp.dtype(dtype).name})", worst, 0.0, atol=tol)]


def dispersion_scene(water: Water, n: int, length: float, dt: float, frames: int, seed: int = 0):
    """A random still-water disturbance run by the spectral simulation; its measured ω(k).

    Heights of 1 mm standard deviation (white noise, seeded) are added to still water and
    run for ``frames`` steps of ``dt`` in the working precision; ω(k) is measured from the frames
    by :func:`~wavephys.harness.measure_dispersion`.

    Parameters
    ----------
    water : Water
        The water simulated.
    n : int
        Grid points per side, even, ≥ 2 (checked by :class:`wavephys.Grid`).
    length : float
        Side of the square grid, m, > 0.
    dt : float
        Time step and time between frames, s, > 0.
    frames : int
        Frames (steps) recorded, 8 to 65536.
    seed : int
        Seed of the random disturbance, ≥ 0.

    Returns
    -------
    DispersionSamples
        The measured (k, ω) points, one per wavenumber shell (rad/m, rad/s).
    """
    from wavephys.simulation import Simulation

    check_int("frames", frames, lo=8, hi=1 << 16)
    check_int("seed", seed, lo=0)
    grid = Grid(n, length)
    sim = Simulation(grid, water, dt=dt, dtype=working_dtype())
    eta0 = 1e-3 * jax.random.normal(jax.random.PRNGKey(seed), (n, n), sim.dtype)
    _, surf = sim.run(sim.add_height(sim.initial_state(), eta0), frames)
    return measure_dispersion(surf.eta, float(grid.dx), dt, axes="tyx")


def check_measured_dispersion() -> list[Check]:
    """Measured ω–k ridge of the spectral simulation against theory, gravity and capillary.

    Returns
    -------
    list of Check
        Two rows, gravity (64 m grid) and capillary (6.4 cm grid, shells above 300 rad/m): the largest
        |ω_measured/ω − 1| over the measured shells of :func:`dispersion_scene`, against 0
        (atol 0.005); the note gives the k range and the worst k.
    """
    rows = []
    for water, args, k_min, label in ((Water(sigma=0.0), (64, 64.0, 0.4, 512), 0.0, "gravity"),
                                      (Water(), (64, 0.064, 1e-3, 1024), 300.0, "capillary")):
        s = dispersion_scene(water, *args).select(k_min=k_min)
        err = np.abs(dispersion_error(s, water))
        rows.append(compare(f"spectral sim, {label}: max |omega_meas/omega - 1| over {s.k.size} shells",
                            err.max(), 0.0, atol=0.005,
                            note=f"k in [{s.k.min():.3g}, {s.k.max():.3g}] rad/m, worst at k = "
                                 f"{s.k[np.argmax(err)]:.4g} rad/m"))
    return rows


def check_fd_dispersion(n: int = 64, courant: float = 0.5, frames: int = 1024) -> list[Check]:
    """The finite-difference peer measured: one speed for every wavelength (its failure).

    A random disturbance run by the explicit finite-difference scheme (Δx = 1 m, c = 1 m/s);
    ω(k) is measured up to k = 0.5 rad/m.

    Parameters
    ----------
    n : int
        Grid points per side, 8 to 4096.
    courant : float
        Courant number c Δt/Δx, dimensionless, in (0, 1/√2] (the scheme's stability limit).
    frames : int
        Steps recorded, 8 to 65536.

    Returns
    -------
    list of Check
        Three rows: the spread of the measured phase speed, max/min − 1 (atol 0.02: non-dispersive);
        the measured ω against the scheme's own ω(k) (max relative error, atol 0.01); and the ratio
        √(k_max/k_min) of deep-water phase speeds the scheme misses (≥ 1.5).
    """
    check_int("n", n, lo=8, hi=4096)
    check_scalar("courant", courant, lo=0.0, hi=1.0 / 2**0.5, lo_open=True)
    check_int("frames", frames, lo=8, hi=1 << 16)
    dx, c = 1.0, 1.0
    dt = courant * dx / c
    eta0 = 1e-3 * jax.random.normal(jax.random.PRNGKey(1), (n, n))
    end, states = FiniteDifferenceStepper(courant, dt).trajectory(TwoLevelState(eta0, eta0), frames)
    hist = jnp.concatenate([states.eta[1:], end.eta[None]])  # η after each step
    s = measure_dispersion(hist, dx, dt, axes="tyx").select(k_max=0.5 / dx)
    speed = s.omega / s.k
    own = np.asarray(fd_angular_frequency(s.k, 0.0, c, dt, dx))
    return [compare("FD scheme: phase-speed spread max/min - 1 (non-dispersive)", speed.max() / speed.min() - 1,
                    0.0, atol=0.02, note=f"k in [{s.k.min():.3g}, {s.k.max():.3g}] rad/m"),
            # shells mix directions; the scheme's ω depends weakly on direction at k·dx <= 0.5
            compare("FD measured omega vs the scheme's own omega(k) (max rel. error)", np.abs(s.omega / own - 1).max(),
                    0.0, atol=0.01),
            bound("deep-water c(k_min)/c(k_max) the FD scheme misses", np.sqrt(s.k.max() / s.k.min()), 1.5,
                  relation=">=")]
