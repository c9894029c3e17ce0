"""Open sides of the shallow-water solver: a lake at rest stays at rest over any bed, for the whole run;
outgoing waves leave; the sea outside is the one asked for (docs/physics.md §1.13, "Open sides")."""

import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from wavephys.checks.shallow_water import lake_at_rest
from wavephys.simulation.shallow_water import (Inflow, Open, ShallowWater, SWState, _rate, sw_mass, sw_run,
                                               sw_state, sw_step)

G = 9.81


@pytest.fixture(autouse=True)
def x64():
    with jax.enable_x64(True):
        yield

ENDS = {"left": "open", "right": "open"}  # a 1-D channel open at both ends


def _ramp_beds(rng, n, count):
    """1-D beds, depths 0.34–0.84 m: random cells, ramps up and down, a sine (the family the defect showed on)."""
    x = (np.arange(n) + 0.5) / n
    beds = [-rng.uniform(0.34, 0.84, n) for _ in range(count)]
    beds += [-(0.34 + 0.5 * x), -(0.84 - 0.5 * x), -(0.6 + 0.2 * np.sin(2 * np.pi * rng.uniform(0.5, 2) * x))]
    return [b[None] for b in beds]


@pytest.mark.parametrize("order", [1, 2])
def test_a_seeded_lake_at_rest_over_an_uneven_bed_does_not_grow_with_open_ends(order):
    """The case that showed the defect: 8 cells, dx 0.1 m, 1e-12 m seeded in one cell. With zero-gradient ends
    it reached 8e-7 m at 4 s and 1 m at 8 s; now it stays at the seed's size or below for 30 s."""
    rng = np.random.default_rng(order)
    for bed in _ramp_beds(rng, 8, 3):
        state = sw_state(bed, 0.0, dtype=jnp.float64)
        state = SWState(state.fields.at[0, 0, rng.integers(8)].add(1e-12), state.time)
        end, steps = sw_run(ShallowWater(0.1, sides=ENDS, order=order), bed, state, until=30.0)
        eta = np.abs(np.asarray(end.h[0]) + bed[0])
        assert steps > 1500
        assert eta.max() <= 1e-12, eta.max()
        assert np.abs(np.asarray(end.fields[1])).max() <= 1e-11


@jax.jit
def _jacobian(solver, bed, fields):
    """The rate at ``fields`` and its Jacobian there (one compiled program per shape)."""
    def rate(f):
        return _rate(solver, bed, f, 0.0)

    return rate(fields), jax.jacfwd(rate)(fields)


@pytest.mark.parametrize("order", [1, 2])
def test_the_linearized_scheme_with_open_ends_has_no_growing_mode(order):
    """Every eigenvalue of the linearized rate about a lake at rest has a negative real part, for beds the
    zero-gradient ends made unstable (there: +0.90 s⁻¹ on a ramp, +3.06 s⁻¹ on a sine, at any resolution)."""
    rng = np.random.default_rng(10 + order)
    for n in (16,):  # the growth of zero-gradient sides was the same from 8 to 128 cells
        for bed in _ramp_beds(rng, n, 2):
            solver = ShallowWater(0.8 / n, sides=ENDS, order=order)
            state = sw_state(bed, 0.0, dtype=jnp.float64)
            solver = solver.settle(bed, state)
            rate, jac = _jacobian(solver, jnp.asarray(bed), state.fields)
            assert float(jnp.abs(rate).max()) < 1e-12
            jac = np.asarray(jac).reshape(3 * n, 3 * n)[:2 * n, :2 * n]
            growth = np.linalg.eigvals(jac).real.max()
            assert growth < -0.1, (n, growth)


@pytest.mark.parametrize("dtype,order", [("float32", 2), ("float64", 1),
                                         pytest.param("float32", 1, marks=pytest.mark.slow),
                                         pytest.param("float64", 2, marks=pytest.mark.slow)])
def test_a_lake_at_rest_with_islands_stays_at_rest_with_open_sides_for_the_whole_run(dtype, order):
    """2-D beds with islands breaking the surface, open on all four sides, 12 s (about 3,000 steps): with
    zero-gradient sides these reached 1.23 m (order 1) and 0.73 m (order 2)."""
    eps = {"float64": 2.3e-16, "float32": 1.2e-7}[dtype]
    for seed in range(2):
        r = lake_at_rest(24, seed=seed, order=order, dtype=dtype, sides="open", until=12.0)
        assert r["islands"] > 0 and r["steps"] > 2500  # the zero-gradient growth (e^(3t)) shows within 10 s
        assert r["eta"] <= 8 * eps, r
        assert r["momentum"] <= 200 * eps * math.sqrt(G), r
        assert r["dry_wetted"] == 0


