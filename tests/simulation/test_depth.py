"""Waves over a varying floor (docs/physics.md §1.12): the two steppers against theory — today's step
on a constant floor, Green's law, Snell's law, Lamb's standing wave on a beach — and the measured
failures of the spectral depth levels (their blend loses amplitude where the floor is between levels)."""

import math

import jax
import numpy as np
import pytest
from scipy.signal import hilbert

from wavephys import Grid, Water
from wavephys.checks.depth import lamb_beach_error, measure_shoaling, travelling_packet
from wavephys.physics.depth import (depth_levels, depth_weights, lamb_beach, mild_slope_transmission,
                                    refraction_angle, shoaling_coefficient)
from wavephys.physics.dispersion import angular_frequency, group_speed, wavenumber
from wavephys.simulation import Model
from wavephys.simulation.depth import (DEPTH_METHODS, Floor, ProfileState, ProfileStepper, depth_state, step_levels,
                                       step_shallow, step_symmetric, symmetric_levels)
from wavephys.steppers import DepthStepper
from wavephys.simulation.stepping import add_height, initial_state, run, surface

G = 9.81


@pytest.fixture(autouse=True)
def x64():
    with jax.enable_x64(True):
        yield


def test_a_constant_floor_at_one_level_is_todays_step():
    rng = np.random.default_rng(1)
    for depth in (0.2, 1.0, 5.0):
        model = Model(Grid(64, 4.0), Water(sigma=0.0, depth=depth), dt=0.03, dtype="float64")
        eta = 1e-3 * np.asarray(Grid(16, 4.0).refine(rng.standard_normal((16, 16)), 4))
        eta = eta - eta.mean()  # the spectral state holds no mean height (a still level)
        today, _ = run(model, add_height(model, initial_state(model), eta), 50)
        want = np.asarray(surface(model, today).eta)
        for method in ("levels", "symmetric"):
            state = DepthStepper(model, Floor(np.full((64, 64), depth)), method).advance(depth_state(model, eta), 50)
            assert np.abs(np.asarray(state.eta) - want).max() <= 1e-11 * np.abs(want).max()


def test_depth_weights_interpolate_and_sum_to_one():
    h = np.random.default_rng(0).uniform(0.1, 3.0, (8, 8))
    levels = depth_levels(h, 4)
    w = np.asarray(depth_weights(h, levels))
    assert np.allclose(w.sum(0), 1.0) and w.min() >= 0
    assert np.allclose(np.tensordot(levels, w, 1), h)  # linear in h: the weights reproduce h


def _packet_run(method, h0, h1, k0, per, ramp=10.0, sigma=2.0):
    return measure_shoaling(method, h0, h1, k0, per, ramp, sigma)


@pytest.mark.slow
def test_shallow_water_shoals_by_greens_law_converging_as_dx_squared():
    """Linear shallow water up a gentle ramp (10 wavelengths, 1 m → 0.25 m, kh ≤ 0.1): the amplitude on the
    plateau against Green's law (h₀/h₁)^(1/4) = √2. Measured 2.7 % high at 16 samples per wavelength, 0.7 % at
    32 (the grid's group-speed error, ∝ dx²): the two resolutions here, extrapolated, are within 1 %."""
    a12, _ = _packet_run("shallow", 1.0, 0.25, 0.1, 12)
    a16, _ = _packet_run("shallow", 1.0, 0.25, 0.1, 16)
    green = (1.0 / 0.25) ** 0.25
    e12, e16 = a12 / green - 1, a16 / green - 1
    assert 0 < e16 < e12  # converging from above
    assert e16 == pytest.approx(e12 * (12 / 16) ** 2, rel=0.25)  # second order
    extrapolated = a16 + (a16 - a12) * 12 ** 2 / (16 ** 2 - 12 ** 2)
    assert extrapolated == pytest.approx(green, rel=0.01)


