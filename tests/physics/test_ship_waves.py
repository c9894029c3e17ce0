import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from wavephys import Grid, Water
from wavephys.physics.dispersion import angular_frequency
from wavephys.physics.ship_waves import (Hull, Ship, max_patch_dt, patch_leak, resonance_quotients, resonance_quotients_exact, ship_multipliers,
                                 ship_multipliers_naive, ship_patch_waves, straight_path, turning_path)

GRID = Grid(128, 8.0)
DEEP = Water(sigma=0.0)


def test_ship_at_rest_adds_nothing(x64):
    m1, m2 = ship_multipliers(GRID, Water(), (0.0, 0.0), 0.1)
    assert float(jnp.max(jnp.abs(m1 + m2))) < 1e-12


def test_straight_motion_is_the_duhamel_integral(x64):
    v, dt = (1.2, 0.3), 0.1
    m1, m2 = ship_multipliers(GRID, DEEP, v, dt)
    ky, kx = GRID.wavenumbers()
    kv = kx * v[0] + ky * v[1]
    w = angular_frequency(GRID.wavenumber_magnitude(), DEEP)
    a = (kv - w) * dt
    safe = jnp.where(a == 0, 1.0, a)
    rhs = jnp.exp(-1j * w * dt) * jnp.where(a == 0, -1j * kv * dt, (jnp.exp(-1j * a) - 1) * kv * dt / safe)
    lhs = m1 + m2 * jnp.exp(-1j * kv * dt)
    assert float(jnp.max(jnp.abs(lhs - rhs))) < 1e-12


def test_one_step_equals_two_half_steps(x64):
    """W(Δt) = P(Δt/2)·W₁(Δt/2) + W₂(Δt/2) for the hull spectrum moving straight."""
    v, dt = np.array([0.9, -0.2]), 0.2
    ky, kx = GRID.wavenumbers()
    f0 = jnp.exp(-0.5 * GRID.wavenumber_magnitude() ** 2 * 0.3**2)  # a Gaussian hull at the origin
    shift = lambda t: jnp.exp(-1j * (kx * v[0] + ky * v[1]) * t)
    m1, m2 = ship_multipliers(GRID, DEEP, v, dt)
    one = f0 * m1 + f0 * shift(dt) * m2
    h1, h2 = ship_multipliers(GRID, DEEP, v, dt / 2)
    prop = jnp.exp(-1j * angular_frequency(GRID.wavenumber_magnitude(), DEEP) * dt / 2)
    two = prop * (f0 * h1 + f0 * shift(dt / 2) * h2) + (f0 * shift(dt / 2) * h1 + f0 * shift(dt) * h2)
    assert float(jnp.max(jnp.abs(one - two))) < 1e-12 * float(jnp.max(jnp.abs(one)))


def test_stable_quotients_float32_near_resonance():
    alpha = np.concatenate([np.geomspace(1e-6, 2.0, 60), -np.geomspace(1e-6, 2.0, 60)])
    q1, q2 = resonance_quotients(jnp.asarray(alpha, jnp.float32))
    r1, r2 = resonance_quotients_exact(alpha)
    assert np.max(np.abs(np.asarray(q1) - r1) / np.abs(r1)) < 1e-6
    assert np.max(np.abs(np.asarray(q2) - r2) / np.abs(r2)) < 1e-6


def test_naive_quotients_fail_in_float32():
    """Documented failure: evaluated as written, the quotients lose all digits near α = 0."""
    v, dt = (1.0, 0.0), 0.05
    m1, m2 = ship_multipliers(GRID, DEEP, v, dt)
    n1, n2 = ship_multipliers_naive(GRID, DEEP, v, dt)
    with jax.enable_x64(True):
        r1, r2 = ship_multipliers(GRID, DEEP, v, dt)
    ref = np.abs(np.asarray(r1)).max()
    assert np.max(np.abs(np.asarray(m1) - np.asarray(r1))) < 1e-5 * ref
    assert np.isnan(np.asarray(n1)[0, 0])  # α = 0 exactly at k = 0: 0/0
    err = np.abs(np.asarray(n1) - np.asarray(r1))
    err[0, 0] = 0.0
    assert err.max() > 1e-2 * ref


