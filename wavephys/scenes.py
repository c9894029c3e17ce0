"""Built-in scenes that need no input files."""

from __future__ import annotations

from typing import Callable, Optional

import numpy as np

from wavephys.disturbances import Stones
from wavephys.params import Grid, Water
from wavephys.simulation import Simulation

__all__ = ["default_scene"]


def default_scene(n: int = 256, steps: int = 120, progress: Optional[Callable[[str], None]] = None):
    """A 16 m pool-sized patch of open water: three stones, 30 steps per second, margin n/8.

    Returns a dict with the final ``eta`` (m), ``eta_dot`` (m/s), ``dx`` (m), ``time`` (s)
    and ``energy_ratio`` (energy after / before the steps with the cutoff off, as a
    sanity figure: 1 to rounding).
    """
    if n < 128:
        raise ValueError(f"n must be ≥ 128 for the default scene (stones need dx ≤ 0.125 m), got {n}")
    grid = Grid(n, 16.0)
    water = Water()
    sim = Simulation(grid, water, dt=1.0 / 30.0, margin=max(1, n // 8))
    stones = Stones([-3.0, 2.0, 0.5], [1.0, -2.5, 3.0], [0.25, 0.15, 0.3], [0.05, 0.03, 0.06])
    state = sim.drop(sim.initial_state(), stones)
    free = Simulation(grid, water, dt=sim.dt)
    e0 = float(free.energy(state))
    say = progress or (lambda _m: None)
    say(f"running {steps} steps on {n}² …")
    final_free, _ = free.run(state, steps)
    state, surfaces = sim.run(state, steps)
    last = sim.surface(state)
    return dict(eta=np.asarray(last.eta), eta_dot=np.asarray(last.eta_dot), dx=float(grid.dx),
                time=float(last.time), energy_ratio=float(free.energy(final_free)) / e0)