def test_shallow_water_holds_lambs_standing_wave_on_a_plane_beach():
    """η = A J₀(2ω√(x/(g tan β))) on h = x tan β, the shoreline a wall of zero depth at x = 0 and a wall at
    x = X where dη/dx = 0 (ω from a zero of J₁): an exact mode of the linear shallow-water equations, kept
    for three periods; the error falls as dx² (n = 64 → 128)."""
    errors = [lamb_beach_error(n) for n in (64, 128)]
    assert errors[1] < 0.012
    assert errors[1] < errors[0] / 3


@pytest.mark.parametrize("method", [pytest.param("levels", marks=pytest.mark.slow), "shallow"])
def test_refraction_over_straight_contours_follows_snells_law(method):
    """An oblique packet from 2 m onto a 0.5 m plateau (contours along y): ky is kept, and |k| on the plateau is
    the one the local dispersion gives at the wave's frequency (each method's own: full for levels, √(gh) for
    shallow water, whose grid adds its (k dx)²/24), so sin θ/c is constant. k measured from the phase gradient
    of the analytic signal (weighted by |η|², no envelope bias)."""
    n, length = 384, 96.0
    grid = Grid(n, length)
    dx = float(grid.dx)
    x, y = (np.asarray(a) for a in grid.mesh())
    h0, h1 = 2.0, 0.5
    ky = 2 * math.pi * 6 / length
    k0 = 1.0
    kx = math.sqrt(k0 ** 2 - ky ** 2)
    h = np.clip(h0 + (h1 - h0) * (x + 10.0) / 6.0, h1, h0)
    water0, water1 = Water(sigma=0.0, depth=h0), Water(sigma=0.0, depth=h1)
    if method == "levels":
        omega = float(angular_frequency(k0, water0))
        k1 = float(wavenumber(omega, water1))
        cg0, cg1 = float(group_speed(k0, water0)), float(group_speed(k1, water1))
    else:
        omega = k0 * math.sqrt(G * h0)
        k1 = 2 / dx * math.asin(omega / math.sqrt(G * h1) * dx / 2)  # the grid's own: sin(k dx/2) = ω dx/(2c)
        cg0, cg1 = math.sqrt(G * h0), math.sqrt(G * h1)
    model = Model(grid, water0, dt=2 * math.pi / omega / 16, dtype="float64")
    env = np.exp(-(x + 28.0) ** 2 / (2 * 5.0 ** 2))  # narrow-band: 1/σ = 0.2 k₀
    phase = kx * x + ky * y
    state = depth_state(model, *travelling_packet(grid, 1e-3 * env * np.exp(1j * phase), method, h0))
    travel = 18.0 / cg0 + 6.0 / (0.5 * (cg0 + cg1)) + 18.0 / cg1  # centre from −28 to +14 m
    state = DepthStepper(model, Floor(h), method).advance(state, int(travel / model.dt))
    eta = np.asarray(state.eta) * (x > -2.0)
    a = hilbert(eta, axis=1)
    weight = np.abs(a) ** 2
    kx_local = np.angle(np.conj(a[:, :-1]) * a[:, 1:]) / dx
    ky_local = np.angle(np.conj(a[:-1]) * a[1:]) / dx
    kx_m = np.sum(weight[:, :-1] * kx_local) / np.sum(weight[:, :-1])
    ky_m = np.sum(weight[:-1] * ky_local) / np.sum(weight[:-1])
    assert ky_m == pytest.approx(ky, rel=0.01)
    assert math.hypot(kx_m, ky_m) == pytest.approx(k1, rel=0.01)
    if method == "levels":  # Snell in its published form
        assert math.atan2(ky_m, kx_m) == pytest.approx(refraction_angle(math.asin(ky / k0), omega, h0, h1), abs=0.01)


