"""Validations of reflecting walls (docs/physics.md §1.11): a tank's energy, its seiche frequencies
measured back by the harness, and the image method at a corner."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from wavephys.checks.common import working_dtype
from wavephys.core.grid import Grid
from wavephys.core.water import Water
from wavephys.harness.checks import Check, bound

__all__ = ["check_walls"]


def check_walls() -> list[Check]:
    """A walled tank conserves energy, rings at its seiche frequencies and equals open water plus images.

    Returns
    -------
    list of Check
        Four rows: the energy drift of a 64² tank over 1000 steps (≤ 1e-3 in float32, ≤ 1e-10 in float64);
        the worst seiche-frequency error measured back by :func:`wavephys.harness.tank.seiche_check` from 300
        frames (≤ 1e-4); the smallest wall reflection coefficient measured the same way (≥ 0.999); a stone
        in a corner against the open-water field of it and its eight images after 30 steps (max-norm error
        over the peak, ≤ 1e-4).
    """
    from wavephys.harness.record import Record
    from wavephys.harness.tank import seiche_check, wall_reflection_check
    from wavephys.physics.disturbances import Stones, stone_height
    from wavephys.physics.walls import image_points
    from wavephys.simulation import Model
    from wavephys.simulation.stepping import add_height, add_source, energy, initial_state, run, surface

    dtype = np.dtype(working_dtype()).name
    water = Water(sigma=0.0, depth=0.3)
    model = Model(Grid(64, 2.0), water, dt=0.02, walls="all", dtype=dtype)
    stones = Stones([0.3, -0.5], [0.2, 0.6], [0.15, 0.2], [0.01, 0.01])
    state = add_source(model, initial_state(model), stones)
    e0 = float(energy(model, state))
    later, surf = run(model, state, 1000)
    drift = abs(float(energy(model, later)) / e0 - 1)
    record = Record.from_array(np.asarray(surf.eta[:300], np.float64), 2.0 / 64, 0.02, axes="tyx")
    seiche = seiche_check(record, water)
    reflection = wall_reflection_check(record, water)

    tank = Model(Grid(64, 2.0), water, dt=0.01, walls="all", dtype=dtype)
    big = replace(tank, grid=Grid(256, 8.0), walls=())
    x0, y0, radius = 0.8, 0.75, 0.06
    xs, ys, _ = image_points(x0, y0, 2.0, "all")
    a, _ = run(tank, add_source(tank, initial_state(tank), Stones(x0, y0, radius, 0.01)), 30)
    crater = stone_height(Stones(xs, ys, [radius] * len(xs), [0.01] * len(xs)), big.grid)
    b, _ = run(big, add_height(big, initial_state(big), crater), 30)
    want = np.asarray(surface(big, b).eta)[96:160, 96:160]
    image_error = float(np.abs(np.asarray(surface(tank, a).eta) - want).max() / np.abs(want).max())
    limit = 1e-10 if dtype == "float64" else 1e-3
    return [bound(f"walled tank: energy drift over 1000 steps ({dtype})", drift, limit),
            bound("walled tank: worst seiche frequency error measured back (harness)", abs(seiche.measured), 1e-4,
                  note=seiche.note),
            bound("walled tank: smallest wall reflection coefficient measured back (harness)", reflection.measured,
                  0.999, relation=">=", note=reflection.note),
            bound("stone in a corner vs open water + 8 images, max error / peak after 30 steps", image_error, 1e-4)]
