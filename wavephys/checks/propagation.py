"""Validations of the spectral step: energy conservation, composition of steps, the energy
measure, and Hermite frames between steps against exact propagation."""

from __future__ import annotations

import math

import jax.numpy as jnp
import numpy as np

from wavephys.checks.common import working_dtype
from wavephys.core.grid import Grid
from wavephys.core.water import Water
from wavephys.harness.checks import Check, compare
from wavephys.harness.energy import measure_energy
from wavephys.physics import dispersion as disp
from wavephys.physics.disturbances import Stones
from wavephys.physics.heights import monochromatic_wave
from wavephys.physics.interpolation import hermite_error, hermite_weights
from wavephys.physics.ring_waves import propagate

__all__ = ["check_energy_conservation", "check_step_composition", "check_energy_measure", "check_hermite"]


def _ring_state(sim):
    return sim.drop(sim.initial_state(), Stones(0.0, 0.0, 4 * float(sim.grid.dx), 1e-3))


def check_energy_conservation(steps: int = 1000) -> list[Check]:
    """Ring-wave propagation without cutoff conserves energy to rounding.

    A stone dropped on a 4 m grid of 128 points, stepped at Δt = 0.05 s in the working precision
    (float64 with ``jax_enable_x64``, else float32).

    Parameters
    ----------
    steps : int
        Steps run, ≥ 1 (checked by the simulation).

    Returns
    -------
    list of Check
        One row: the energy drift |E_end/E_0 − 1| against 0, within the a priori FFT rounding bound
        steps · ε · log₂ n (ε the machine epsilon of the working precision).
    """
    from wavephys.simulation import Simulation

    dtype = working_dtype()
    grid = Grid(128, 4.0)
    sim = Simulation(grid, Water(), dt=0.05, dtype=dtype)
    st = _ring_state(sim)
    e0 = float(sim.energy(st))
    end, _ = sim.run(st, steps)
    drift = abs(float(sim.energy(end)) / e0 - 1)
    tol = steps * float(jnp.finfo(dtype).eps) * math.log2(grid.n)  # a priori FFT rounding: eps·log2(n) per step
    return [compare(f"energy drift, {steps} steps, {jnp.dtype(dtype).name} (rounding bound steps*eps*log2 n)",
                    drift, 0.0, atol=tol)]


def check_step_composition() -> list[Check]:
    """n steps of Δt equal one step of nΔt; the step equals ring_waves.propagate.

    Returns
    -------
    list of Check
        One row: 50 simulation steps of 0.01 s against one :func:`~wavephys.physics.ring_waves.propagate`
        of 0.5 s (max difference / max |ψ|), atol 1e-5 in float32, 1e-12 in float64.
    """
    from wavephys.simulation import Simulation

    dtype = working_dtype()
    grid, water = Grid(128, 4.0), Water()
    sim = Simulation(grid, water, dt=0.01, dtype=dtype)
    st = _ring_state(sim)
    many, _ = sim.run(st, 50)
    one = propagate(st.psi, grid, water, 0.5)
    scale = float(jnp.max(jnp.abs(one)))
    tol = 1e-5 if dtype == jnp.float32 else 1e-12
    return [compare("50 steps of dt vs 1 step of 50 dt (max diff / max |psi|)",
                    float(jnp.max(jnp.abs(many.psi - one))) / scale, 0.0, atol=tol)]


def check_energy_measure() -> list[Check]:
    """Monochromatic deep gravity wave: E = ½ρgA², kinetic = potential, state energy = measured.

    Returns
    -------
    list of Check
        Three rows (rtol 1e-5): the measured total energy against ½ρgA², J/m²; kinetic / potential
        against 1 (equipartition); and the simulation state's energy against the energy measured
        from η and η̇, J/m².
    """
    from wavephys.simulation import Simulation

    water = Water(sigma=0.0)
    grid = Grid(128, 16.0)
    psi, k, amplitude = monochromatic_wave(grid, water, 0.05)
    sim = Simulation(grid, water, dt=0.1, dtype=working_dtype())
    state = sim.state_from_psi(psi)
    surf = sim.surface(state)
    e = measure_energy(surf.eta, surf.eta_dot, float(grid.dx), water)
    return [compare("monochromatic wave total energy 1/2 rho g A^2", e.total, 0.5 * 1000 * 9.81 * amplitude**2,
                    rtol=1e-5, unit="J/m^2"),
            compare("equipartition kinetic/potential", e.kinetic / e.potential, 1.0, rtol=1e-5),
            compare("state energy 1/2 rho <phi K phi + chi K chi> vs measured from eta, eta_dot",
                    float(sim.energy(state)), e.total, rtol=1e-5, unit="J/m^2")]


def check_hermite() -> list[Check]:
    """Weights at s = 1/3; a simulated frame against exact propagation; fourth-order error.

    Returns
    -------
    list of Check
        Six rows: the four cubic Hermite weights h00, h01, h10, h11 at s = 1/3 against 20/27, 7/27,
        4/27, −2/27; a frame interpolated at Δt/3 (ωΔt = 1) against exact propagation, relative to
        the amplitude, against the analytic error :func:`~wavephys.physics.interpolation.hermite_error`
        (rtol 0.01); and the convergence order from halving ωΔt, against 4 (atol 0.05).
    """
    from wavephys.simulation import Simulation

    w = [float(v) for v in hermite_weights(1.0 / 3.0)]
    rows = [compare(f"Hermite weight {name}(1/3)", got, want, atol=1e-7)
            for name, got, want in zip(("h00", "h01", "h10", "h11"), w, (20 / 27, 7 / 27, 4 / 27, -2 / 27))]
    dtype = working_dtype()
    grid, water = Grid(128, 4.0), Water()
    psi, k, amplitude = monochromatic_wave(grid, water, 0.01)
    dt = 1.0 / float(disp.angular_frequency(k, water))  # ωΔt = 1
    sim, fine = Simulation(grid, water, dt=dt, dtype=dtype), Simulation(grid, water, dt=dt / 3, dtype=dtype)
    st1, s0 = sim.step(sim.state_from_psi(psi))
    _, s1 = sim.step(st1)
    _, exact = fine.step(fine.step(fine.state_from_psi(psi))[0])
    measured = float(jnp.max(jnp.abs(sim.frame(s0, s1, 1.0 / 3.0) - exact.eta))) / amplitude
    rows.append(compare("Hermite frame at dt/3, omega dt = 1: simulated vs analytic error", measured,
                        hermite_error(1.0), rtol=0.01))
    rows.append(compare("Hermite convergence order (halving omega dt)",
                        math.log2(hermite_error(0.2) / hermite_error(0.1)), 4.0, atol=0.05))
    return rows
