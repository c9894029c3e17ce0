"""No silent garbage from a step: a concrete Δt past a stepper's stable limit is refused by name, a state that
is not finite is refused, float64 without x64 is refused; under jit a step too long shows as NaN or negative
depth, which the runs refuse when their result is read (issue 52, item 6)."""

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from wavephys.models.pipes import COURANT_LIMITS, Pipes, pipes_courant, pipes_run, pipes_state, pipes_step
from wavephys.simulation.shallow_water import (ShallowWater, SWState, advance_fields, check_run, stable_dt,
                                               stable_dt_fields, sw_run, sw_state, sw_step)


def _family(rng, n=24):
    """A few 1-D and 2-D beds with a wave on them: depths 0.2–1.5 m, waves up to a tenth of the depth."""
    out = []
    for rows in (1, 6):
        depth = rng.uniform(0.2, 1.5)
        bed = -depth * (1 + 0.3 * rng.uniform(-1, 1, (rows, n)))
        eta = 0.1 * depth * np.sin(rng.uniform(0.2, 1.0) * np.arange(n))[None] * np.ones((rows, 1))
        out.append((bed, sw_state(bed, eta)))
    return out


def test_the_shallow_water_steps_refuse_a_step_past_courant_one_and_take_one_below():
    rng = np.random.default_rng(0)
    for (bed, state), order in zip(_family(rng)[1:], (2,)):  # a 2-D bed at order 2 (the steppers' set: each stepper)
        if True:
            solver = ShallowWater(0.1, order=order)
            limit = float(stable_dt(solver, state, bed)) / solver.cfl
            sw_step(solver, bed, state, dt=0.95 * limit)
            for factor in (1.05, 3.0, 1e4):
                with pytest.raises(ValueError, match=r"dt = .* past the stable step: Courant number"):
                    sw_step(solver, bed, state, dt=factor * limit)
                with pytest.raises(ValueError, match=r"dt = .* past the stable step"):
                    sw_run(solver, bed, state, steps=2, dt=factor * limit)
                with pytest.raises(ValueError, match=r"dt = .* past the stable step"):
                    advance_fields(solver, jnp.asarray(bed, state.fields.dtype), state.fields, 0.0,
                                   factor * limit)


def test_the_virtual_pipes_refuse_a_step_past_their_measured_courant_limit():
    rng = np.random.default_rng(2)
    for rows, limit in ((1, COURANT_LIMITS[0]), (8, COURANT_LIMITS[1])):
        depth = rng.uniform(0.05, 1.0)
        bed = np.zeros((rows, 32))
        state = pipes_state(bed, depth + 0.01 * depth * rng.standard_normal((rows, 32)))
        pipes = Pipes(0.1)
        unit = pipes_courant(pipes, float(np.max(state.depth)), 1.0)  # the Courant number of a 1 s step
        pipes_step(pipes, bed, state, 0.95 * limit / unit)
        for courant in (1.05 * limit, 3000.0):
            with pytest.raises(ValueError, match=rf"past the stable step: Courant number .* > {limit}"):
                pipes_step(pipes, bed, state, courant / unit)
            with pytest.raises(ValueError, match=rf"> {limit}"):
                pipes_run(pipes, bed, state, 3, courant / unit)


def test_courant_numbers_past_the_measured_range_are_refused_by_the_settings():
    with pytest.raises(ValueError, match="cfl"):
        ShallowWater(0.1, cfl=1.5)
    with pytest.raises(ValueError, match="cfl"):
        ShallowWater(0.1, cfl=1.0001)
    assert ShallowWater(0.1, cfl=1.0).cfl == 1.0


def test_states_that_are_not_finite_are_refused_by_what_reads_them():
    bed = -np.ones((1, 16))
    state = sw_state(bed, 0.0)
    bad = np.asarray(state.fields).copy()
    bad[0, 0, 3] = np.nan
    with pytest.raises(ValueError, match="finite"):
        SWState(bad, state.time)
    with pytest.raises(ValueError, match="finite"):
        stable_dt_fields(ShallowWater(0.1), bad)
    with pytest.raises(ValueError, match="finite"):
        check_run(ShallowWater(0.1), bad, 1.0)


def test_float64_without_x64_is_refused_by_the_state_makers():
    if jax.config.jax_enable_x64:
        pytest.skip("x64 is on in this process")
    bed = -np.ones((1, 8))
    with pytest.raises(ValueError, match="jax_enable_x64"):
        sw_state(bed, 0.0, dtype=np.float64)
    with pytest.raises(ValueError, match="jax_enable_x64"):
        pipes_state(bed, 0.0, dtype="float64")
    with jax.enable_x64(True):
        assert sw_state(bed, 0.0, dtype=np.float64).fields.dtype == np.float64


def test_under_jit_a_step_too_long_shows_as_non_finite_or_negative_depth():
    """Inside a trace nothing can be refused before the work: the documented behaviour is a field that is not
    finite or has negative depths, which check_run (and every run) turns into a ValueError naming dt."""
    bed = -np.ones((1, 32))
    state = sw_state(bed, 0.05 * np.exp(-((np.arange(32) - 16.0) / 3) ** 2)[None])
    solver = ShallowWater(0.1)
    limit = float(stable_dt(solver, state)) / solver.cfl

    @jax.jit
    def many(fields, dt):
        def body(f, _):
            return advance_fields(solver, jnp.asarray(bed, f.dtype), f, 0.0, dt), None
        return jax.lax.scan(body, fields, None, length=40)[0]

    out = np.asarray(many(state.fields, 30 * limit))
    assert not np.all(np.isfinite(out)) or out[0].min() < 0
    with pytest.raises(ValueError, match="dt = .* past the stable step"):
        check_run(solver, out, 1.0, dt=30 * limit)
