"""The built-in validations: scenes with known answers, measured and compared.

Each ``check_*`` function runs one scene and returns a list of
:class:`~wavephys.validate.Check` rows; ``wavephys validate`` prints them all and the
test suite asserts them. The measurement helpers (``cutoff_reflection``,
``hermite_error``, ``second_order_breakdown``, …) are public because the benchmarks chart
them over their whole range.
"""

from __future__ import annotations

import math
from typing import Callable

import jax
import jax.numpy as jnp
import numpy as np

from wavephys import dispersion as disp
from wavephys.boundary import cutoff_profile
from wavephys.finite_difference import (STABILITY_LIMIT, fd_angular_frequency, fd_run,
                                        find_stability_limit)
from wavephys.heights import second_order_height
from wavephys.interpolation import hermite_weights
from wavephys.params import Grid, Water
from wavephys.ring_waves import propagate
from wavephys.simulation import Simulation
from wavephys.stokes import stokes_wave
from wavephys.validate import (Check, bound, compare, dispersion_error, measure_dispersion,
                               measure_energy)

__all__ = [
    "CHECKS",
    "run_all",
    "all_checks",
    "dispersion_scene",
    "cutoff_reflection",
    "cutoff_boundary",
    "single_wave",
    "hermite_error",
    "second_order_error",
    "second_order_breakdown",
]

_F32_RTOL = 1e-5


def _dtype():
    return jnp.float64 if jax.config.jax_enable_x64 else jnp.float32


# -- dispersion relation ---------------------------------------------------------------
def check_dispersion_limits() -> list[Check]:
    """Analytic limits of ω(k), c, c_g; closed-form c_g against autodiff; the minima."""
    deep = Water(sigma=0.0)
    w = Water()
    rows = []
    k = 2.0
    rows.append(compare("deep gravity c = sqrt(g/k) at k=2", disp.phase_speed(k, deep),
                        math.sqrt(9.81 / k), rtol=_F32_RTOL, unit="m/s"))
    h = 1.0
    rows.append(compare("shallow c → sqrt(g h) at kh=1e-3", disp.phase_speed(1e-3, Water(sigma=0.0, depth=h)),
                        math.sqrt(9.81 * h), rtol=_F32_RTOL, unit="m/s"))
    kc = 1e5
    rows.append(compare("capillary c → sqrt(σk/ρ) at k=1e5", disp.phase_speed(kc, w),
                        math.sqrt(0.0728 * kc / 1000.0), rtol=1e-3, unit="m/s"))
    rows.append(compare("deep gravity c_g/c", disp.group_speed(k, deep) / disp.phase_speed(k, deep),
                        0.5, rtol=_F32_RTOL))
    rows.append(compare("capillary c_g/c at k=1e6", disp.group_speed(1e6, w) / disp.phase_speed(1e6, w),
                        1.5, rtol=1e-4))
    rows.append(compare("shallow c_g/c at kh=1e-3",
                        disp.group_speed(1e-3, Water(sigma=0.0, depth=h)) / disp.phase_speed(1e-3, Water(sigma=0.0, depth=h)),
                        1.0, rtol=_F32_RTOL))
    ks = jnp.logspace(-3, 4, 400, dtype=_dtype())
    worst = 0.0
    for water in (w, Water(depth=0.5), Water(sigma=0.0, depth=3.0)):
        auto = jax.vmap(jax.grad(lambda x: disp.angular_frequency(x, water)))(ks)
        worst = max(worst, float(jnp.max(jnp.abs(auto / disp.group_speed(ks, water) - 1))))
    rows.append(compare("c_g closed form vs jax.grad (max rel. diff)", worst, 0.0, atol=1e-5))
    c_min, k_min = disp.min_phase_speed(w)
    rows.append(compare("minimum phase speed c_min", c_min, 0.2312, atol=5e-5, unit="m/s"))
    rows.append(compare("wavelength at c_min", 2 * math.pi / k_min * 100, 1.71, atol=0.005, unit="cm"))
    cg_min, kg_min = disp.min_group_speed(w)
    rows.append(compare("minimum group speed c_g,min", cg_min, 0.1776, atol=5e-5, unit="m/s"))
    rows.append(compare("wavelength at c_g,min", 2 * math.pi / kg_min * 100, 4.35, atol=0.005, unit="cm"))
    return rows


