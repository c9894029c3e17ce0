"""The harness on a user's shallow water (docs/harness.md): correct solvers pass (ours, at two precisions, over
families of dams and beds) and simulators written the way engines write them get the right verdict and cause —
a Lax–Friedrichs scheme that is not well balanced, a solver that zeroes thin water, virtual pipes, a wrong g."""

import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from wavephys.harness.shallow_water import dam_break_check, lake_at_rest_check, mass_check
from wavephys.models.pipes import Pipes, pipes_run, pipes_state
from wavephys.simulation.shallow_water import ShallowWater, sw_frames, sw_state, sw_step

G = 9.81


@pytest.fixture(autouse=True)
def x64():
    with jax.enable_x64(True):
        yield


def _dam_frames(h0=1.0, hr=0.0, n=400, frames=9, g=G, dtype=jnp.float64):
    length = 2.6 * 2 * math.sqrt(G * h0) * 1.0
    dx = length / n
    x = (np.arange(n) + 0.5) * dx
    dam = 0.35 * length
    bed = np.zeros((1, n))
    solver = ShallowWater(dx, sides="wall", g=g)
    state = sw_state(bed, depth=np.where(x < dam, h0, hr)[None], dtype=dtype)
    out = sw_frames(solver, bed, state, np.linspace(0.0, 1.0, frames))
    return np.asarray(out.h, np.float64)[:, 0], dx, 1.0 / (frames - 1), dam


@pytest.mark.parametrize("h0,hr", [(1.0, 0.0), (0.5, 0.05), pytest.param(2.0, 0.0, marks=pytest.mark.slow),
                                   pytest.param(1.0, 0.3, marks=pytest.mark.slow)])
def test_a_correct_solver_passes_the_dam_break_and_keeps_its_mass(h0, hr):
    depth, dx, dt, dam = _dam_frames(h0, hr)
    row = dam_break_check(depth, dx, dt, h0, dam=dam, hr=hr)
    assert row.ok, row
    assert mass_check(depth, dx, rtol=1e-12).ok  # walls: nothing leaves


def test_a_coarse_solver_lags_and_is_told_to_refine():
    """At 200 cells our own solver's thin front (1 % of h0) runs 6 % slow: the check says it lags and converges
    with finer cells, not that g is wrong (the rarefaction's head is right)."""
    depth, dx, dt, dam = _dam_frames(n=200)
    row = dam_break_check(depth, dx, dt, 1.0, dam=dam)
    assert not row.ok and "lags" in row.note and "check g" not in row.note, row


def test_float32_frames_pass_too():
    depth, dx, dt, dam = _dam_frames(dtype=jnp.float32)
    assert dam_break_check(depth, dx, dt, 1.0, dam=dam).ok
    assert mass_check(depth, dx).ok


def test_virtual_pipes_fail_the_dam_break_for_want_of_momentum():
    n, h0 = 400, 1.0
    length = 2.6 * 2 * math.sqrt(G * h0)
    dx = length / n
    x = (np.arange(n) + 0.5) * dx
    dam = 0.35 * length
    bed = np.zeros((1, n))
    state = pipes_state(bed, depth=np.where(x < dam, h0, 0.0)[None], dtype=jnp.float64)
    frames, steps = [np.asarray(state.depth[0])], 40
    for _ in range(8):
        state = pipes_run(Pipes(dx), bed, state, steps, 1.0 / 8 / steps)
        frames.append(np.asarray(state.depth[0]))
    row = dam_break_check(np.array(frames), dx, 1.0 / 8, h0, dam=dam)
    assert not row.ok and "no momentum" in row.note, row
    assert mass_check(np.array(frames), dx).ok  # pipes conserve water: the fault is elsewhere


def test_a_wrong_gravity_is_told_apart_from_missing_momentum():
    depth, dx, dt, dam = _dam_frames(g=G / 2)  # the engine's g is half the real one
    row = dam_break_check(depth, dx, dt, 1.0, dam=dam)
    assert not row.ok and "check g" in row.note and "head too" in row.note, row
    assert row.measured / row.expected == pytest.approx(math.sqrt(0.5), rel=0.03)


