"""The harness on tanks: seiche frequencies and wall reflection, right verdicts with their causes, on
records written independently of the library's step (mode sums, an engine's finite-difference tank) and
on the library's own walled step."""

import math

import numpy as np
import pytest

from wavephys import Grid, Stones, Water
from wavephys.harness import Record, check_record
from wavephys.harness.tank import looks_like_tank, measure_seiches, seiche_check, wall_reflection_check


def _omega(k, water):
    h = water.depth
    return np.sqrt((water.g * k + water.sigma / water.rho * k ** 3) * (np.tanh(k * h) if math.isfinite(h) else 1.0))


def _mode_sum(nx, ny, dx, dt, nt, water, seed, *, omega=None, length_cut=0.0, gamma=0.0, modes=6):
    """A tank record written out from Lamb's modes: random (m, q), amplitudes and phases; ``omega(k)``
    replaces theory's frequencies (a broken simulator), ``length_cut`` shortens the tank the modes belong
    to (walls on the first and last samples: length_cut = dx), ``gamma`` damps every mode."""
    rng = np.random.default_rng(seed)
    lx, ly = nx * dx - length_cut, ny * dx - length_cut
    x = (np.arange(nx) + 0.5) * dx - 0.5 * length_cut
    y = (np.arange(ny) + 0.5) * dx - 0.5 * length_cut
    t = np.arange(nt)[:, None, None] * dt
    eta = np.zeros((nt, ny, nx))
    for _ in range(modes):
        m, q = rng.integers(0, 7, 2)
        if m == q == 0:
            m = 1
        k = math.pi * math.hypot(m / lx, q / ly)
        w = (omega or (lambda kk: _omega(kk, water)))(k)
        shape = np.cos(q * math.pi * y / ly)[:, None] * np.cos(m * math.pi * x / lx)[None, :]
        eta += rng.uniform(0.2, 1.0) * 1e-3 * shape * np.cos(w * t + rng.uniform(0, 2 * math.pi)) * np.exp(-gamma * t)
    return Record.from_array(eta, dx, dt, axes="tyx")


WATERS = [Water(sigma=0.0, depth=0.2), pytest.param(Water(depth=0.05), marks=pytest.mark.slow),
          pytest.param(Water(sigma=0.0), marks=pytest.mark.slow), pytest.param(Water(sigma=0.0, depth=1.5),
                                                                                marks=pytest.mark.slow)]


@pytest.mark.parametrize("water", WATERS, ids=["h0.2", "h0.05-sigma", "deep", "h1.5"])
def test_correct_tanks_pass_every_tank_check(water):
    """Mode sums of tanks (odd and even sizes, square and 2 x 1.25 m strips either way round) with theory's
    frequencies pass seiche, wall reflection and the energy on the tank's modes; dispersion and tiling are
    skipped."""
    for seed, (nx, ny) in enumerate([(48, 48), (64, 64), (33, 33), (48, 30), (30, 48)]):
        dx = 2.0 / nx
        w_max = _omega(math.pi * math.hypot(7 / 2.0, 7 / (ny * dx)), water)
        dt = min(0.04, 1.0 / w_max)
        rec = _mode_sum(nx, ny, dx, dt, 200, water, seed)
        report = check_record(rec, water, tank=True)
        assert report.ok, report.report()
        assert {"seiche", "wall_reflection", "energy"} <= set(report.rows)
        assert "dispersion" in report.skipped and "tiling" in report.skipped


def test_the_librarys_walled_step_passes_and_is_recognised_as_a_tank_without_the_claim():
    from wavephys.simulation import Model
    from wavephys.simulation.stepping import add_source, initial_state, run

    water = Water(sigma=0.0, depth=0.3)
    model = Model(Grid(64, 2.0), water, dt=0.02, walls="all")
    rng = np.random.default_rng(4)
    xy = rng.uniform(-0.7, 0.7, (2, 2))
    state = add_source(model, initial_state(model), Stones(xy[0], xy[1], [0.15, 0.2], [0.01, 0.01]))
    _, surf = run(model, state, 300)
    rec = Record.from_array(np.asarray(surf.eta), 2.0 / 64, 0.02, axes="tyx")
    report = check_record(rec, water, tank=True)
    assert report.ok, report.report()
    plain = check_record(rec, water)
    assert not plain.rows["dispersion"].ok
    assert "looks like a closed tank" in plain.rows["dispersion"].note and "--tank" in plain.rows["dispersion"].note