def check_inverse_dispersion() -> list[Check]:
    """k(ω(k)) = k over 1e-2 < k < 1e4 rad/m (deep) and 1e-3 < kh < 1e3 (finite depth)."""
    dtype = _dtype()
    tol = 1e-10 if dtype == jnp.float64 else 1e-5
    cases = [(Water(), jnp.logspace(-2, 4, 300, dtype=dtype)),
             (Water(sigma=0.0), jnp.logspace(-2, 4, 300, dtype=dtype))]
    for h in (0.01, 1.0, 100.0):
        cases.append((Water(depth=h), jnp.logspace(-3, 3, 300, dtype=dtype) / h))
    worst = 0.0
    for water, k in cases:
        back = disp.wavenumber(disp.angular_frequency(k, water), water)
        worst = max(worst, float(jnp.max(jnp.abs(back / k - 1))))
    return [compare(f"k(ω(k)) round trip, max rel. error ({jnp.dtype(dtype).name})", worst, 0.0,
                    atol=tol)]


def dispersion_scene(water: Water, n: int, length: float, dt: float, frames: int, seed: int = 0):
    """Random still-water disturbance run by the spectral simulation; measured ω(k)."""
    grid = Grid(n, length)
    sim = Simulation(grid, water, dt=dt, dtype=_dtype())
    eta0 = 1e-3 * jax.random.normal(jax.random.PRNGKey(seed), (n, n), sim.dtype)
    _, surf = sim.run(sim.add_height(sim.initial_state(), eta0), frames)
    return measure_dispersion(surf.eta, float(grid.dx), dt)


def check_measured_dispersion() -> list[Check]:
    """Measured ω–k ridge of the spectral simulation vs theory, gravity and capillary."""
    rows = []
    gravity = Water(sigma=0.0)
    s = dispersion_scene(gravity, 64, 64.0, 0.4, 512)
    rows.append(compare(f"spectral sim, gravity: max |ω_meas/ω − 1| over {s.k.size} shells "
                        f"k∈[{s.k.min():.3g}, {s.k.max():.3g}] rad/m",
                        np.abs(dispersion_error(s, gravity)).max(), 0.0, atol=0.005))
    cap = Water()
    s = dispersion_scene(cap, 64, 0.064, 1e-3, 1024).select(k_min=300.0)
    rows.append(compare(f"spectral sim, capillary: max |ω_meas/ω − 1| over {s.k.size} shells "
                        f"k∈[{s.k.min():.3g}, {s.k.max():.3g}] rad/m",
                        np.abs(dispersion_error(s, cap)).max(), 0.0, atol=0.005))
    rows.extend(check_fd_dispersion())
    return rows


def check_fd_dispersion(n: int = 64, courant: float = 0.5, frames: int = 1024) -> list[Check]:
    """The finite-difference scheme measured: one speed for every wavelength."""
    dx, c = 1.0, 1.0
    dt = courant * dx / c
    eta0 = 1e-3 * jax.random.normal(jax.random.PRNGKey(1), (n, n))
    _, _, hist = fd_run(eta0, eta0, courant, frames)
    s = measure_dispersion(hist, dx, dt).select(k_max=0.5 / dx)
    speed = s.omega / s.k
    rows = [compare(f"FD scheme: phase-speed spread max/min − 1 over k∈[{s.k.min():.3g}, "
                    f"{s.k.max():.3g}] (non-dispersive)", speed.max() / speed.min() - 1, 0.0,
                    atol=0.02)]
    own = np.asarray(fd_angular_frequency(s.k, 0.0, c, dt, dx))
    # shells mix directions; the scheme's ω depends weakly on direction at k·dx ≤ 0.5
    rows.append(compare("FD measured ω vs the scheme's own ω(k) (max rel. error)",
                        np.abs(s.omega / own - 1).max(), 0.0, atol=0.01))
    deep = np.sqrt(s.k.max() / s.k.min())
    rows.append(bound("deep-water c(k_min)/c(k_max) the FD scheme misses", deep, 1.5,
                      relation="≥"))
    return rows


