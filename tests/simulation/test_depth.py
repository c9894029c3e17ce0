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
from wavephys.simulation.depth import DEPTH_METHODS, Floor, depth_state, run_depth, step_levels, step_shallow
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
        state, _ = run_depth(model, Floor(np.full((64, 64), depth)), depth_state(model, eta), 50, "levels")
        want = np.asarray(surface(model, today).eta)
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
    state, _ = run_depth(model, Floor(h), state, int(travel / model.dt), method)
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
        run_depth(model, Floor(np.ones((16, 16))), state, 2, "mild")
    assert set(DEPTH_METHODS) == {"levels", "shallow"}