def test_an_engines_finite_difference_tank_with_mirrored_ghost_cells_passes():
    """How engines write a pool: the shallow-water wave equation η_tt = g h ∇²η by leapfrog on a grid with
    ghost cells mirrored at the walls (no flux half a cell outside the edges). In shallow water (kh ≤ 0.13)
    at a fine step it is a correct tank, and gets a correct verdict."""
    water = Water(sigma=0.0, depth=0.01)
    n, length = 64, 2.0
    dx = length / n
    c = math.sqrt(water.g * water.depth)
    dt_step = 0.2 * dx / c
    x = (np.arange(n) + 0.5) * dx
    eta = 1e-3 * np.exp(-((x[None, :] - 0.6) ** 2 + (x[:, None] - 1.3) ** 2) / (2 * 0.25 ** 2))
    prev = eta.copy()
    frames, every = [], 10
    for i in range(4000):
        p = np.pad(eta, 1, mode="edge")  # mirrored ghost cells: ∂η/∂n = 0 half a cell outside
        lap = (p[1:-1, 2:] + p[1:-1, :-2] + p[2:, 1:-1] + p[:-2, 1:-1] - 4 * eta) / dx ** 2
        eta, prev = 2 * eta - prev + (c * dt_step) ** 2 * lap, eta
        if i % every == 0:
            frames.append(eta.copy())
    rec = Record.from_array(np.array(frames), dx, every * dt_step, axes="tyx")
    rows = check_record(rec, water, tank=True, only=["seiche", "wall_reflection"]).rows
    assert rows["seiche"].ok and rows["wall_reflection"].ok, (rows["seiche"].report(), rows["wall_reflection"].report())


@pytest.mark.parametrize("seed, nx, ny", [(0, 48, 48), (3, 48, 30), pytest.param(1, 48, 48, marks=pytest.mark.slow),
                                          pytest.param(2, 30, 48, marks=pytest.mark.slow)])
def test_broken_tanks_fail_with_their_cause(seed, nx, ny):
    """Square tanks and 2 x 1.25 m strips."""
    water = Water(sigma=0.0, depth=0.3)
    dx, dt = 2.0 / nx, 0.03
    cases = {
        "non-dispersive": (dict(omega=lambda k: k * math.sqrt(water.g * water.depth)), "h = 0.3 m, the claimed"),
        "periodic": (dict(omega=lambda k: _omega(2 * k, water)), "wrap around"),
        "vertex": (dict(length_cut=dx), "first and last samples"),
        "factor": (dict(omega=lambda k: 1.04 * _omega(k, water)), "same factor"),
        "slower wave equation": (dict(omega=lambda k: 1.2 * k), "one speed c = 1.2 m/s"),
        "shallower water": (dict(omega=lambda k: _omega(k, Water(sigma=0.0, depth=0.15))), "water 0.15 m deep"),
    }
    for name, (kw, cause) in cases.items():
        rec = _mode_sum(nx, ny, dx, dt, 240, water, seed, **kw)
        row = seiche_check(rec, water)
        assert not row.ok, name
        assert cause in row.note, (name, row.note)
    damped = _mode_sum(nx, ny, dx, dt, 240, water, seed, gamma=0.15)
    row = wall_reflection_check(damped, water)
    assert not row.ok and "absorb" in row.note and row.measured < 0.99


def test_a_periodic_simulation_is_not_a_tank():
    from wavephys.simulation import Model
    from wavephys.simulation.stepping import add_source, initial_state, run

    water = Water(sigma=0.0, depth=0.3)
    model = Model(Grid(64, 2.0), water, dt=0.02)
    state = add_source(model, initial_state(model), Stones([0.3, -0.5], [0.2, 0.6], [0.15, 0.2], [0.01, 0.01]))
    _, surf = run(model, state, 300)
    rec = Record.from_array(np.asarray(surf.eta), 2.0 / 64, 0.02, axes="tyx")
    row = seiche_check(rec, water)
    assert not row.ok and "not a sum of a tank's standing modes" in row.note
    assert looks_like_tank(rec, water) == ""
    assert check_record(rec, water).ok  # and as what it is, it passes