# -- propagation ------------------------------------------------------------------------
def _ring_state(sim: Simulation):
    from wavephys.disturbances import Stones
    return sim.drop(sim.initial_state(), Stones(0.0, 0.0, 4 * float(sim.grid.dx), 1e-3))


def check_energy_conservation(steps: int = 1000) -> list[Check]:
    """Ring-wave propagation without cutoff conserves energy to rounding."""
    dtype = _dtype()
    grid, water = Grid(128, 4.0), Water()
    sim = Simulation(grid, water, dt=0.05, dtype=dtype)
    st = _ring_state(sim)
    e0 = float(sim.energy(st))
    end, _ = sim.run(st, steps)
    drift = abs(float(sim.energy(end)) / e0 - 1)
    eps = float(jnp.finfo(dtype).eps)
    tol = steps * eps * math.log2(grid.n)  # a priori FFT rounding bound: eps·log2(n) per step
    return [compare(f"energy drift, {steps} steps, {jnp.dtype(dtype).name} "
                    f"(rounding bound steps·eps·log2 n)", drift, 0.0, atol=tol)]


def check_step_composition() -> list[Check]:
    """n steps of Δt equal one step of nΔt; the step equals ring_waves.propagate."""
    dtype = _dtype()
    grid, water = Grid(128, 4.0), Water()
    sim = Simulation(grid, water, dt=0.01, dtype=dtype)
    st = _ring_state(sim)
    many, _ = sim.run(st, 50)
    one = propagate(st.psi, grid, water, 0.5)
    scale = float(jnp.max(jnp.abs(one)))
    tol = 1e-5 if dtype == jnp.float32 else 1e-12
    return [compare("50 steps of Δt vs 1 step of 50Δt (max diff / max |ψ|)",
                    float(jnp.max(jnp.abs(many.psi - one))) / scale, 0.0, atol=tol)]


def cutoff_reflection(ratio: float, kind: str = "quadratic", margin: int = 32,
                      group_cells_per_step: float = 0.5) -> float:
    """Energy fraction of a wave packet that the margin cutoff reflects (1-D, deep gravity).

    A packet of wavelength λ = ratio·M cells (Gaussian envelope of width 2λ) travels
    toward the right margin; the cutoff is applied every step, and the step moves the
    group ``group_cells_per_step`` cells (the reflection grows when the cutoff is applied
    more often per crossing). Once the reflection is back in the middle of the domain,
    the energy of the left-moving components (kx < 0, weighted by K = |k|) over the
    initial energy is the reflected fraction. A y-uniform wave on the 2-D grid separates
    into exactly this 1-D problem.
    """
    water = Water(sigma=0.0)
    dx = 1.0
    lam = ratio * margin * dx
    n = 1 << int(np.ceil(np.log2(2 * (9 * lam + margin))))
    k0 = 2 * np.pi / lam
    k = 2 * np.pi * np.fft.fftfreq(n, dx)
    x = np.arange(n) * dx
    env = np.exp(-0.5 * ((x - n / 2) / (2 * lam)) ** 2)
    cg = float(disp.group_speed(k0, water))
    dt = group_cells_per_step * dx / cg
    steps = int(1.5 * (n / 2 - margin) / group_cells_per_step)
    kabs = np.abs(k)
    omega = np.asarray(disp.angular_frequency(kabs.astype(np.float32), water), np.float64)
    mult = jnp.asarray(np.exp(-1j * omega * dt), jnp.complex64)
    h = cutoff_profile(n, margin, kind, jnp.float32)

    @jax.jit
    def run(f):
        def body(f, _):
            return jnp.fft.ifft(jnp.fft.fft(f * h) * mult), None
        return jax.lax.scan(body, f, None, length=steps)[0]

    f0 = jnp.asarray(env * np.exp(1j * k0 * x), jnp.complex64)
    e0 = float(jnp.sum(jnp.abs(jnp.fft.fft(f0)) ** 2 * kabs))
    spec = jnp.fft.fft(run(f0))
    left = float(jnp.sum(jnp.where(k < 0, jnp.abs(spec) ** 2 * kabs, 0.0)))
    return left / e0


