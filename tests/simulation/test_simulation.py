import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from wavephys import Grid, Simulation, Stones, Water
from wavephys.checks import dispersion_scene
from wavephys.physics.heights import monochromatic_wave
from wavephys.physics.disturbances import stone_height, stone_height_spectrum
from wavephys.physics.heights import first_order_height, height_rate, second_order_height
from wavephys.physics.ring_waves import propagate
from wavephys.harness import dispersion_error, measure_energy

GRID = Grid(64, 2.0)
WATER = Water()


def _stone_state(sim, depth=1e-3):
    return sim.drop(sim.initial_state(), Stones(0.1, -0.2, 4 * float(sim.grid.dx), depth))


class TestStep:
    def test_step_is_exact_propagation_and_surface_of_input(self):
        sim = Simulation(GRID, WATER, dt=0.03)
        st, _ = sim.run(_stone_state(sim), 3)  # moving water: η̇ ≠ 0
        new, surf = sim.step(st)
        scale = float(jnp.max(jnp.abs(st.psi)))
        assert float(jnp.max(jnp.abs(new.psi - propagate(st.psi, GRID, WATER, 0.03)))) < 1e-5 * scale
        eta = first_order_height(st.psi, GRID, WATER)
        assert float(jnp.max(jnp.abs(surf.eta - eta))) < 1e-5 * float(jnp.max(jnp.abs(eta)))
        rate = height_rate(st.psi, GRID, WATER)
        assert float(jnp.max(jnp.abs(surf.eta_dot - rate))) < 1e-5 * float(jnp.max(jnp.abs(rate)))
        assert float(new.time) == pytest.approx(0.12) and float(surf.time) == pytest.approx(0.09)

    def test_dropped_stone_is_the_crater(self):
        sim = Simulation(GRID, WATER, dt=0.03)
        x, y = (float(GRID.coordinates[i]) for i in (36, 26))
        stones = Stones(x, y, 4 * float(GRID.dx), 1e-3)  # centre on sample (row 26, column 36)
        surf = sim.surface(sim.drop(sim.initial_state(), stones))
        crater = stone_height(stones, GRID)
        assert float(jnp.max(jnp.abs(surf.eta - crater))) < 1e-4 * 1e-3
        assert float(jnp.min(surf.eta)) == pytest.approx(-1e-3, rel=1e-3)

    def test_stones_in_step_equal_drop_before_step(self):
        sim = Simulation(GRID, WATER, dt=0.03)
        stones = Stones([0.0, 0.5], [0.0, 0.3], [0.15, 0.1], [1e-3, 2e-3])
        a, sa = sim.step(sim.initial_state(), stones)
        b, sb = sim.step(sim.drop(sim.initial_state(), stones))
        assert float(jnp.max(jnp.abs(a.psi - b.psi))) < 1e-6 * float(jnp.max(jnp.abs(b.psi)))
        assert float(jnp.max(jnp.abs(sa.eta - sb.eta))) < 1e-8

    def test_stone_spectrum_matches_space_profile(self):
        stones = Stones([0.1, -0.3], [0.2, 0.0], [0.1, 0.12], [0.01, 0.02])  # 3 dx ≤ R ≪ L
        space = stone_height(stones, GRID)
        spec = jnp.fft.irfft2(stone_height_spectrum(stones, GRID), s=(64, 64))
        assert float(jnp.max(jnp.abs(space - spec))) < 1e-6 * 0.02

    def test_run_equals_repeated_steps(self):
        sim = Simulation(GRID, WATER, dt=0.02, margin=8)
        st = _stone_state(sim)
        end, surfs = sim.run(st, 5)
        s = st
        for i in range(5):
            s, surf = sim.step(s)
            np.testing.assert_allclose(surfs.eta[i], surf.eta, atol=1e-9)
        np.testing.assert_allclose(end.phi, s.phi, atol=1e-9)

    def test_second_order_in_step(self):
        sim = Simulation(GRID, Water(sigma=0.0), dt=0.02, second_order=True)
        psi, k, A = monochromatic_wave(GRID, Water(sigma=0.0), 0.2)
        surf = sim.surface(sim.state_from_psi(psi))
        np.testing.assert_allclose(surf.eta, second_order_height(psi, GRID, Water(sigma=0.0)), atol=1e-6 * A)
        crest = float(GRID.refine(surf.eta, 32).max())  # the crest falls between samples
        assert crest - A == pytest.approx(0.5 * k * A * A, rel=1e-3)