def test_the_seiche_fit_measures_frequency_and_decay():
    water = Water(sigma=0.0, depth=0.4)
    rec = _mode_sum(40, 40, 0.05, 0.03, 300, water, 9, gamma=0.02, modes=1)
    s = measure_seiches(rec.eta, rec.dx, rec.dt, 1)
    assert s.omega[0] == pytest.approx(_omega(s.k[0], water), rel=1e-6)
    assert s.gamma[0] == pytest.approx(0.02, rel=1e-4)


def test_tank_checks_refuse_bad_input_by_name():
    water = Water()
    with pytest.raises(ValueError, match="eta must be frames"):
        measure_seiches(np.zeros((4, 8, 8)), 0.1, 0.1)
    with pytest.raises(ValueError, match="dx"):
        measure_seiches(np.zeros((10, 8, 8)), -1.0, 0.1)
    rec = _mode_sum(16, 16, 0.1, 0.05, 20, Water(sigma=0.0, depth=0.2), 0)
    with pytest.raises(ValueError, match="assumes a periodic domain"):
        check_record(rec, water, tank=True, only=["dispersion"])
    with pytest.raises(TypeError, match="tank"):
        check_record(rec, water, tank="yes")


def test_a_shallow_water_tank_takes_its_depth_from_a_flat_bed_and_leaves_an_uneven_one_out():
    """Frames of the surface's elevation over a claimed bed (how shallow-water tanks export): over a flat bed the
    seiche theory's depth is the water's over it (here 5 cm, no depth claimed); over an uneven bed the flat
    floor's modes are not the tank's, and the seiche and wall rows say so instead of failing a correct simulator;
    a still lake gets no wave rows at all, and its quantization row (nothing varies) is ok. The simulator: the
    linear shallow-water depth stepper (energy-conserving) in a 2 x 1.25 m tank, its first mode (kh 0.08)."""
    import jax

    from wavephys import Grid
    from wavephys.core.spectral import _tank_block
    from wavephys.simulation import Model
    from wavephys.simulation.depth import Floor, depth_state
    from wavephys.steppers import DepthStepper

    dx, lx, ly, h = 0.0625, 2.0, 1.25, 0.05
    with jax.enable_x64(True):
        model = Model(Grid(32, lx), Water(sigma=0.0, depth=h), dt=0.08, walls="all", tank=(lx, ly), dtype="float64")
        x = np.asarray(model.grid.mesh()[0])
        run = DepthStepper(model, Floor(np.full((32, 32), h)), "shallow").run(
            depth_state(model, 2e-3 * np.cos(math.pi * (x + lx / 2) / lx)), until=20.0, every=0.08)
    rows, cols = _tank_block(32, model.tank_cells)
    frames, bed = run.frames[:, rows, cols], -h * np.ones((rows.stop - rows.start, cols.stop - cols.start))
    report = check_record(Record(frames, dx, 0.08), Water(sigma=0.0), tank=True, bed=bed)
    assert report.ok and {"seiche", "wall_reflection", "mass"} <= set(report.rows), report.report()
    tilted = bed + 0.01 * (np.arange(bed.shape[1]) / bed.shape[1] - 0.5)[None, :]
    report = check_record(Record(frames, dx, 0.08), Water(sigma=0.0), tank=True, bed=tilted)
    assert "flat floor's" in report.skipped["seiche"] and "flat floor's" in report.skipped["wall_reflection"]
    still = check_record(Record(np.zeros((16,) + bed.shape), dx, 0.08), Water(sigma=0.0), tank=True, bed=bed,
                         at_rest=True)
    assert still.ok and set(still.rows) == {"mass", "lake_at_rest"}, still.report()
    assert check_record(Record(np.zeros((16, 8, 8)), dx, 0.08), only=["quantization"]).ok