def test_zeroing_thin_water_loses_mass_and_says_so():
    n, h0 = 200, 1.0
    dx = 10.0 / n
    x = (np.arange(n) + 0.5) * dx
    bed = np.zeros((1, n))
    solver = ShallowWater(dx)
    state = sw_state(bed, depth=np.where(x < 4.0, h0, 0.0)[None], dtype=jnp.float64)
    frames = [np.asarray(state.h[0])]
    for i in range(120):
        state = sw_step(solver, bed, state)
        thin = state.fields[0] < 5e-3  # an engine's "dry" cut-off applied to the depth itself
        state = type(state)(state.fields.at[0].set(jnp.where(thin, 0.0, state.fields[0])), state.time)
        if i % 15 == 14:
            frames.append(np.asarray(state.h[0]))
    row = mass_check(np.array(frames), dx)
    assert not row.ok and "water lost" in row.note, row


def _lxf_lake(bed, level, dx, steps):
    """A collocated Lax–Friedrichs scheme with the bed source by central differences (a textbook or engine
    first try): not well balanced."""
    h = np.maximum(level - bed, 0.0)
    q = np.zeros_like(h)
    dt = 0.4 * dx / math.sqrt(G * h.max())
    frames = [h.copy()]
    for k in range(steps):
        hp, qp = np.pad(h, 1, mode="edge"), np.pad(q, 1, mode="reflect") * np.r_[-1, np.ones(len(q)), -1]
        bp = np.pad(bed, 1, mode="edge")
        u = np.where(hp > 1e-8, qp / np.maximum(hp, 1e-8), 0.0)
        f1, f2 = qp, qp * u + 0.5 * G * hp * hp
        h = 0.5 * (hp[:-2] + hp[2:]) - dt / (2 * dx) * (f1[2:] - f1[:-2])
        q = (0.5 * (qp[:-2] + qp[2:]) - dt / (2 * dx) * (f2[2:] - f2[:-2])
             - dt * G * hp[1:-1] * (bp[2:] - bp[:-2]) / (2 * dx))
        h = np.maximum(h, 0.0)
        if k % 20 == 19:
            frames.append(h.copy())
    return np.array(frames)


@pytest.mark.parametrize("seed", [0, pytest.param(1, marks=pytest.mark.slow)])
def test_lake_at_rest_passes_a_well_balanced_solver_and_fails_lax_friedrichs(seed):
    rng = np.random.default_rng(seed)
    n = 128
    dx = 10.0 / n
    x = (np.arange(n) + 0.5) * dx
    bed = 0.3 * np.sin(2 * np.pi * x / rng.uniform(2, 5)) - 1.0 + 0.9 * np.exp(-((x - 5) / 0.6) ** 2)  # an island
    for dtype in (jnp.float64, jnp.float32):
        solver = ShallowWater(dx)
        state = sw_state(bed[None], 0.0, dtype=dtype)
        out = sw_frames(solver, bed[None], state, np.linspace(0.0, 3.0, 7))
        row = lake_at_rest_check(np.asarray(out.h), bed[None], dx)
        assert row.ok, row
    naive = _lxf_lake(bed, 0.0, dx, 200)
    row = lake_at_rest_check(naive, bed, dx)
    assert not row.ok and "well balanced" in row.note, row


