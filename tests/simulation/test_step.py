"""The pure step: a model pytree, one source protocol, jit/vmap/grad, and the wrapper's equality."""

import dataclasses

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from wavephys import Grid, Simulation, Stones, Water, stack
from wavephys.physics.forcing import Forcing
from wavephys.physics.ship_waves import Hull, Ship, straight_path
from wavephys.physics.wake import GaussianPressure, steady_wake
from wavephys.physics.wind import WindSea
from wavephys.simulation import Model, add_height, add_source, checked, initial_state, run, step, surface

GRID = Grid(64, 4.0)
STONE = Stones(0.3, -0.2, 0.25, 1e-3)


def _ring(model, steps=3):
    state = add_source(model, initial_state(model), STONE)
    for _ in range(steps):
        state, _ = step(model, state)
    return state


class TestModel:
    def test_simulation_model_is_the_model(self):
        sim = Simulation(GRID, Water(depth=0.5), dt=0.05, margin=8)
        assert isinstance(sim.model, Model) and sim.model.water == Water(depth=0.5)
        state = sim.drop(sim.initial_state(), STONE)
        a, sa = sim.step(state)
        b, sb = step(sim.model, state)
        np.testing.assert_array_equal(a.fields, b.fields)
        np.testing.assert_array_equal(sa.fields, sb.fields)

    def test_replace_makes_variants(self):
        model = Model(GRID, Water(), dt=0.05)
        shallow = dataclasses.replace(model, water=Water(depth=0.1))
        a = surface(model, _ring(model)).eta
        b = surface(shallow, _ring(shallow)).eta
        assert float(jnp.max(jnp.abs(a - b))) > 0.1 * float(jnp.max(jnp.abs(a)))

    def test_is_a_pytree_with_static_options(self):
        model = Model(GRID, Water(), dt=0.05, margin=4, second_order=True)
        leaves, tree = jax.tree_util.tree_flatten(model)
        assert len(leaves) == 6  # length, g, rho, sigma, depth, dt
        back = jax.tree_util.tree_unflatten(tree, leaves)
        assert back.margin == 4 and back.second_order and back.grid.n == 64

    @pytest.mark.parametrize("kw,error,name", [
        (dict(grid=(64, 4.0)), TypeError, "grid"), (dict(water="deep"), TypeError, "water"),
        (dict(dt=0.0), ValueError, "dt"), (dict(margin=32), ValueError, "margin"),
        (dict(cutoff="cubic"), ValueError, "cutoff"), (dict(second_order="yes"), TypeError, "second_order"),
        (dict(dtype="int32"), ValueError, "dtype"), (dict(ship_patch=7), ValueError, "ship_patch"),
        (dict(ship_method="sails"), ValueError, "ship_method")])
    def test_bad_model(self, kw, error, name):
        with pytest.raises(error, match=name):
            Model(**{"grid": GRID, **kw})


class TestTransformations:
    def test_vmap_over_eight_depths_equals_eight_runs(self):
        depths = [0.05, 0.1, 0.2, 0.4, 0.8, 1.6, 3.2, float("inf")]
        base = Model(GRID, Water(), dt=0.05)
        state = _ring(base, 0)

        def eta(water):
            model = dataclasses.replace(base, water=water)
            s, _ = step(model, state)
            return step(model, s)[1].eta

        batched = jax.vmap(eta)(stack([Water(depth=d) for d in depths]))
        for i, d in enumerate(depths):
            single = eta(Water(depth=d))
            # float32 rounding: traced multipliers are float32, a concrete model's are rounded from float64
            np.testing.assert_allclose(batched[i], single, atol=2e-6 * float(jnp.max(jnp.abs(single))))
        assert float(jnp.max(jnp.abs(batched[0] - batched[-1]))) > 0  # the depths matter

    @pytest.mark.parametrize("field,value", [("depth", 0.3), ("sigma", 0.0728)])
    def test_grad_matches_finite_difference(self, field, value, x64):
        base = Model(Grid(32, 1.0), Water(), dt=0.02, dtype="float64")
        state = add_source(base, initial_state(base), Stones(0.0, 0.0, 0.1, 1e-3))
        weights = jnp.cos(jnp.arange(32.0))[None, :] * jnp.sin(jnp.arange(32.0))[:, None]

        def f(x):
            model = dataclasses.replace(base, water=dataclasses.replace(base.water, **{field: x}))
            s = state
            for _ in range(4):
                s, surf = step(model, s)
            return jnp.sum(surf.eta * weights)

        grad = float(jax.grad(f)(value))
        h = 1e-4 * value  # central differences: truncation ~h², rounding ~1e-16|f|/h
        fd = (float(f(value + h)) - float(f(value - h))) / (2 * h)
        assert grad == pytest.approx(fd, rel=1e-5)
        assert abs(grad) > 0

    def test_jit_of_step(self):
        model = Model(GRID, Water(), dt=0.05, margin=4)
        state = _ring(model, 0)
        a = jax.jit(lambda s: step(model, s, [STONE]))(state)
        b = step(model, state, [STONE])
        np.testing.assert_allclose(a[0].fields, b[0].fields, atol=1e-7)