@pytest.mark.slow
def test_levels_fail_greens_law_and_lambs_beach_measured():
    """What the levels neglect, measured: up the gentle ramp at kh = 0.3 their amplitude is 0.745 of the
    incident (theory: 1.391, ratio 0.54); so beaches go to the shallow-water method (and levels refuse dry land)."""
    a, omega = _packet_run("levels", 1.0, 0.25, 0.3, 6)
    assert a / shoaling_coefficient(omega, 1.0, 0.25) < 0.7
    model = Model(Grid(32, 4.0), Water(sigma=0.0), dt=0.05)
    with pytest.raises(ValueError, match="dry land"):
        step_levels(model, Floor(np.zeros((32, 32))), depth_state(model, np.zeros((32, 32))))


def test_the_mild_slope_reference_conserves_energy_flux_and_is_the_shoaling_law_on_gentle_slopes():
    water = Water(sigma=0.0)
    for kh0 in (0.1, 0.5, 2.0):
        omega = float(angular_frequency(kh0, Water(sigma=0.0, depth=1.0)))
        lam = 2 * math.pi / kh0
        cg0 = float(group_speed(kh0, Water(sigma=0.0, depth=1.0)))
        k1 = float(wavenumber(omega, Water(sigma=0.0, depth=0.25)))
        cg1 = float(group_speed(k1, Water(sigma=0.0, depth=0.25)))
        for ramp in (0.2, 1.0, 20.0):
            t, r = mild_slope_transmission(omega, [0.0, ramp * lam], [1.0, 0.25], water)
            assert r * r + t * t * cg1 / cg0 == pytest.approx(1.0, abs=1e-7)
        assert t == pytest.approx(shoaling_coefficient(omega, 1.0, 0.25), rel=1e-3)  # 20 wavelengths: WKB


@pytest.mark.parametrize("method", ["levels", "shallow", "symmetric"])
def test_the_one_step_functions_are_the_depth_steppers_one_step_at_a_time(method):
    """step_levels/step_shallow/step_symmetric called by hand agree with DepthStepper (the same program)."""
    model = Model(Grid(16, 2.0), Water(sigma=0.0), dt=0.02, dtype="float64")
    x = (np.arange(16) + 0.5) / 16
    depth = np.tile(0.1 + 0.4 * x, (16, 1))  # a slope, wet everywhere (the levels method needs it)
    floor = Floor(depth)
    eta = 1e-3 * np.exp(-((x - 0.5) ** 2)[None, :] / 0.02 - ((x - 0.5) ** 2)[:, None] / 0.02)
    step = {"levels": step_levels, "shallow": step_shallow, "symmetric": step_symmetric}[method]
    by_hand = depth_state(model, eta)
    for _ in range(3):
        by_hand, _ = step(model, floor, by_hand)
    together = DepthStepper(model, floor, method).advance(depth_state(model, eta), 3)
    assert float(np.abs(np.asarray(by_hand.fields) - np.asarray(together.fields)).max()) < 1e-15
    assert float(np.abs(np.asarray(together.fields)[0] - eta).max()) > 1e-6  # it moved