def test_bad_records_are_refused_by_name():
    with pytest.raises(ValueError, match="depth"):
        mass_check(-np.ones((3, 4, 4)), 0.1)
    with pytest.raises(ValueError, match="at least 2 frames"):
        mass_check(np.ones((1, 4, 4)), 0.1)
    with pytest.raises(ValueError, match="bed must have"):
        lake_at_rest_check(np.ones((3, 4, 4)), np.zeros((3, 3)), 0.1)
    with pytest.raises(ValueError, match="not a lake at rest"):
        lake_at_rest_check(np.stack([np.linspace(1, 2, 16).reshape(4, 4)] * 3), np.zeros((4, 4)), 0.1)
    with pytest.raises(ValueError, match="hr must be below h0"):
        dam_break_check(np.ones((3, 8)), 0.1, 0.1, 1.0, dam=0.4, hr=2.0)
    with pytest.raises(ValueError, match="fewer than 3 frames"):
        dam_break_check(np.ones((3, 8)), 0.1, 0.1, 1.0, dam=0.4)


def test_check_record_and_the_command_run_the_shallow_water_rows(tmp_path, capsys):
    """Surface frames over a claimed bed: mass and the dam break run, the linear-wave checks are skipped; the
    command reads --bed and --dam and refuses a dam_break without them."""
    from wavephys.app.cli import main
    from wavephys.harness import Record, check_record

    depth, dx, dt, dam = _dam_frames(n=400, frames=9)
    depth = np.repeat(depth[:, None, :], 400, axis=1)  # the same dam across a square (records are square)
    bed = np.zeros(depth.shape[1:])
    record = Record.from_array(depth + bed, dx, dt, axes="tyx")
    report = check_record(record, bed=bed, dam=dict(x=dam, h0=1.0))
    assert set(report.rows) >= {"mass", "dam_break"} and report.rows["dam_break"].ok and report.rows["mass"].ok
    assert {"dispersion", "energy", "tiling"} <= set(report.skipped)
    np.save(tmp_path / "frames.npy", depth.astype(np.float32))
    np.save(tmp_path / "bed.npy", bed)
    argv = ["check", str(tmp_path / "frames.npy"), "--axes", "tyx", "--dx", str(dx), "--dt", str(dt),
            "--bed", str(tmp_path / "bed.npy"), "--dam", str(dam), "1.0", "--only", "mass", "dam_break"]
    assert main(argv) == 0
    assert "ok     dam_break" in capsys.readouterr().out
    with pytest.raises(ValueError, match="bed="):
        check_record(record, dam=dict(x=dam, h0=1.0))
    with pytest.raises(ValueError, match="dam must hold"):
        check_record(record, bed=bed, dam=dict(x=dam))
    with pytest.raises(SystemExit):
        main(["check", str(tmp_path / "frames.npy"), "--axes", "tyx", "--dx", str(dx), "--dt", str(dt),
              "--only", "dam_break"])  # the check needs --bed and --dam


def test_the_pytest_fixture_gives_the_verdict_and_the_cause(wavephys_check, tmp_path):
    """A user's suite: ``wavephys_check.record`` on frames saved to a file, with the bed and the dam claimed —
    our solver passes, the virtual pipes' frames fail naming missing momentum."""
    depth, dx, dt, dam = _dam_frames(n=400, frames=9)
    square = np.repeat(depth[:, None, :], 400, axis=1)
    bed = np.zeros(square.shape[1:])
    np.save(tmp_path / "solver.npy", square.astype(np.float32))
    wavephys_check.record(tmp_path / "solver.npy", dx=dx, dt=dt, axes="tyx", only=["dam_break", "mass"], bed=bed,
                          dam=dict(x=dam, h0=1.0))
    state = pipes_state(bed[:1], depth=depth[:1], dtype=jnp.float64)
    frames = [np.asarray(state.depth[0])]
    for _ in range(8):
        state = pipes_run(Pipes(dx), bed[:1], state, 40, dt / 40)
        frames.append(np.asarray(state.depth[0]))
    np.save(tmp_path / "pipes.npy", np.repeat(np.array(frames)[:, None, :], 400, axis=1).astype(np.float32))
    with pytest.raises(AssertionError, match="no momentum"):
        wavephys_check.record(tmp_path / "pipes.npy", dx=dx, dt=dt, axes="tyx", only=["dam_break"], bed=bed,
                              dam=dict(x=dam, h0=1.0))
