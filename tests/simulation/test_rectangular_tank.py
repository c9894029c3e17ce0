"""Rectangular tanks, Lx ≠ Ly (docs/physics.md §1.11): a tank smaller than the grid's square, centred, closed
by walls — its own cosine modes stepped exactly, land held still, stones mirrored in its walls."""

import math

import jax
import numpy as np
import pytest

from wavephys import Grid, Stones, Water
from wavephys.physics.disturbances import stone_height
from wavephys.physics.ship_waves import Hull, Ship, straight_path
from wavephys.physics.wind import WindSea
from wavephys.simulation import Model, Simulation
from wavephys.simulation.depth import Floor, depth_state, step_symmetric
from wavephys.simulation.stepping import add_height, add_source, energy, initial_state, run, surface

pytestmark = pytest.mark.usefixtures("x64")


@pytest.fixture
def x64():
    with jax.enable_x64(True):
        yield


def _family(seed, count):
    """Generated tanks on a 64-cell, 4 m grid: even cell counts 8–64 a side, a mode (m, p) of each, a depth."""
    rng = np.random.default_rng(seed)
    cases = []
    for _ in range(count):
        mx, my = (2 * int(v) for v in rng.integers(4, 33, 2))
        m, p = int(rng.integers(0, min(mx, 8))), int(rng.integers(1, min(my, 8)))
        cases.append((mx, my, m, p, float(rng.choice([0.05, 0.4, math.inf]))))
    return cases


@pytest.mark.parametrize("mx, my, m, p, depth", _family(3, 2) + [pytest.param(*c, marks=pytest.mark.slow) for c in _family(4, 3)])
def test_a_rectangular_tank_steps_its_own_modes_exactly(mx, my, m, p, depth):
    """cos(mπx'/Lx)·cos(pπy'/Ly) on the tank turns at ω = √(gk tanh kh), k = π√((m/Lx)² + (p/Ly)²) (written out
    here): after 100 steps within 1e-10 of the amplitude; the land around it stays 0; energy kept to 1e-11."""
    n, length = 64, 4.0
    dx = length / n
    lx, ly = mx * dx, my * dx
    model = Model(Grid(n, length), Water(sigma=0.0, depth=depth), dt=0.02, walls="all", tank=(lx, ly),
                  dtype="float64")
    x, y = (np.asarray(a) for a in model.grid.mesh())
    inside = (np.abs(x) < lx / 2) & (np.abs(y) < ly / 2)
    assert inside.sum() == mx * my
    mode = np.where(inside, np.cos(m * np.pi * (x + lx / 2) / lx) * np.cos(p * np.pi * (y + ly / 2) / ly), 0.0)
    state = add_height(model, initial_state(model), 1e-3 * mode)
    e0 = float(energy(model, state))
    end, _ = run(model, state, 100)
    k = math.pi * math.hypot(m / lx, p / ly)
    omega = math.sqrt(9.81 * k * (math.tanh(k * depth) if math.isfinite(depth) else 1.0))
    got = np.asarray(surface(model, end).eta)
    assert np.abs(got - 1e-3 * mode * math.cos(omega * 2.0)).max() < 1e-10 * 1e-3
    assert np.all(got[~inside] == 0.0)  # (a generated tank may fill the grid: no land)
    assert abs(float(energy(model, end)) / e0 - 1) < 1e-11


@pytest.mark.slow
def test_a_tank_the_size_of_the_grid_is_the_walled_model():
    grid = Grid(32, 2.0)
    square = Model(grid, Water(sigma=0.0, depth=0.3), dt=0.02, walls="all", dtype="float64")
    tank = Model(grid, Water(sigma=0.0, depth=0.3), dt=0.02, walls="all", tank=(2.0, 2.0), dtype="float64")
    results = []
    for model in (square, tank):
        state = add_source(model, initial_state(model), Stones([0.3, -0.6], [0.1, 0.5], [0.1, 0.08], [0.01, 0.01]))
        state = add_source(model, state, WindSea(jax.random.PRNGKey(2), "phillips", dict(wind_speed=2.0)))
        results.append(np.asarray(surface(model, run(model, state, 40)[0]).eta))
    assert np.abs(results[0] - results[1]).max() <= 1e-12 * np.abs(results[0]).max()