def test_depth_steppers_refuse_bad_input_by_name():
    model = Model(Grid(16, 1.0), Water(), dt=0.05)
    state = depth_state(model, np.zeros((16, 16)))
    with pytest.raises(ValueError, match="floor depth must have the grid's shape"):
        step_shallow(model, Floor(np.ones((8, 8))), state)
    with pytest.raises(ValueError, match="depth"):
        Floor(-np.ones((16, 16)))
    with pytest.raises(TypeError, match="floor"):
        step_shallow(model, np.ones((16, 16)), state)
    with pytest.raises(ValueError, match="method"):
        DepthStepper(model, Floor(np.ones((16, 16))), "mild")
    assert set(DEPTH_METHODS) == {"levels", "shallow", "symmetric"}
    with pytest.raises(ValueError, match="dry everywhere"):
        step_symmetric(model, Floor(np.zeros((16, 16))), state)
    with pytest.raises(ValueError, match="phi"):
        ProfileState(np.zeros(16), np.zeros(8))
    with pytest.raises(ValueError, match="profile's 16 samples"):
        ProfileStepper(np.ones(16), 0.1, Water(), 0.05).advance(ProfileState(np.zeros(8), np.zeros(8)), 3)
    with pytest.raises(ValueError, match="dx"):
        ProfileStepper(np.ones(16), -0.1, Water(), 0.05)
    with pytest.raises(ValueError, match="depth"):
        ProfileStepper(-np.ones(16), 0.1, Water(), 0.05)
    with pytest.raises(ValueError, match="levels method needs depth > 0"):
        ProfileStepper(np.zeros(16), 0.1, Water(), 0.05, "levels")
    with pytest.raises(ValueError, match="dt: ProfileStepper steps its own dt"):
        ProfileStepper(np.ones(16), 0.1, Water(), 0.05).step(ProfileState(np.zeros(16), np.zeros(16)), dt=0.1)


# -- the symmetric blend: shoals right at every kh ---------------------------------------------------------
def _shoaling_error(method, kh0, ratio, ramp, levels=4, per=16):
    """Amplitude over the far plateau against the mild-slope reference, a σ = 6 packet (its own spreading 0.2 %)."""
    a, _ = measure_shoaling(method, 1.0, ratio, kh0, per, ramp, 6.0, levels)
    omega = float(angular_frequency(kh0, Water(sigma=0.0, depth=1.0)))
    reference, _ = mild_slope_transmission(omega, [0.0, ramp * 2 * math.pi / kh0], [1.0, ratio])
    return a / reference - 1


def _family(seed, count):
    """Generated cases: kh₀ log-uniform in [0.1, 3], the far depth 0.2–0.5 m (shoaling) or 1.5–3 m (deshoaling)."""
    rng = np.random.default_rng(seed)
    kh = np.exp(rng.uniform(np.log(0.1), np.log(3.0), count))
    ratio = np.where(rng.random(count) < 0.5, rng.uniform(0.2, 0.5, count), rng.uniform(1.5, 3.0, count))
    return list(zip(kh.round(4), ratio.round(3)))


@pytest.mark.parametrize("kh0, ratio", _family(7, 3) + [pytest.param(*c, marks=pytest.mark.slow) for c in _family(8, 6)])
def test_symmetric_shoals_by_energy_flux_at_every_kh(kh0, ratio):
    """Up (or down) a 10-wavelength ramp, the symmetric blend's amplitude is the mild-slope reference's within 1 %
    (measured ≤ 0.11 % for 1 → 0.25 m at kh₀ 0.1–3), where the levels blend (its outputs weighted, not
    symmetric) is 28–48 % off at kh₀ ≤ 1 and 8.6 % at 3, and shallow water 20–57 % at kh₀ ≥ 1."""
    assert abs(_shoaling_error("symmetric", kh0, ratio, 10.0)) < 0.01


@pytest.mark.slow
def test_symmetric_blend_fails_on_ramps_shorter_than_its_levels_measured():
    """The failure boundary: its weights' square roots turn sharply where a level's weight goes to 0, a potential
    the waves feel where the floor crosses the levels within about a wavelength. Measured (1 → 0.25 m): 4 levels
    over a 1-wavelength ramp −4.7 / −5.4 / −7.1 % at kh₀ 0.1 / 1 / 3; 2 levels over it within 0.3 %."""
    errors = [_shoaling_error("symmetric", kh, 0.25, 1.0) for kh in (0.1, 1.0, 3.0)]
    assert max(errors) < -0.03
    assert max(abs(_shoaling_error("symmetric", kh, 0.25, 1.0, levels=2)) for kh in (0.1, 1.0, 3.0)) < 0.005