def cutoff_boundary(kind: str = "quadratic", threshold: float = 1e-3, lo: float = 0.125,
                    hi: float = 2.0, iterations: int = 6, **kw) -> float:
    """The λ/M above which the margin reflects more than ``threshold`` of the energy.

    Bisection in log(λ/M) on :func:`cutoff_reflection` (which grows with λ/M).
    """
    a, b = math.log(lo), math.log(hi)
    if cutoff_reflection(lo, kind, **kw) > threshold or cutoff_reflection(hi, kind, **kw) < threshold:
        raise RuntimeError(f"reflection boundary of {kind} cutoff not in [{lo}, {hi}]")
    for _ in range(iterations):
        m = 0.5 * (a + b)
        a, b = (a, m) if cutoff_reflection(math.exp(m), kind, **kw) > threshold else (m, b)
    return math.exp(0.5 * (a + b))


def check_cutoff() -> list[Check]:
    """The quadratic margin absorbs waves up to a longer λ/M than the linear one."""
    q = cutoff_reflection(0.5, "quadratic")
    lin = cutoff_reflection(0.5, "linear")
    bq, bl = cutoff_boundary("quadratic"), cutoff_boundary("linear")
    return [
        bound("cutoff reflection, quadratic, λ/M=0.5 (energy fraction)", q, 1e-3),
        bound("cutoff reflection, linear/quadratic at λ/M=0.5", lin / q, 1.0, relation="≥"),
        bound(f"largest λ/M reflecting < 0.1 %: quadratic {bq:.3f} vs linear", bq, bl, relation="≥"),
        bound("… quadratic reflects visibly (> 1 %) at λ/M = 1 (failure boundary)",
              cutoff_reflection(1.0, "quadratic"), 0.01, relation="≥"),
    ]


# -- heights -------------------------------------------------------------------------------
def single_wave(grid: Grid, water: Water, steepness: float):
    """ψ = a e^{i k x} with first-order amplitude A = steepness/k along x; returns (ψ, k, A)."""
    k = float(2 * np.pi / float(grid.length) * 4)
    A = steepness / k
    omega = float(disp.angular_frequency(k, water))
    a = A * omega / k
    x, _ = grid.mesh()
    psi = a * jnp.exp(1j * k * (x + float(grid.length) / 2))
    return psi, k, A


def second_order_error(steepness: float, water: Water = Water(sigma=0.0), n: int = 256) -> dict:
    """Errors of first- and second-order heights against the exact Stokes wave (deep water).

    The wave of first-harmonic amplitude A (kA = ``steepness``) is built in ψ; its
    second-order height is compared with the exact steady Stokes wave whose η(x) has the
    same first harmonic (:func:`wavephys.stokes.stokes_wave`), both at the same phase.
    Returns max |error| / A for the first-order and the second-order height, and the
    exact wave's height-to-amplitude ratio.
    """
    grid = Grid(n, 2 * np.pi * 4 / 1.0)
    psi, k, A = single_wave(grid, water, steepness)
    eta2 = np.asarray(second_order_height(psi, grid, water), np.float64)[0]
    xs = np.asarray(grid.coordinates, np.float64) + float(grid.length) / 2
    # our first harmonic is −A sin(kx): shift the exact (crest at x=0) profile to match
    exact = stokes_wave(steepness, k)(xs - np.pi / (2 * k) * 3)
    eta1 = -A * np.sin(k * xs)
    return dict(first=np.abs(eta1 - exact).max() / A, second=np.abs(eta2 - exact).max() / A)