def test_a_stone_near_a_wall_of_a_rectangular_tank_is_open_water_plus_its_images():
    """A 2 × 1.25 m tank in a 2 m grid: the field inside it equals open water (a 4× periodic domain) holding the
    stone and its mirror images in the tank's walls — x + 2jLx and (2j + 1)Lx − x for j = −1, 0, 1, likewise in y,
    36 in all (with the nearest 9 only, the missing images' far field is 1.4e-5 of the peak at the far wall after
    30 steps)."""
    n, length, lx, ly = 64, 2.0, 2.0, 1.25
    model = Model(Grid(n, length), Water(sigma=0.0, depth=0.25), dt=0.01, walls="all", tank=(lx, ly),
                  dtype="float64")
    big = Model(Grid(4 * n, 4 * length), Water(sigma=0.0, depth=0.25), dt=0.01, dtype="float64")
    x, y = (np.asarray(a) for a in model.grid.mesh())
    inside = (np.abs(x) < lx / 2) & (np.abs(y) < ly / 2)
    rng = np.random.default_rng(9)
    for x0, y0 in ((rng.uniform(-0.4, 0.4), rng.uniform(0.35, 0.5)), (rng.uniform(0.7, 0.85), rng.uniform(-0.5, -0.35))):
        radius = rng.uniform(0.04, 0.07)
        xs = np.array([x0 + 2 * j * lx for j in (-1, 0, 1)] + [(2 * j + 1) * lx - x0 for j in (-1, 0, 1)])
        ys = np.array([y0 + 2 * j * ly for j in (-1, 0, 1)] + [(2 * j + 1) * ly - y0 for j in (-1, 0, 1)])
        px, py = (a.ravel() for a in np.meshgrid(xs, ys))
        walled = add_source(model, initial_state(model), Stones(x0, y0, radius, 0.01))
        crater = stone_height(Stones(px, py, [radius] * 36, [0.01] * 36), big.grid)
        opened = add_height(big, initial_state(big), crater)
        got = np.asarray(surface(model, run(model, walled, 30)[0]).eta)
        want = np.asarray(surface(big, run(big, opened, 30)[0]).eta)[3 * n // 2:5 * n // 2, 3 * n // 2:5 * n // 2]
        # the mean level over the tank is a still level (its k = 0 mode): the tank keeps the sampled craters' tiny
        # net volume as one, the open domain spreads it over 64 m²; compare the waves
        got_w, want_w = got[inside] - got[inside].mean(), want[inside] - want[inside].mean()
        scale = np.abs(want_w).max()
        assert np.abs(got_w - want_w).max() <= 1e-5 * scale, (x0, y0)
        assert np.abs(got[~inside]).max() == 0.0


def test_bad_tanks_are_refused_by_name():
    grid = Grid(32, 2.0)
    with pytest.raises(ValueError, match="walls='all'"):
        Model(grid, Water(), walls="x", tank=(2.0, 1.0))
    with pytest.raises(ValueError, match="even number of cells"):
        Model(grid, Water(), walls="all", tank=(2.0, 1.0625))
    with pytest.raises(ValueError, match="at most the grid's side"):
        Model(grid, Water(), walls="all", tank=(2.5, 1.0))
    with pytest.raises(ValueError, match="tank"):
        Model(grid, Water(), walls="all", tank=(2.0, -1.0))
    with pytest.raises(TypeError, match="tank"):
        Model(grid, Water(), walls="all", tank="wide")
    sim = Simulation(grid, Water(), dt=0.02, walls="all", tank=(2.0, 1.0))
    assert sim.tank == (2.0, 1.0)
    with pytest.raises(ValueError, match="outside the tank"):
        sim.drop(sim.initial_state(), Stones(0.0, 0.75, 0.1, 0.01))
    ship = Ship(Hull("gaussian", 0.3, 0.1), straight_path((0.0, 0.0), (0.5, 0.0)), 0.01)
    with pytest.raises(ValueError, match="ships in a tank"):
        sim.step(sim.initial_state(), ships=[ship])
    # a varying floor in the tank is stepped (tests/simulation/test_steppers.py), the land kept still
    bump = depth_state(sim.model, np.full((32, 32), 1e-3))
    assert np.count_nonzero(np.asarray(bump.fields[0])) == 32 * 16  # the tank's block only
    after, _ = step_symmetric(sim.model, Floor(np.full((32, 32), 0.5)), bump)
    assert np.abs(np.asarray(after.fields[0]).reshape(32, 32)[:8]).max() == 0.0
