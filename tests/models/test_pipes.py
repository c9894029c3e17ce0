"""The virtual pipes (docs/physics.md §1.14), measured: mass to rounding and depths never negative (by the
outflow scaling), a lake at rest at rest, and their failures — waves √2 too fast once both pipes of a face
carry flow (so a constant cross-section is right at no depth it was not tuned for), a dam break whose front
lags Ritter's at every resolution, and the Courant number where they blow up."""

import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from wavephys.checks.shallow_water import dam_break_errors, pipes_dam_break, pipes_seiche
from wavephys.models.pipes import (Pipes, PipesState, PipesStepper, pipes_courant, pipes_run, pipes_state,
                                   pipes_step)

G = 9.81


@pytest.fixture(autouse=True)
def x64():
    with jax.enable_x64(True):
        yield


def test_mass_is_conserved_and_depth_stays_non_negative():
    rng = np.random.default_rng(2)
    for trial in range(3):
        n = 32
        bed = 0.2 * rng.standard_normal((n, n))
        depth = np.maximum(0.3 * rng.uniform(size=(n, n)) - 0.1, 0.0)  # a patchy, partly dry floor
        for sides in ("wall", "periodic"):
            pipes = Pipes(1.0 / n, sides=sides)
            state = pipes_state(bed, depth=depth, dtype=jnp.float64)
            end = PipesStepper(pipes, bed, 0.2 / n / math.sqrt(G * 0.5)).run(state, steps=400).state
            assert float(end.depth.min()) >= 0
            assert abs(float(end.depth.sum()) / float(state.depth.sum()) - 1) < 1e-13
            assert float(end.flows.min()) >= 0


def test_a_lake_at_rest_stays_at_rest():
    rng = np.random.default_rng(4)
    bed = rng.uniform(0, 0.6, (24, 24))
    state = pipes_state(bed, 0.5, dtype=jnp.float64)
    end = PipesStepper(Pipes(0.05), bed, 0.005).run(state, steps=500).state
    eta = np.asarray(end.depth) + bed
    wet = np.asarray(state.depth) > 0
    assert np.abs(eta - 0.5)[wet].max() < 1e-13
    assert np.array_equal(np.asarray(end.depth) == 0, np.asarray(state.depth) == 0)


@pytest.mark.parametrize("depth", [0.05, pytest.param(0.01, marks=pytest.mark.slow),
                                   pytest.param(0.2, marks=pytest.mark.slow)])
def test_waves_run_sqrt_2_too_fast_and_a_constant_area_is_right_at_no_depth(depth):
    """Both pipes of a face end up carrying flow, so the net flux accelerates at 2gA/l: c² = 2gA/l. With A = l h
    the seiche is √2 too fast at every depth; with a constant A the speed does not follow the depth."""
    r = pipes_seiche(depth, amplitude=0.02 * depth)
    assert r["frequency_ratio"] == pytest.approx(math.sqrt(2), rel=2e-3)
    assert r["mass"] < 1e-13 and r["damping"] < 0.015  # at amplitude/depth = 2 %: < 1.5 % a period
    dx = 1.0 / 64
    area = dx * dx
    c = pipes_seiche(depth, area=area, amplitude=0.02 * depth)
    assert c["frequency_ratio"] == pytest.approx(math.sqrt(2 * area / dx / depth), rel=5e-3)


def test_their_damping_grows_with_the_amplitude():
    """The clamps act once flows reverse: 0.6 % a period at amplitude/depth = 1 %, 4 % at 10 % (depth 1 cm)."""
    small, large = pipes_seiche(0.01, amplitude=1e-4), pipes_seiche(0.01, amplitude=1e-3)
    assert small["damping"] < 0.01 < 0.03 < large["damping"]


def test_the_courant_number_where_pipes_blow_up_is_measured():
    """Stable to c Δt/l = 0.7 in 1-D and 0.5 in 2-D (c = √(gh), the nominal speed: the effective one is √2
    larger), unstable from 0.72 and 0.52."""
    assert pipes_seiche(courant=0.7, periods=6)["growth"] < 2
    assert pipes_seiche(courant=0.72, periods=6)["growth"] > 10
    assert pipes_seiche(courant=0.5, periods=3, rows=32)["growth"] < 2
    assert pipes_seiche(courant=0.52, periods=3, rows=32)["growth"] > 10


def test_a_dam_break_in_pipes_lags_ritter_at_every_resolution():
    """The pipes carry no momentum (no u·∇u): the dry-bed front lags the exact 2√(gh) t by more than half its
    run, and refining does not help — the error stays while the finite-volume solver's shrinks."""
    coarse, fine = pipes_dam_break(200), pipes_dam_break(800)
    assert fine["front"] < -3.0 and coarse["front"] < -3.0
    assert fine["l1"] > 0.9 * coarse["l1"] > 0.05
    assert fine["mass"] < 1e-13
    assert dam_break_errors(800)["l1"] < 0.02 * fine["l1"]


def test_step_and_run_agree_and_bad_input_is_refused():
    bed = np.zeros((8, 8))
    state = pipes_state(bed, depth=np.linspace(0.1, 0.3, 64).reshape(8, 8), dtype=jnp.float64)
    pipes = Pipes(0.1)
    one = state
    for _ in range(5):
        one = pipes_step(pipes, bed, one, 0.01)
    five = PipesStepper(pipes, bed, 0.01).run(state, steps=5).state
    assert np.abs(np.asarray(one.depth) - np.asarray(five.depth)).max() < 1e-15
    assert float(five.time) == pytest.approx(0.05)
    with pytest.warns(DeprecationWarning, match="PipesStepper"):  # the old name, for a release
        old = pipes_run(pipes, bed, state, 5, 0.01)
    assert np.array_equal(np.asarray(old.depth), np.asarray(five.depth))
    assert pipes_courant(pipes, 0.3, 0.01) == pytest.approx(math.sqrt(G * 0.3) * 0.1)
    with pytest.raises(ValueError, match="area"):
        Pipes(0.1, area="volume")
    with pytest.raises(TypeError, match="area"):
        Pipes(0.1, area=[1.0])
    with pytest.raises(ValueError, match="sides"):
        Pipes(0.1, sides="open")
    with pytest.raises(ValueError, match="dt"):
        pipes_step(pipes, bed, state, 0.0)
    with pytest.raises(ValueError, match="bed"):
        PipesStepper(pipes, np.zeros((4, 4)), 0.01).run(state, steps=3)
    with pytest.raises(TypeError, match="state"):
        PipesStepper(pipes, bed, 0.01).run("state", steps=3)
    with pytest.raises(ValueError, match="exactly one"):
        pipes_state(bed)
    assert isinstance(jax.jit(lambda s: PipesStepper(pipes, bed, 0.01).advance(s, 3))(state), PipesState)