STEEPNESS = tuple(np.round(np.arange(0.02, 0.331, 0.02), 3))
"""Steepness values kA at which second-order heights are compared with exact Stokes waves."""


def second_order_breakdown(tolerance: float = 0.1, steepness=STEEPNESS) -> float:
    """Smallest kA at which the second-order height error (max |Δη| / A) reaches ``tolerance``.

    Linear interpolation between the sampled ``steepness`` values; ``inf`` if never.
    """
    errs = [second_order_error(float(s))["second"] for s in steepness]
    for (s0, e0), (s1, e1) in zip(zip(steepness, errs), zip(steepness[1:], errs[1:])):
        if e0 < tolerance <= e1:
            return float(s0 + (tolerance - e0) * (s1 - s0) / (e1 - e0))
    return math.inf


def check_second_order() -> list[Check]:
    """Second-order heights equal the Stokes result on a single wave."""
    dtype = _dtype()
    water = Water(sigma=0.0)
    grid = Grid(256, 10.0)
    psi, k, A = single_wave(grid, water, 0.2)
    psi = psi.astype(jnp.complex128 if dtype == jnp.float64 else jnp.complex64)
    eta = second_order_height(psi, grid, water)
    x = grid.coordinates + float(grid.length) / 2
    theta = k * x + np.pi / 2  # first-order height is A cos θ with θ = kx + π/2
    stokes = A * jnp.cos(theta) + 0.5 * k * A**2 * jnp.cos(2 * theta)
    err = float(jnp.max(jnp.abs(eta[0] - stokes))) / A
    tol = 1e-5 if dtype == jnp.float32 else 1e-12
    rows = [compare("2nd-order height vs Stokes A cos θ + (kA²/2) cos 2θ (max err / A)", err, 0.0, atol=tol)]
    crest, trough = float(jnp.max(eta)), float(jnp.min(eta))
    rows.append(compare("crest height − A (Stokes: +kA²/2)", crest - A, 0.5 * k * A**2, rtol=1e-3, unit="m"))
    rows.append(compare("trough depth − A (Stokes: −kA²/2)", -trough - A, -0.5 * k * A**2, rtol=1e-3, unit="m"))
    small = second_order_error(0.1)
    rows.append(bound("2nd-order error vs exact Stokes wave at kA=0.1 (max |Δη|/A)", small["second"], 0.01))
    rows.append(bound("… improvement over 1st order at kA=0.1 (error ratio 1st/2nd)",
                      small["first"] / small["second"], 5.0, relation="≥"))
    rows.append(compare("breakdown steepness kA where 2nd-order error reaches 10 % of A",
                        second_order_breakdown(0.1, (0.26, 0.28, 0.30, 0.32)), 0.3, atol=0.02))
    return rows


# -- Hermite frames ---------------------------------------------------------------------
def hermite_error(omega_dt: float, s: float = 1.0 / 3.0) -> float:
    """|error| / amplitude of the Hermite frame at t + sΔt for a wave of frequency ω.

    Exact for one Fourier mode e^{−iωt}: compares h00 + h01 e^{−ix} + (−ix)(h10 + h11
    e^{−ix}) with e^{−isx}, x = ωΔt. The worst case over a field is its largest ωΔt.
    """
    h00, h01, h10, h11 = (float(v) for v in hermite_weights(s))
    x = omega_dt
    z = np.exp(-1j * x)
    approx = h00 + h01 * z - 1j * x * (h10 + h11 * z)
    return float(abs(approx - np.exp(-1j * s * x)))