class TestSources:
    def test_stones_in_step_are_dropped_before_the_surface(self):
        model = Model(GRID, Water(), dt=0.05)
        a, sa = step(model, initial_state(model), [STONE])
        b, sb = step(model, add_source(model, initial_state(model), STONE))
        np.testing.assert_allclose(a.fields, b.fields, atol=1e-9)
        np.testing.assert_allclose(sa.eta, sb.eta, atol=1e-9)

    def test_wind_sea_source_equals_add_wind(self):
        sim = Simulation(GRID, Water(sigma=0.0), dt=0.05)
        key = jax.random.PRNGKey(3)
        a = sim.add_wind(sim.initial_state(), key, "phillips", wind_speed=3.0)
        b = add_source(sim.model, sim.initial_state(), WindSea(key, "phillips", dict(wind_speed=3.0)))
        np.testing.assert_array_equal(a.fields, b.fields)
        eta = sim.surface(a).eta
        assert float(jnp.std(eta)) > 0 and abs(float(jnp.mean(eta))) < 1e-3 * float(jnp.std(eta))

    def test_forcing_in_run_equals_steps(self):
        model = Model(GRID, Water(), dt=0.05, margin=4)
        push = Forcing(lambda x, y, t: 20.0 * jnp.exp(-((x - 0.3 * t) ** 2 + y**2) / 0.05))
        end, surfs = run(model, initial_state(model), 6, [push])
        s = initial_state(model)
        for i in range(6):
            s, surf = step(model, s, [push])
            np.testing.assert_allclose(surfs.eta[i], surf.eta, rtol=0, atol=1e-6 * float(jnp.max(jnp.abs(surf.eta))))
        scale = float(jnp.max(jnp.abs(s.fields)))
        np.testing.assert_allclose(end.fields, s.fields, rtol=0, atol=1e-6 * scale)
        assert scale > 0

    @pytest.mark.parametrize("omega_dt,substeps", [(0.3, 1), (1.0, 1), (2.0, 1), (2.0, 4), (3.0, 8)])
    def test_resonant_forcing_follows_the_midpoint_factor(self, omega_dt, substeps):
        """The documented failure boundary: a forcing moving with a wave of frequency ω is applied
        with the factor 2 sin(ωδ/2)/(ωδ), δ = Δt/substeps (exact Duhamel weights otherwise)."""
        grid, water, s0 = Grid(32, 8.0), Water(sigma=0.0), 1e-3
        k = 2 * np.pi * 3 / 8.0
        omega = float(np.sqrt(9.81 * k))
        dt = omega_dt / omega
        model = Model(grid, water, dt=dt, dtype="float32")
        push = Forcing(lambda x, y, t: -1000.0 * s0 * jnp.cos(k * x - omega * t), substeps)
        steps = 12
        state, _ = run(model, initial_state(model), steps, [push])
        amplitude = float(jnp.abs(jnp.fft.fft2(state.psi))[0, 3]) / (32 * 32 * s0 / 2 * steps * dt)
        x = omega_dt / substeps
        assert amplitude == pytest.approx(2 * np.sin(x / 2) / x, rel=2e-5)

    @pytest.mark.slow
    def test_moving_pressure_converges_to_its_steady_wake(self):
        """The Duhamel forcing and the steady-wake formula solve the same equation: a Gaussian
        pressure switched on smoothly and towed at U approaches its steady Kelvin wake."""
        grid, deep, speed, source = Grid(512, 20.0), Water(sigma=0.0), 1.0, GaussianPressure(100.0, 0.1)
        model = Model(grid, deep, dt=0.2, margin=16)
        x0 = -8.0
        ramp = lambda t: jnp.clip(t / 2.0, 0.0, 1.0) ** 2 * (3 - 2 * jnp.clip(t / 2.0, 0.0, 1.0))
        push = Forcing(lambda x, y, t: ramp(t) * source.amplitude * jnp.exp(-((x - x0 - speed * t) ** 2 + y**2)
                                                                            / (2 * source.size**2)), substeps=8)
        big = Grid(4096, 4096 * float(grid.dx))  # the steady wake must not wrap: it fades over U/ε = 200 m
        steady = steady_wake(big, deep, speed, source, damping=0.005)
        c = np.asarray(grid.coordinates)

        def difference(duration, behind):
            steps = int(round(duration / 0.2))
            state, _ = run(model, initial_state(model), steps, [push])
            eta = np.asarray(surface(model, state).eta)
            xs = x0 + speed * steps * 0.2
            ref = np.asarray(big.shift(steady, xs))[1792:2304, 1792:2304]  # the same samples as `grid`
            cols = (c > xs - behind[1]) & (c < xs - behind[0])
            a, b = eta[156:356][:, cols], ref[156:356][:, cols]
            return np.linalg.norm(a - b) / np.linalg.norm(b)

        near, waves = difference(15.0, (0.0, 2.0)), difference(15.0, (1.0, 6.0))
        assert near < 0.05 and waves < 0.08, (near, waves)
        assert difference(6.0, (1.0, 6.0)) > 2 * waves  # the wake is still forming at 6 s

    def test_not_a_source(self):
        model = Model(GRID, Water(), dt=0.05)
        with pytest.raises(TypeError, match="sources"):
            step(model, initial_state(model), [object()])
        with pytest.raises(TypeError, match="sources"):
            step(model, initial_state(model), STONE)  # one source, not a sequence

    def test_run_refuses_impulses_and_ships(self):
        model = Model(GRID, Water(), dt=0.05)
        with pytest.raises(ValueError, match="continuous"):
            run(model, initial_state(model), 3, [STONE])

    def test_ships_cannot_be_traced(self):
        model = Model(Grid(128, 8.0), Water(sigma=0.0), dt=0.05, margin=8)
        ship = Ship(Hull("gaussian", 0.4, 0.2), straight_path((0.0, 0.0), (0.5, 0.0)))
        with pytest.raises(TypeError, match="ships"):
            jax.jit(lambda s: step(model, s, [ship]))(initial_state(model))

    def test_state_of_another_grid_is_refused(self):
        model = Model(GRID, Water(), dt=0.05)
        other = initial_state(Model(Grid(32, 4.0), Water(), dt=0.05))
        with pytest.raises(ValueError, match="state"):
            step(model, other)
        with pytest.raises(TypeError, match="state"):
            step(model, other.fields)