@pytest.mark.slow
@pytest.mark.parametrize("order", [1, 2])
def test_a_lake_at_rest_with_open_sides_over_a_hundred_thousand_steps(order):
    rng = np.random.default_rng(40 + order)
    for bed in _ramp_beds(rng, 16, 2):
        state = sw_state(bed, 0.0, dtype=jnp.float64)
        state = SWState(state.fields.at[0, 0, 5].add(1e-12), state.time)
        end, steps = sw_run(ShallowWater(0.05, sides=ENDS, order=order), bed, state, until=820.0)
        assert steps >= 100_000
        assert np.abs(np.asarray(end.h[0]) + bed[0]).max() <= 1e-12


@pytest.mark.parametrize("order", [1, 2])
def test_a_hump_leaves_through_open_ends(order):
    """A Gaussian hump splits and both halves leave a 1 m deep, 20 m channel: what stays is the reflection."""
    n, dx = 400, 0.05
    x = (np.arange(n) + 0.5) * dx
    bed = -np.ones((1, n))
    for amp, left in ((0.001, 1e-5), (0.05, 2e-4), (0.2, 1e-3)):
        state = sw_state(bed, (amp * np.exp(-((x - 10) / 0.5) ** 2))[None], dtype=jnp.float64)
        end, _ = sw_run(ShallowWater(dx, sides=ENDS, order=order), bed, state, until=10 / math.sqrt(G) + 3)
        assert np.abs(np.asarray(end.h[0]) + bed[0]).max() <= left * amp, amp


def test_an_open_side_drains_to_its_sea_level():
    """A pool 0.1 m above the sea outside (Open(level=0)) drains through its open end down to the sea: mass
    leaves and the surface settles at 0."""
    n, dx = 64, 0.05
    bed = -np.linspace(0.5, 1.0, n)[None]
    state = sw_state(bed, 0.1, dtype=jnp.float64)
    solver = ShallowWater(dx, sides={"right": Open(level=0.0)})
    end, _ = sw_run(solver, bed, state, until=30.0)
    eta = np.asarray(end.h[0]) + bed[0]
    assert np.abs(eta).max() < 2e-3, np.abs(eta).max()
    assert float(sw_mass(end, dx)) < float(sw_mass(state, dx)) - 0.09 * n * dx * dx
    # a level per edge cell along the side, and the plain string, settle to the same sea
    a = ShallowWater(dx, sides={"right": Open(level=np.zeros(1))}).settle(bed, state)
    b = ShallowWater(dx, sides={"right": Open(level=0.0)}).settle(bed, state)
    np.testing.assert_array_equal(np.asarray(a.inflows[1].depth), np.asarray(b.inflows[1].depth))


def test_an_inflow_at_the_lakes_level_keeps_it_at_rest():
    rng = np.random.default_rng(3)
    bed = -rng.uniform(0.34, 0.84, 16)[None]
    calm = Inflow([0.0, 100.0], [0.0, 0.0])
    for order in (1, 2):
        end, _ = sw_run(ShallowWater(0.1, sides={"left": calm, "right": "open"}, order=order), bed,
                        sw_state(bed, 0.0, dtype=jnp.float64), until=20.0)
        assert np.abs(np.asarray(end.h[0]) + bed[0]).max() <= 1e-15


def test_single_steps_need_a_settled_open_side():
    bed = -np.ones((1, 8))
    state = sw_state(bed, 0.0, dtype=jnp.float64)
    solver = ShallowWater(0.1, sides=ENDS)
    assert not solver.settled
    with pytest.raises(ValueError, match=r"solver.settle\(bed, state\)"):
        sw_step(solver, bed, state)
    settled = solver.settle(bed, state)
    assert settled.settled and settled.sides == solver.sides
    assert settled.settle(bed, state) is not None
    step = sw_step(settled, bed, state)
    assert np.abs(np.asarray(step.h) - 1.0).max() == 0.0
    sw_step(ShallowWater(0.1, sides={"left": Open(level=0.0)}), bed, state)  # a given level needs no settling
    with pytest.raises(ValueError, match="one per edge cell"):
        ShallowWater(0.1, sides={"left": Open(level=np.zeros(3))}).settle(bed, state)
    with pytest.raises(TypeError, match="level"):
        Open(level="sea")
    with pytest.raises(TypeError, match="sides"):
        ShallowWater(0.1, sides={"left": 3})