def test_levels_and_shallow_water_fail_where_the_symmetric_blend_holds():
    """The same gentle ramp, the same packet: the levels lose the energy flux (−28 % at kh₀ = 1), shallow water
    has the wrong group speed (+20 %)."""
    assert _shoaling_error("levels", 1.0, 0.25, 10.0, per=8) < -0.2
    assert _shoaling_error("shallow", 1.0, 0.25, 10.0) > 0.15


def test_symmetric_step_conserves_energy_with_walls_and_dry_land():
    """A walled tank, a random floor with a dry island, random waves: leapfrog's invariant of a linear system,
    E − (δ²/8)·g²⟨η, Ĝη⟩ with E = ½Σ(gη² + φ·Ĝφ) (Ĝ the blended operator, η̇ = Ĝφ), is kept to 1e-10 over 300
    steps — energy is conserved, no drift — and nothing moves on the dry cells. (At n = 64 over 8 m the grid's
    highest frequency is 18.6 rad/s, so Δt = 0.05 s is one sub-step, δ = Δt.)"""
    n = 64
    grid = Grid(n, 8.0)
    x, y = (np.asarray(a) for a in grid.mesh())
    rng = np.random.default_rng(3)
    bumps = np.asarray(Grid(8, 8.0).refine(rng.standard_normal((8, 8)), 8))
    depth = np.clip(0.6 + 0.25 * bumps - 0.9 * np.exp(-(x ** 2 + y ** 2) / 2.0), 0.0, None)
    assert (depth == 0).sum() > 20 and depth.max() > 0.5
    eta = 1e-3 * np.asarray(Grid(16, 8.0).refine(rng.standard_normal((16, 16)), 4)) * (depth > 0)
    model = Model(grid, Water(sigma=0.0), dt=0.05, walls="all", dtype="float64")
    floor = Floor(depth)
    state = depth_state(model, eta)

    def apply(s, phi):  # Ĝφ: the rate η̇ the step reports
        return np.asarray(step_symmetric(model, floor, depth_state(model, s.eta, phi))[1][1])

    def energy(s, modified=True):
        eta, phi = np.asarray(s.eta), np.asarray(s.phi)
        e = 0.5 * np.sum(G * eta ** 2 + phi * apply(s, phi))
        return float(e - modified * model.dt ** 2 / 8 * G ** 2 * np.sum(eta * apply(s, eta)))

    e0 = energy(state)
    stepper = DepthStepper(model, floor, "symmetric")
    end, states = stepper.trajectory(state, 300)
    record = stepper.surfaces(states)
    assert abs(energy(end) / e0 - 1) < 1e-10
    assert abs(energy(end, False) / energy(state, False) - 1) > 1e-4  # the plain energy oscillates: the test can tell
    assert np.abs(np.asarray(end.eta)[depth == 0]).max() == 0.0
    assert np.abs(np.asarray(record[:, 1])).max() > 1e-3  # the waves moved


def test_symmetric_levels_add_a_dry_level_only_for_dry_land():
    assert np.allclose(symmetric_levels(np.array([[0.25, 1.0]]), 3), [0.25, 0.5, 1.0])
    assert np.allclose(symmetric_levels(np.array([[0.0, 0.25, 1.0]]), 3), [0.0, 0.25, 0.5, 1.0])


