"""``python -m bench ship``: the wake of a moving hull, Φ1/Φ2 kernels at several Δt against
dropping a row of stones along the path, error against cost; the cost of a ship per
step at N = 1024; the steady wake on 2048²; and the finite-difference peer's wake angle.
"""

from __future__ import annotations

import math
import statistics
import time

import jax
import numpy as np

from bench.timing import interleaved, median_seconds
from wavephys import Grid, Simulation, Water
from wavephys.harness.wake import wake_angle
from wavephys.models.finite_difference import fd_moving_source
from wavephys.physics.ship_waves import Hull, Ship, straight_path
from wavephys.physics.wake import KELVIN_ANGLE, GaussianPressure, HullSource, steady_wake

DEEP = Water(sigma=0.0)
U, HULL = 0.7, Hull("gaussian", 0.4, 0.4)


def _reference(dx):
    big = Grid(4096, 4096 * dx)
    return big, steady_wake(big, DEEP, U, HullSource(HULL, 0.01), damping=0.005)


def _near_wake_error(eta, grid, big, steady, x):
    """Relative L2 difference within 2 m behind the hull at x (rows |y| < 3 m), against the
    steady wake moved to x; ``big`` shares the grid's samples (centred, same spacing)."""
    offset = (big.n - grid.n) // 2
    ref = np.asarray(big.shift(steady, x))[offset:offset + grid.n, offset:offset + grid.n]
    c = np.asarray(grid.coordinates)
    rows, cols = np.abs(c) < 3.0, (c > x - 2.0) & (c < x)
    a, b = np.asarray(eta)[rows][:, cols], ref[rows][:, cols]
    return float(np.linalg.norm(a - b) / np.linalg.norm(b))


def wake_rows(progress=print) -> list[dict]:
    """Relative L2 error within 2 m behind the hull after 20 s, and seconds per run."""
    grid = Grid(512, 20.0)
    big, steady = _reference(float(grid.dx))
    rows = []
    for method in ("kernels", "impulses"):
        for dt in (0.05, 0.1, 0.2, 0.4):
            progress(f"ship wake {method} dt={dt}")
            ship = Ship(HULL, straight_path((-7.0, 0.0), (U, 0.0)), 0.01)
            sim = Simulation(grid, DEEP, dt=dt, margin=32, ship_method=method, ship_patch=64)

            def run():
                state = sim.initial_state()
                for _ in range(int(round(20.0 / dt))):
                    state, _ = sim.step(state, ships=[ship])
                return state

            t0 = time.perf_counter()
            try:
                state = jax.block_until_ready(run())
            except ValueError as exc:  # the patch guard refuses this Δt
                rows.append(dict(family="ship wake refused", method=method, dt=dt, reason=str(exc)))
                continue
            seconds = time.perf_counter() - t0
            error = _near_wake_error(sim.surface(state).eta, grid, big, steady, ship.path(float(state.time))[0])
            rows.append(dict(family="ship wake", method="Φ1/Φ2 kernels" if method == "kernels" else "row of stones",
                             n=512, dtype="float32", dt=dt, label=f"Δt={dt}", seconds=seconds, baseline_seconds=None,
                             error=error))
    return rows


def speed_rows(progress=print) -> list[dict]:
    progress("ship cost at n=1024; steady wake at 2048²")
    grid = Grid(1024, 20.0)
    sim = Simulation(grid, DEEP, dt=1 / 30, margin=64)
    ship = Ship(HULL, straight_path((0.0, 0.0), (U, 0.0)), 0.01)
    state = sim.initial_state()
    times = interleaved({"step": lambda: sim.step(state), "step + ship": lambda: sim.step(state, ships=[ship])},
                        repeats=15, block=3)
    extra = statistics.median((b - a) / a for a, b in zip(times["step"], times["step + ship"]))
    g2 = Grid(2048, 40.0)
    wake_s = median_seconds(lambda: steady_wake(g2, DEEP, 1.0, GaussianPressure(100.0, 0.05)), 5)
    return [dict(family="ship speed", method="one ship per step", n=1024, dtype="float32",
                 seconds=statistics.median(times["step + ship"]), baseline_seconds=statistics.median(times["step"]),
                 ratio=1 + extra, extra_fraction=extra, error=None),
            dict(family="ship speed", method="steady wake 2048²", n=2048, dtype="float32", seconds=wake_s,
                 baseline_seconds=None, error=None)]


def fd_rows(progress=print) -> list[dict]:
    """The non-dispersive FD peer with a moving Gaussian forcing: a Mach cone, not Kelvin."""
    progress("finite-difference wake")
    eta, grid, xs = fd_moving_source()
    angle = wake_angle(np.asarray(eta), grid, source=(xs, 0.0), near=2.0, far=12.0, exclude=0.5)
    return [dict(family="fd wake", method="finite difference (c = 0.5 m/s, U = 1 m/s)", angle=angle.angle,
                 uncertainty=angle.uncertainty, mach_angle=math.degrees(math.asin(0.5)), kelvin_angle=KELVIN_ANGLE,
                 error=None)]


def figures(rows) -> dict:
    from wavephys.plot import plot_error_vs_time

    wr = [r for r in rows if r["family"] == "ship wake"]
    return {"wake": plot_error_vs_time(wr, "moving hull, 20 s: wake error (within 2 m) vs time",
                                        ylabel="relative L2 error of η against the steady wake")}