class TestEnergy:
    def test_matches_measured_energy_of_surface(self):
        sim = Simulation(GRID, WATER, dt=0.02)
        st = _stone_state(sim)
        surf = sim.surface(st)
        e = measure_energy(surf.eta, surf.eta_dot, float(GRID.dx), WATER)
        assert float(sim.energy(st)) == pytest.approx(e.total, rel=1e-4)

    def test_cutoff_removes_energy(self):
        sim = Simulation(GRID, WATER, dt=0.05, margin=8)
        st = _stone_state(sim)
        end, _ = sim.run(st, 400)
        assert float(sim.energy(end)) < 0.05 * float(sim.energy(st))


class TestMeasuredDispersion:
    def test_surface_tension_switch_changes_the_result(self):
        """Dropping σ on a capillary grid is measurably wrong (the check can fail)."""
        s = dispersion_scene(WATER, 64, 0.064, 1e-3, 1024).select(k_min=300.0)
        assert np.abs(dispersion_error(s, Water(sigma=0.0))).max() > 0.5

    @pytest.mark.parametrize("depth", [0.05, 0.3, 2.0])
    def test_finite_depth_dispersion_is_measured(self, depth):
        """A family of depths (the registry measures deep water): the ridge follows tanh(kh)."""
        water = Water(sigma=0.0, depth=depth)
        s = dispersion_scene(water, 32, 8.0, 0.1, 256)
        assert s.k.size > 50
        assert np.abs(dispersion_error(s, water)).max() < 0.005
        assert np.abs(dispersion_error(s, Water(sigma=0.0))).max() > 0.02  # deep-water theory is off


class TestHermiteFrames:
    def test_frame_at_ends_is_exact(self):
        sim = Simulation(GRID, WATER, dt=0.05)
        st = _stone_state(sim)
        st1, s0 = sim.step(st)
        _, s1 = sim.step(st1)
        np.testing.assert_allclose(sim.frame(s0, s1, 0.0), s0.eta, atol=1e-12)
        np.testing.assert_allclose(sim.frame(s0, s1, 1.0), s1.eta, atol=1e-9)


class TestBadInput:
    @pytest.mark.parametrize("kw,name", [(dict(dt=0.0), "dt"), (dict(dt=-1.0), "dt"), (dict(dt=math.nan), "dt"),
                                         (dict(margin=32), "margin"), (dict(margin=-1), "margin"),
                                         (dict(cutoff="cubic"), "cutoff"), (dict(dtype=jnp.int32), "dtype")])
    def test_constructor(self, kw, name):
        with pytest.raises(ValueError, match=name):
            Simulation(GRID, WATER, **{"dt": 0.1, **kw})

    def test_float64_without_x64_is_explained(self):
        with pytest.raises(ValueError, match="x64"):
            Simulation(GRID, WATER, dt=0.1, dtype=jnp.float64)

    def test_wrong_types(self):
        with pytest.raises(TypeError, match="grid"):
            Simulation((64, 2.0), WATER)

    def test_state_and_disturbances(self):
        sim = Simulation(GRID, WATER, dt=0.1)
        with pytest.raises(ValueError, match="psi"):
            sim.state_from_psi(jnp.zeros((32, 32)))
        with pytest.raises(ValueError, match="eta"):
            sim.add_height(sim.initial_state(), jnp.full((64, 64), jnp.nan))
        with pytest.raises(ValueError, match="x"):
            sim.drop(sim.initial_state(), Stones(5.0, 0.0, 0.1, 1e-3))
        with pytest.raises(ValueError, match="radius"):
            sim.drop(sim.initial_state(), Stones(0.0, 0.0, 0.001, 1e-3))
        with pytest.raises(ValueError, match="depth"):
            Stones(0.0, 0.0, 0.1, -1.0)
        with pytest.raises(ValueError, match="radius"):
            Stones(0.0, 0.0, math.nan, 1.0)
        with pytest.raises(ValueError, match="steps"):
            sim.run(sim.initial_state(), 0)


def test_float64_simulation(x64):
    sim = Simulation(GRID, WATER, dt=0.03, dtype=jnp.float64)
    st = _stone_state(sim)
    new, surf = sim.step(st)
    assert new.phi.dtype == jnp.float64 and surf.eta.dtype == jnp.float64
    assert float(jnp.max(jnp.abs(new.psi - propagate(st.psi, GRID, WATER, 0.03)))) < 1e-13