def test_symmetric_leapfrog_has_no_phase_error_at_a_level():
    """The symmetric stepper's leapfrog uses K̃ = 4 sin²(ωδ/2)/(Rδ²) at each level, so a mode at a
    level's depth turns at exactly ω. Water 0.5 m deep with a dry 4 × 4-cell corner (levels 0 and
    0.5 m: the leapfrog path, every wet cell at a level) steps a packet 10 times at ω_max·δ = 0.9 (one
    sub-step): it matches the spectral step to 1.9e-4 of its peak away from the corner (measured,
    with and without surface tension); with plain K (leapfrog's own frequency 2 arcsin(ωδ/2)/δ) it
    was 1.1e-2 (measured before the change)."""
    for water in (Water(sigma=0.0, depth=0.5), Water(depth=0.5)):
        grid = Grid(64, 3.2)
        x = np.asarray(grid.coordinates)
        eta = 1e-3 * np.exp(-(x[None, :] ** 2 + x[:, None] ** 2) / (2 * 0.1**2))
        eta = eta - eta.mean()
        dt = 0.9 / float(angular_frequency(math.pi / float(grid.dx), water))
        model = Model(grid, water, dt=dt, dtype="float64")
        depth = np.full((64, 64), 0.5)
        depth[:4, :4] = 0.0
        assert list(symmetric_levels(depth)) == [0.0, 0.5]
        state = DepthStepper(model, Floor(depth), "symmetric").advance(depth_state(model, eta), 10)
        today, _ = run(model, add_height(model, initial_state(model), eta), 10)
        want = np.asarray(surface(model, today).eta)
        inner = (slice(16, 48), slice(16, 48))
        assert np.abs(np.asarray(state.eta)[inner] - want[inner]).max() <= 1e-3 * np.abs(want).max()


def test_a_profile_between_walls_rings_at_its_modes_and_sloshes_over_a_slope_at_second_order():
    """ProfileStepper(ends="walls"): a wall half a sample past each end. Flat floors (0.1 and 1 m, modes 1, 3, 8 of
    a 4 m tank): the levels and symmetric methods return each cosine mode after one period to 1e-13. Over a
    floor sloping 3 → 7 cm in 2 m, against the exact long-wave sloshing mode (tests/simulation/test_steppers.py):
    shallow after one period within 6.4e-5 / 1.0e-5 / 1.8e-6 of the amplitude at 32 / 64 / 128 cells (second
    order), levels 2.5e-3 (its blend), and the symmetric blend 0.57 / 0.64 / 0.71, worse as the grid refines
    (its √w gradient, docs/physics.md §1.12), its measured failure. Water is kept to rounding between walls."""
    from test_steppers import LX as length, _sloshing_reference, _slope

    water = Water(sigma=0.0)
    n, side = 64, 4.0
    x = (np.arange(n) + 0.5) * side / n
    for depth in (0.1, 1.0):
        for m in (1, 3, 8):
            k = m * math.pi / side
            period = 2 * math.pi / math.sqrt(G * k * math.tanh(k * depth))
            eta = 1e-3 * np.cos(k * x)
            for method in ("levels", "symmetric"):
                stepper = ProfileStepper(np.full(n, depth), side / n, water, period / 40, method, ends="walls")
                end = stepper.advance(ProfileState(eta, np.zeros(n)), 40).eta
                assert np.abs(np.asarray(end) - eta).max() < 1e-13, (depth, m, method)
    w_ref, xs, shape = _sloshing_reference()
    errors = {}
    for cells in (32, 64, 128):
        dx = length / cells
        x = (np.arange(cells) + 0.5) * dx
        eta = 1e-3 * np.interp(x, xs, shape)
        for method in ("shallow", "levels", "symmetric") if cells == 64 else ("shallow",):
            stepper = ProfileStepper(_slope(x), dx, water, 2 * math.pi / w_ref / 40, method, ends="walls")
            end = stepper.advance(ProfileState(eta, np.zeros(cells)), 40).eta
            errors[cells, method] = np.abs(np.asarray(end) - eta).max() / 1e-3
            if method == "shallow":
                assert abs(float(np.sum(end) - eta.sum()) * dx) < 1e-15
    assert errors[32, "shallow"] < 1e-4 and errors[128, "shallow"] < errors[32, "shallow"] / 16, errors
    assert errors[64, "levels"] < 4e-3 and errors[64, "symmetric"] > 0.3, errors
    with pytest.raises(ValueError, match="ends"):
        ProfileStepper(np.ones(8), 0.1, water, 0.01, ends="open")