def check_hermite() -> list[Check]:
    """Weights at s = 1/3; simulation frames vs exact propagation; fourth-order error."""
    rows = []
    w = [float(v) for v in hermite_weights(1.0 / 3.0)]
    for name, got, want in zip(("h00", "h01", "h10", "h11"), w, (20 / 27, 7 / 27, 4 / 27, -2 / 27)):
        rows.append(compare(f"Hermite weight {name}(1/3)", got, want, atol=1e-7))
    # measured on the simulation: frame at Δt/3 vs the exact surface there
    dtype = _dtype()
    grid, water = Grid(128, 4.0), Water()
    psi, k, A = single_wave(grid, water, 0.01)
    omega = float(disp.angular_frequency(k, water))
    dt = 1.0 / omega  # ωΔt = 1
    sim = Simulation(grid, water, dt=dt, dtype=dtype)
    fine = Simulation(grid, water, dt=dt / 3, dtype=dtype)
    st = sim.state_from_psi(psi)
    st1, s0 = sim.step(st)
    _, s1 = sim.step(st1)
    _, exact = fine.step(fine.step(fine.state_from_psi(psi))[0])
    frame = sim.frame(s0, s1, 1.0 / 3.0)
    measured = float(jnp.max(jnp.abs(frame - exact.eta))) / A
    rows.append(compare("Hermite frame at Δt/3, ωΔt=1: sim vs analytic error", measured,
                        hermite_error(1.0), rtol=0.01))
    e1, e2 = hermite_error(0.2), hermite_error(0.1)
    rows.append(compare("Hermite convergence order (halving ωΔt)", math.log2(e1 / e2), 4.0, atol=0.05))
    return rows


# -- energy -----------------------------------------------------------------------------
def check_energy_measure() -> list[Check]:
    """Monochromatic deep gravity wave: E = ½ρgA², kinetic = potential."""
    water = Water(sigma=0.0)
    grid = Grid(128, 16.0)
    psi, k, A = single_wave(grid, water, 0.05)
    sim = Simulation(grid, water, dt=0.1, dtype=_dtype())
    surf = sim.surface(sim.state_from_psi(psi))
    e = measure_energy(surf.eta, surf.eta_dot, float(grid.dx), water)
    return [
        compare("monochromatic wave total energy ½ρgA²", e.total, 0.5 * 1000 * 9.81 * A**2, rtol=1e-4, unit="J/m²"),
        compare("equipartition kinetic/potential", e.kinetic / e.potential, 1.0, rtol=1e-4),
        compare("state energy ½ρ⟨φKφ+χKχ⟩ vs measured from η, η̇", float(sim.energy(sim.state_from_psi(psi))),
                e.total, rtol=1e-4, unit="J/m²"),
    ]


# -- finite differences -----------------------------------------------------------------
def check_fd_stability() -> list[Check]:
    """The explicit FD scheme's measured blow-up Courant number vs 1/√2."""
    return [compare("FD stability boundary cΔt/Δx (measured by bisection)", find_stability_limit(),
                    STABILITY_LIMIT, rtol=0.02)]