class TestChecked:
    def test_checked_step_equals_step(self):
        model = Model(GRID, Water(), dt=0.05)
        state = _ring(model, 1)
        a, _ = step(model, state)
        b, _ = checked(step)(model, state)
        np.testing.assert_array_equal(a.fields, b.fields)

    def test_checked_catches_a_nan_made_inside(self):
        model = Model(GRID, Water(), dt=0.05)

        def broken(model, state):
            new, surf = step(model, state)
            return jnp.log(new.fields - 1.0)  # log of a negative number: NaN inside the trace

        with pytest.raises(ValueError, match="not finite"):
            checked(broken)(model, initial_state(model))


def test_heights_in_the_wrong_units_get_a_hint():
    model = Model(GRID, Water(), dt=0.05)
    with pytest.raises(ValueError, match="mm or cm"):
        add_height(model, initial_state(model), np.full((64, 64), 5.0))  # 5 "m" on a 4 m domain: millimetres?


@pytest.mark.slow
def test_an_hour_of_60_hz_steps_in_float32_keeps_time_and_matches_float64():
    """The clock is a compensated sum: 216,000 float32 steps of 1/60 s end at 3600 s to float32
    rounding (a plain float32 sum drifts by 2.8 s), so a ship's path position agrees with
    float64 to micrometres, and the surface after an hour agrees with the float64 run."""
    from wavephys.physics.ship_waves import straight_path

    steps, chunk = 3600 * 60, 21600

    def hour(dtype):
        model = Model(Grid(32, 4.0), Water(), dt=1 / 60, dtype=dtype)
        s = add_source(model, initial_state(model), Stones(0.0, 0.0, 0.4, 1e-3))
        for _ in range(steps // chunk):
            s, _ = run(model, s, chunk)
        return s, surface(model, s)

    s32, surf32 = hour("float32")
    naive = np.float32(0.0)
    for _ in range(steps):
        naive = np.float32(naive + np.float32(1 / 60))
    assert abs(float(naive) - 3600.0) > 1.0  # what the old clock did
    assert abs(s32.exact_time - 3600.0) < 1e-5
    with jax.enable_x64(True):
        s64, surf64 = hour("float64")
        assert abs(s64.exact_time - 3600.0) < 1e-9
        path = straight_path((-1.0, 0.0), (5.0, 0.0))  # 5 m/s: a drift of 2.8 s would be 14 m
        x32, x64 = np.asarray(path(s32.exact_time)), np.asarray(path(s64.exact_time))
        assert np.max(np.abs(x32 - x64)) < 1e-4
        eta32, eta64 = np.asarray(surf32.eta, np.float64), np.asarray(surf64.eta)
    # float32 loses amplitude by rounding, within the a-priori bound steps·eps·log2(n) on energy
    # (docs/physics.md §1.8): compare the shape (phase) and the amplitude apart
    a = float(np.sum(eta32 * eta64) / np.sum(eta64 * eta64))
    shape_error = np.max(np.abs(eta32 - a * eta64)) / np.max(np.abs(eta64))
    assert abs(1 - a) < 0.5 * steps * np.finfo(np.float32).eps * np.log2(32)  # measured 0.0164 < 0.0644
    assert shape_error < 1e-2  # measured 4.6e-3: float32 rounding of 216,000 steps, not the clock