def test_hulls():
    u, v = jnp.meshgrid(jnp.linspace(-1, 1, 41), jnp.linspace(-1, 1, 41))
    ell = Hull("ellipse", 1.0, 0.4).evaluate(u, v)
    assert float(ell.sum()) * (2 / 40) ** 2 == pytest.approx(math.pi * 0.5 * 0.2, rel=0.1)
    mask = np.zeros((4, 8))
    mask[1:3, 2:6] = 1.0
    assert float(Hull("mask", 1.0, 0.4, mask=mask).evaluate(jnp.array(0.0), jnp.array(0.0))) == 1.0
    with pytest.raises(ValueError, match="mask"):
        Hull("mask", 1.0, 0.4)
    with pytest.raises(ValueError, match="length"):
        Hull("ellipse", -1.0, 0.4)


def test_paths():
    p = straight_path((0.0, 1.0), (2.0, 0.0))
    assert p(1.5) == (3.0, 1.0, 0.0)
    c = turning_path((0.0, 0.0), 2.0, 1.0)
    x, y, heading = c(math.pi)
    assert math.hypot(x, y) == pytest.approx(2.0) and heading == pytest.approx(math.pi / 2 + math.pi / 2)
    with pytest.raises(ValueError, match="radius"):
        turning_path((0.0, 0.0), 0.0, 1.0)


def test_patch_waves_and_leak_grows_with_dt():
    ship = Ship(Hull("gaussian", 0.6, 0.3, blur=0.05), straight_path((0.0, 0.0), (1.0, 0.0)), 0.01)
    grid = Grid(256, 16.0)
    waves, (r0, c0) = ship_patch_waves(ship, grid, DEEP, 0.0, 0.05, 32)
    assert waves.shape == (64, 64) and r0 == 128 - 32 and float(jnp.abs(waves).max()) > 0
    leaks = [patch_leak(ship, grid, DEEP, 0.0, dt, 16) for dt in (0.02, 0.5, 2.0)]
    assert leaks[0] < leaks[1] < leaks[2]
    assert leaks[0] < 1e-3 < leaks[2]
    dt_max = max_patch_dt(ship, grid, DEEP, 16)
    assert patch_leak(ship, grid, DEEP, 0.0, 0.9 * dt_max, 16) <= 1e-3 < patch_leak(ship, grid, DEEP, 0.0, 1.1 * dt_max, 16)


def test_patch_leak_on_grids_smaller_than_twice_the_patch():
    """The leak's reference patch is twice as large, or the whole grid where that does not
    fit (it used to raise for any grid under 4× the patch half-size, e.g. n = 96 with the
    default 64-point patch); a patch that is the whole periodic grid misses nothing."""
    ship = Ship(Hull("gaussian", 0.6, 0.3, blur=0.05), straight_path((0.0, 0.0), (1.0, 0.0)), 0.01)
    grid = Grid(96, 6.0)
    leaks = [patch_leak(ship, grid, Water(), 0.0, 0.05, half) for half in (16, 32, 48)]
    assert 0.0 < leaks[1] < leaks[0] < 1e-3  # 32 → the whole grid (48) as reference, no error
    assert leaks[2] == 0.0


def test_patch_guards():
    ship = Ship(Hull("ellipse", 0.6, 0.3), straight_path((0.0, 0.0), (1.0, 0.0)), 0.01)
    grid = Grid(256, 16.0)
    with pytest.raises(ValueError, match="patch half-size"):
        ship_patch_waves(ship, grid, DEEP, 0.0, 5.0, 16)  # moves 5 m in one step
    with pytest.raises(ValueError, match="larger than the grid"):
        ship_patch_waves(ship, Grid(16, 16.0), DEEP, 0.0, 0.01, 16)


@pytest.mark.parametrize("velocity,name", [((math.nan, 0.0), "velocity"), ((1.0,), "velocity")])
def test_bad_velocity(velocity, name):
    with pytest.raises(ValueError, match=name):
        ship_multipliers(GRID, DEEP, velocity, 0.1)