def check_moving_sources() -> list[Check]:
    """Ship kernels' exact identities, their float32 stability, and Kelvin wakes."""
    from wavephys.ship_waves import (resonance_quotients, resonance_quotients_exact, ship_multipliers,
                                     ship_multipliers_naive)
    from wavephys.wake import (KELVIN_ANGLE, GaussianPressure, cusp_line, steady_wake, track_wavelength,
                               transverse_wavelength, wake_angle)

    grid, deep = Grid(128, 8.0), Water(sigma=0.0)
    rows = []
    m1, m2 = ship_multipliers(grid, Water(), (0.0, 0.0), 0.1)
    rows.append(compare("ship at rest: max |M1 + M2|", float(jnp.max(jnp.abs(m1 + m2))), 0.0, atol=1e-6))
    alpha = np.concatenate([np.geomspace(1e-6, 2.0, 40), -np.geomspace(1e-6, 2.0, 40)])
    q1, _ = resonance_quotients(jnp.asarray(alpha, jnp.float32))
    r1, _ = resonance_quotients_exact(alpha)
    rows.append(compare("float32 Q1(α) vs exact, |α| ∈ [1e-6, 2] (max rel. error)",
                        float(np.max(np.abs(np.asarray(q1) - r1) / np.abs(r1))), 0.0, atol=1e-6))
    n1, _ = ship_multipliers_naive(grid, deep, (1.0, 0.0), 0.05)
    s1, _ = ship_multipliers(grid, deep, (1.0, 0.0), 0.05)
    err = np.abs(np.asarray(n1) - np.asarray(s1))
    err[0, 0] = 0.0  # 0/0 there
    rows.append(bound("naive quotients in float32: max |M1 error| (documented failure)", float(err.max()), 1e-2,
                      relation="≥"))
    wgrid = Grid(2048, 40.0)
    eta = steady_wake(wgrid, deep, 1.0, GaussianPressure(100.0, 0.05))
    angle = wake_angle(eta, wgrid, near=2.0, far=16.0, exclude=0.3)
    rows.append(compare(f"steady wake of a near-point source: half-angle ({angle.method})", angle.angle,
                        KELVIN_ANGLE, atol=0.3, unit="deg"))
    rows.append(compare("transverse wavelength on the track vs 2πU²/g", track_wavelength(eta, wgrid, near=4.0, far=16.0),
                        transverse_wavelength(1.0), rtol=0.01, unit="m"))
    rows.append(compare("cusp line from the dispersion relation (deep, gravity)", cusp_line(1.0).angle, KELVIN_ANGLE,
                        atol=1e-3, unit="deg"))
    for size in (0.05, 0.3):
        e = eta if size == 0.05 else steady_wake(wgrid, deep, 1.0, GaussianPressure(100.0, size))
        edge = wake_angle(e, wgrid, method="cusp", speed=1.0, near=3.0, far=14.0)
        rows.append(compare(f"steady wake, source σ/λ = {size / transverse_wavelength(1.0):.2f}: outer edge "
                            f"(± {edge.uncertainty:.2f})", edge.angle, KELVIN_ANGLE, atol=0.3, unit="deg"))
    largest = wake_angle(e, wgrid, near=2.0, far=16.0, exclude=0.3)
    rows.append(bound("σ/λ = 0.47: angle of maximum amplitude below Kelvin (a different quantity)",
                      KELVIN_ANGLE - largest.angle, 5.0, relation="≥", unit="deg"))
    cgrid, cap = Grid(1024, 1.0), Water()
    n, dx = 1024, float(cgrid.dx)

    def behind(u):
        e = np.asarray(steady_wake(cgrid, cap, u, GaussianPressure(10.0, 0.005)))
        return np.abs(e[:, n // 2 - int(0.4 / dx):n // 2 - int(0.1 / dx)]).max() / np.abs(e).max()

    rows.append(bound("capillary-gravity wake amplitude ratio U=0.26 / U=0.22 (c_min = 0.2312)",
                      behind(0.26) / behind(0.22), 100.0, relation="≥"))
    return rows


CHECKS: dict[str, Callable[[], list[Check]]] = {
    "dispersion limits": check_dispersion_limits,
    "inverse dispersion": check_inverse_dispersion,
    "measured dispersion": check_measured_dispersion,
    "energy conservation": check_energy_conservation,
    "step composition": check_step_composition,
    "energy measurement": check_energy_measure,
    "open-ocean cutoff": check_cutoff,
    "second-order heights": check_second_order,
    "Hermite frames": check_hermite,
    "finite-difference stability": check_fd_stability,
    "moving sources": check_moving_sources,
}
"""Every built-in validation, in the order ``wavephys validate`` runs them."""


def all_checks() -> dict[str, Callable[[], list[Check]]]:
    """The wave checks (:data:`CHECKS`) followed by the optics ones (``optics.checks``)."""
    from optics.checks import CHECKS as OPTICS

    return {**CHECKS, **OPTICS}


def run_all(progress: Callable[[int, int, str], None] | None = None) -> list[Check]:
    """Run every check of :func:`all_checks`; ``progress(i, total, name)`` is called before each."""
    rows: list[Check] = []
    checks = all_checks()
    for i, (name, fn) in enumerate(checks.items()):
        if progress:
            progress(i, len(checks), name)
        rows.extend(fn())
    return rows
