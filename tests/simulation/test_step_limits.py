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
    # a state that skipped the checks (as one a compiled function returns does: pytrees are rebuilt unchecked)
    treedef = jax.tree_util.tree_structure(state)
    unchecked = jax.tree_util.tree_unflatten(treedef, [jnp.asarray(bad), state.time])
    with pytest.raises(ValueError, match="NaN or inf values; no step is stable"):
        stable_dt(ShallowWater(0.1), unchecked)  # before: a finite step, the NaN cell read as dry
    pipes = pipes_state(bed, 0.0)
    depth = np.asarray(pipes.depth).copy()
    depth[0, 3] = np.nan
    leaves, treedef = jax.tree_util.tree_flatten(pipes)
    unchecked = jax.tree_util.tree_unflatten(treedef, [jnp.asarray(depth) if np.shape(v) == depth.shape else v
                                                       for v in leaves])
    with pytest.raises(ValueError, match="NaN or inf values; a step needs a finite state"):
        pipes_step(Pipes(0.1), bed, unchecked, 0.01)


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


def _past_the_limit(name):
    """A stepper ``name`` on 1 m of water with a bump (2 × 32, float64 on), a Δt 30 × its stable one, its
    concrete refusals checked: (stepper, state, dt for advance, the depth of a state, the state scaled by 1 + a)."""
    from wavephys.models.pipes import PipesStepper
    from wavephys.simulation.shallow_water import ShallowWaterStepper
    from wavephys.simulation.split import Split, SplitStepper

    bed = -np.ones((2, 32))
    bump = 0.05 * np.exp(-((np.arange(32) - 16.0) / 3) ** 2) * np.ones((2, 1))
    if name == "PipesStepper":
        pipes = Pipes(0.1, sides="periodic")
        state = pipes_state(bed, bump, dtype=jnp.float64)
        stepper = PipesStepper(pipes, bed, 0.5 * 0.1 / np.sqrt(9.81 * 1.05))
        fast = PipesStepper(pipes, bed, 30 * stepper.dt)
        with pytest.raises(ValueError, match="dt = .* is past the stable step: Courant"):
            fast.init(state)
        with pytest.raises(ValueError, match="steps its own dt"):  # a fixed-Δt stepper: another Δt is refused
            stepper.step(state, 30 * stepper.dt)
        return fast, state, None, lambda s: s.depth, lambda a: type(state)(state.depth * (1 + a), state.flows,
                                                                            state.time)
    solver = ShallowWater(0.1, sides="periodic")
    fast = ShallowWaterStepper(solver, bed) if name == "ShallowWaterStepper" else \
        SplitStepper(Split(solver, levels=(1.0,)), bed)
    state = sw_state(bed, bump, dtype=jnp.float64)
    dt = 30 * float(stable_dt(solver, state)) / solver.cfl
    with pytest.raises(ValueError, match="past the stable step"):
        fast.step(state, dt)
    return fast, state, dt, lambda s: s.fields[0], lambda a: type(state)(state.fields * (1 + a), state.time)


@pytest.mark.parametrize("name", ["ShallowWaterStepper", "SplitStepper", "PipesStepper"])
def test_under_jit_a_step_past_the_limit_of_each_nonlinear_stepper_shows(name):
    """The documented behaviour under a trace, where nothing can be refused before the work (wavephys.core.stepper
    ``advance``): 40 steps of 30 × the stable step (the pipes: 30 × their Courant limit) give a state that is not
    finite, or negative depths (shallow water, the split); the same Δt with concrete arrays is refused by name.
    Through ``jax.grad`` the value and gradient are NaN: the pipes here (their NaN is added, so the gradient sees
    it), shallow water in the slow set (compiling its gradient takes 19 s). (The pipes
    keep depths ≥ 0 whatever Δt: before their step turned NaN past the limit, 30 × answered finite depths of 0 to
    2.5 m on water 1 m deep under jit, and a finite value and gradient through jax.grad.)"""
    with jax.enable_x64(True):
        fast, state, dt, depth, scaled = _past_the_limit(name)
        out = depth(jax.jit(lambda s: fast.advance(s, 40, dt))(state))
        assert not np.all(np.isfinite(out)) or np.min(out) < 0, (name, np.nanmin(out))
        if name == "PipesStepper":
            value, gradient = jax.value_and_grad(lambda a: jnp.sum(depth(fast.advance(scaled(a), 40, dt)) ** 2))(0.0)
            assert np.isnan(value) and np.isnan(gradient), (name, value, gradient)


@pytest.mark.slow  # compiling the gradient of shallow water's step: 19 s on 2 cores
@pytest.mark.parametrize("name", ["ShallowWaterStepper"])
def test_through_grad_a_step_past_the_limit_is_nan(name):
    """40 steps of 30 × the stable step through ``jax.grad``: a NaN value and a NaN gradient. The split's gradient
    was measured so too (NaN, NaN) but is not run: compiling it takes 55 s at LLVM level 1, more at CI's defaults."""
    with jax.enable_x64(True):
        fast, state, dt, depth, scaled = _past_the_limit(name)
        value, gradient = jax.value_and_grad(lambda a: jnp.sum(depth(fast.advance(scaled(a), 40, dt)) ** 2))(0.0)
        assert np.isnan(value) and np.isnan(gradient), (name, value, gradient)


def test_a_pipes_run_whose_water_deepens_past_the_courant_limit_is_refused_by_name():
    """A dam break against a wall at a Δt 0.69 of the 1-D limit for the water at the start: the reflected water
    piles to 1.08 m at 2.2 s, a Courant number of 0.72 (measured with the unchecked loop); the run stops there and
    says why (before, it answered on past the limit)."""
    from wavephys.models.pipes import PipesStepper

    with jax.enable_x64(True):
        bed = np.zeros((1, 64))
        state = pipes_state(bed, depth=np.where(np.arange(64) < 32, 1.0, 0.0)[None], dtype=jnp.float64)
        stepper = PipesStepper(Pipes(0.1), bed, 0.69 * 0.1 / np.sqrt(9.81))
        with pytest.raises(ValueError, match=r"non-finite by t = 2\.\d+ s: the water grew deep enough .*Courant"):
            stepper.run(state, steps=2000, every=100)
        assert np.isfinite(np.asarray(stepper.run(state, steps=80).state.depth)).all()  # before the pile-up
