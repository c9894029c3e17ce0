"""The cheap surface models (noise, Gerstner, choppy, foam, resampling) over families of inputs.

Each claim is tested over seeds, directions, depths, steepnesses and dtypes generated here,
with errors in the max norm; the validate rows (wavephys/checks/surfaces.py) test single
seeded scenes.
"""

import math
import warnings

import jax
import jax.numpy as jnp
import numpy as np
import pytest

import wavephys.surfaces.choppy as choppy
import wavephys.surfaces.gerstner as gerstner
import wavephys.surfaces.noise as noise
from wavephys import Grid, Water
from wavephys.checks.surfaces import normal_orders, random_sea
from wavephys.surfaces import resample_heights
from wavephys.surfaces.resample import map_jacobian

RNG = np.random.default_rng(12)


# -- noise ---------------------------------------------------------------------------------
@pytest.mark.parametrize("dim", [2, 3])
@pytest.mark.parametrize("seed", [7, 123456])
def test_gradient_noise_vanishes_on_the_lattice_and_is_bounded(dim, seed):
    pts = [RNG.integers(-300, 300, 500).astype(np.float32) for _ in range(dim)]
    assert float(jnp.max(jnp.abs(noise.gradient_noise(*pts, seed=seed)))) == 0.0
    pts = [RNG.uniform(-50, 50, 20000).astype(np.float32) for _ in range(dim)]
    n = np.asarray(noise.gradient_noise(*pts, seed=seed))
    assert np.abs(n).max() < 1.0 and n.std() > 0.1


@pytest.mark.parametrize("kind", [noise.gradient_noise, noise.value_noise])
@pytest.mark.parametrize("dim", [2, 3])
def test_noise_derivatives_are_exact(kind, dim, x64):
    pts = [RNG.uniform(-20, 20, 2000) for _ in range(dim)]
    seed = int(RNG.integers(0, 2**31 - 1))
    _, grad = kind(*pts, seed=seed, derivatives=True)
    h = 1e-6
    for a in range(dim):
        up = [p + (h if b == a else 0) for b, p in enumerate(pts)]
        dn = [p - (h if b == a else 0) for b, p in enumerate(pts)]
        fd = (np.asarray(kind(*up, seed=seed)) - np.asarray(kind(*dn, seed=seed))) / (2 * h)
        assert np.max(np.abs(np.asarray(grad[a]) - fd)) < 1e-6


@pytest.mark.parametrize("period", [1, 3, 256])
def test_noise_tiles_with_its_period(period):
    x, y, z = (RNG.uniform(0, period, 1000).astype(np.float32) for _ in range(3))
    a = noise.gradient_noise(x, y, z, seed=5, period=period)
    b = noise.gradient_noise(x + period, y - 2 * period, z + period, seed=5, period=period)
    assert float(jnp.max(jnp.abs(a - b))) < 1e-4


@pytest.mark.parametrize("octaves,hurst", [(3, 0.5), (6, 1.5)])
def test_fbm_tiles_a_grid_and_its_gradient_is_exact(octaves, hurst, x64):
    grid = Grid(64, 8.0)
    x, y = (np.asarray(c, np.float64) for c in grid.mesh())
    params = dict(octaves=octaves, hurst=hurst, frequency=0.5, tile=8.0, amplitude=0.1, seed=3, evolution=0.7)
    a = fbm = noise.fbm(x, y, 1.3, **params)
    assert float(jnp.max(jnp.abs(noise.fbm(x + 8.0, y - 16.0, 1.3, **params) - a))) < 1e-9
    _, (gx, gy) = noise.fbm(x, y, 1.3, derivatives=True, **params)
    h = 1e-6
    fdx = (noise.fbm(x + h, y, 1.3, **params) - noise.fbm(x - h, y, 1.3, **params)) / (2 * h)
    assert float(jnp.max(jnp.abs(gx - fdx))) < 1e-6 * max(1.0, float(jnp.max(jnp.abs(gx))))
    assert float(jnp.max(jnp.abs(fbm))) <= 0.1 * sum(2 ** (-hurst * i) for i in range(octaves))


def test_fbm_lattice_animation_is_continuous_in_time_and_matches_jit():
    x = RNG.uniform(-4, 4, 300).astype(np.float32)
    y = RNG.uniform(-4, 4, 300).astype(np.float32)
    params = dict(octaves=2, frequency=1.0, evolution=1.0, animation="lattices")
    before = noise.fbm(x, y, 0.999999, **params)
    after = noise.fbm(x, y, 1.000001, **params)
    assert float(jnp.max(jnp.abs(before - after))) < 1e-4  # the lattices blend, no jump at whole times
    f = jax.jit(lambda t: noise.fbm(x, y, t, octaves=3, frequency=1.0))
    assert float(jnp.max(jnp.abs(f(0.4) - noise.fbm(x, y, 0.4, octaves=3, frequency=1.0)))) < 1e-6


@pytest.mark.parametrize("seed", [1])
def test_normals_three_ways_converge_at_their_orders(seed):
    orders = normal_orders(seed=seed, points=2048)
    assert abs(orders["shifted"]["order"] - 1.0) < 0.15, orders
    assert abs(orders["central"]["order"] - 2.0) < 0.2, orders
    assert orders["central"]["error"] < orders["shifted"]["error"]


def test_fbm_spectrum_slope_follows_hurst():
    from wavephys.checks.surfaces import fbm_spectrum

    for hurst, seed in ((0.25, 4), (0.75, 5), (1.25, 6)):
        assert abs(fbm_spectrum(hurst, n=128, length=32.0, octaves=6, seed=seed) - noise.fbm_spectrum_slope(hurst)) < 0.25


def test_bspline_surface_reproduces_constants_and_planes_and_tiles(x64):
    ctl = np.full((8, 8), 0.37)
    x, y = RNG.uniform(-10, 10, 500), RNG.uniform(-10, 10, 500)
    h, (gx, gy) = noise.bspline_surface(ctl, 4.0, x, y, derivatives=True)
    assert np.allclose(h, 0.37) and np.allclose(gx, 0) and np.allclose(gy, 0)
    ctl = RNG.standard_normal((8, 8))
    a = noise.bspline_surface(ctl, 4.0, x, y)
    assert np.allclose(a, noise.bspline_surface(ctl, 4.0, x + 4.0, y - 8.0))
    assert float(jnp.max(a)) <= ctl.max() and float(jnp.min(a)) >= ctl.min()  # convex hull
    _, (gx, _) = noise.bspline_surface(ctl, 4.0, x, y, derivatives=True)
    fd = (noise.bspline_surface(ctl, 4.0, x + 1e-6, y) - noise.bspline_surface(ctl, 4.0, x - 1e-6, y)) / 2e-6
    assert float(jnp.max(jnp.abs(gx - fd))) < 1e-6


def test_noise_sea_on_a_grid_and_bad_input():
    grid = Grid(64, 16.0)
    sea = noise.NoiseSea()
    h = sea.heights(grid, 2.0)
    assert h.shape == (64, 64) and h.dtype == jnp.float32 and 0 < float(jnp.std(h)) < 0.1
    gx, gy = sea.gradient(grid, 2.0)
    cx, cy = sea.gradient(grid, 2.0, "central", 1e-3)  # base surface included in both
    assert float(jnp.max(jnp.hypot(gx - cx, gy - cy))) < 1e-3 * float(jnp.max(jnp.hypot(gx, gy)))
    with pytest.raises(ValueError, match="octaves"):
        noise.fbm(0.0, 0.0, octaves=0)
    with pytest.raises(ValueError, match="tile"):
        noise.fbm(0.0, 0.0, frequency=0.3, tile=1.0)
    with pytest.raises(ValueError, match="octaves"):
        noise.fbm(np.array([1e5]), np.array([0.0]), octaves=20)
    with pytest.raises(ValueError, match="grid"):
        sea.heights(Grid(64, 8.0))
    with pytest.raises(TypeError, match="grid"):
        sea.heights("grid")


# -- Gerstner ---------------------------------------------------------------------------------
def _random_waves(grid, rng, count, steepness, water=Water(sigma=0.0), scale=0.5):
    m = rng.integers(-6, 7, size=(count, 2))
    m = m[(m != 0).any(1)]
    k = m * float(grid.dk)
    kk = np.hypot(k[:, 0], k[:, 1])
    amp = scale / kk / len(kk) * rng.uniform(0.3, 1.0, len(kk))
    return gerstner.GerstnerWaves(k, amp, rng.uniform(0, 2 * np.pi, len(kk)), steepness, water)


@pytest.mark.parametrize("seed", range(2))
@pytest.mark.parametrize("water", [Water(sigma=0.0), Water(depth=0.3), Water(sigma=0.0, depth=2.0)])
def test_gerstner_normals_and_jacobian_are_exact(seed, water, x64):
    rng = np.random.default_rng(seed)
    waves = _random_waves(Grid(32, 10.0), rng, 6, rng.uniform(0.2, 1.0), water)
    x, y = rng.uniform(-5, 5, 400), rng.uniform(-5, 5, 400)
    t = rng.uniform(0, 10)
    h = 1e-6
    p = lambda a, b: np.asarray(waves.displacement(a, b, t)) + np.stack([a, b, 0 * a])
    tx = (p(x + h, y) - p(x - h, y)) / (2 * h)
    ty = (p(x, y + h) - p(x, y - h)) / (2 * h)
    n = np.cross(tx, ty, axis=0)
    n /= np.linalg.norm(n, axis=0)
    assert np.max(np.abs(np.asarray(waves.normals(x, y, t)) - n)) < 1e-7
    jac = tx[0] * ty[1] - ty[0] * tx[1]
    assert np.max(np.abs(np.asarray(waves.jacobian(x, y, t)) - jac)) < 1e-7


@pytest.mark.parametrize("seed", range(3))
def test_gerstner_heights_sit_on_the_displaced_surface(seed):
    rng = np.random.default_rng(seed)
    grid = Grid(64, 12.0)
    waves = _random_waves(grid, rng, 8, 0.9, scale=0.6)
    t = float(rng.uniform(0, 5))
    z = np.asarray(waves.heights(grid, t), np.float64)
    # the fast grid resampling of the same displaced surface agrees with the exact inversion
    x, y = grid.mesh()
    d = waves.displacement(x, y, t)
    for refine, tol in ((1, 0.02), (2, 0.006), (4, 0.0015)):
        est = np.asarray(resample_heights(d[:2], d[2], grid, refine=refine), np.float64)
        assert np.max(np.abs(est - z)) < tol * np.ptp(z), (refine, np.max(np.abs(est - z)) / np.ptp(z))


def test_gerstner_q0_is_a_plain_sum_of_cosines():
    grid = Grid(32, 8.0)
    waves = _random_waves(grid, np.random.default_rng(3), 5, 0.0)
    x, y = grid.mesh()
    z = sum(a * jnp.cos(k[0] * x + k[1] * y - w * 2.0 + p) for k, a, w, p in
            zip(waves.wavevectors, waves.amplitudes, waves.frequencies, waves.phases))
    assert float(jnp.max(jnp.abs(waves.heights(grid, 2.0) - z))) < 1e-6


@pytest.mark.parametrize("water", [Water(), Water(sigma=0.0, depth=0.4)])
def test_gerstner_dispersion_is_what_it_was_built_with(water):
    from wavephys.checks.surfaces import gerstner_dispersion

    seed = 1 if water.sigma else 2  # each depth its own random sum
    assert np.max(np.abs(gerstner_dispersion(water, seed=seed, frames=192))) < 0.003


def test_gerstner_folds_are_refused_or_warned():
    with pytest.raises(ValueError, match="steepness"):
        gerstner.GerstnerWaves(np.array([[2.0, 0.0]]), np.array([0.5]), steepness=1.0)
    with pytest.raises(ValueError, match="steepness"):  # finite depth: coth(kh) makes orbits wider
        gerstner.GerstnerWaves(np.array([[2.0, 0.0]]), np.array([0.45]), steepness=1.0, water=Water(depth=0.2))
    with pytest.warns(gerstner.FoldWarning):
        waves = gerstner.GerstnerWaves(np.array([[2.0, 0.0], [3.0, 0.0]]), np.array([0.3, 0.2]), steepness=1.0)
    assert waves.fold_measure == pytest.approx(1.2)
    folded = waves.fold_fraction(Grid(64, 2 * np.pi))  # J = 1 − 0.6 cos θ₁ − 0.6 cos θ₂ < 0 where crests meet
    assert 0 < folded < 0.2, folded
    with pytest.raises(ValueError, match="folds"):
        waves.heights(Grid(64, 2 * np.pi))
    with pytest.raises(ValueError, match="grid"):  # a wave the grid does not resolve
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            gerstner.GerstnerWaves(np.array([[40.0, 0.0]]), np.array([0.001])).heights(Grid(16, 2.0))
    with pytest.raises(ValueError, match="wavevectors"):
        gerstner.GerstnerWaves(np.array([[0.0, 0.0]]), np.array([0.1]))
    with pytest.raises(ValueError, match="amplitudes"):
        gerstner.GerstnerWaves(np.array([[1.0, 0.0]]), np.array([0.1, 0.2]))


def test_gerstner_from_spectrum_tiles_the_grid():
    from wavephys.physics.wind import wind_spectrum

    grid = Grid(64, 32.0)
    ky, kx = grid.wavenumbers()
    f = wind_spectrum(kx, ky, Water(sigma=0.0), "phillips", wind_speed=6.0)
    waves = gerstner.GerstnerWaves.from_spectrum(f, grid, jax.random.PRNGKey(1), count=20, steepness=0.5)
    assert waves.wavevectors.shape == (20, 2)
    m = waves.wavevectors / float(grid.dk)
    assert np.allclose(m, np.round(m), atol=1e-6)
    with pytest.raises(ValueError, match="spectrum"):
        gerstner.GerstnerWaves.from_spectrum(np.full((64, 64), np.nan), grid, jax.random.PRNGKey(1))


@pytest.mark.parametrize("kA", [0.05, 0.12, 0.2, 0.28])
def test_gerstner_crest_against_stokes(kA):
    c = gerstner.crest_comparison(kA)
    assert c["gerstner_mean"] == pytest.approx(-(c["height"] / 2) ** 2 / 2, rel=1e-4)
    assert c["crest_error"] < 0 < c["trough_error"]  # the trochoid's crest is the lower one
    assert abs(c["crest_error"]) == pytest.approx(0.65 * kA**3, rel=0.35)  # relative third order


# -- choppy and foam -----------------------------------------------------------------------
@pytest.mark.parametrize("seed", range(3))
def test_choppy_one_wave_is_gerstner_in_any_direction(seed):
    rng = np.random.default_rng(seed)
    grid = Grid(64, 10.0)
    m = rng.integers(-5, 6, 2)
    m = m if m.any() else np.array([1, 0])
    k = m * float(grid.dk)
    kk = float(np.hypot(*k))
    a = rng.uniform(0.1, 0.9) / kk
    phase = rng.uniform(0, 2 * np.pi)
    x, y = grid.mesh()
    h = a * jnp.cos(k[0] * x + k[1] * y + phase)
    lam = rng.uniform(0.2, 1.0)
    waves = gerstner.GerstnerWaves(k[None], np.array([a]), np.array([phase]), steepness=lam)
    d = waves.displacement(x, y)
    assert float(jnp.max(jnp.abs(choppy.displacement(h, grid, lam) - d[:2]))) < 1e-5 * a * 10
    assert float(jnp.max(jnp.abs(choppy.jacobian(h, grid, lam) - waves.jacobian(x, y)))) < 1e-4
    assert choppy.fold_choppiness(h, grid) >= 1 / (kk * a) * (1 - 1e-3)


@pytest.mark.parametrize("seed", range(2))
def test_choppy_jacobian_matches_the_displacement_map(seed):
    sea, grid = random_sea(n=64, length=32.0, seed=seed)
    lam = 0.5 * choppy.fold_choppiness(sea, grid)
    d = choppy.displacement(sea, grid, lam)
    assert float(jnp.max(jnp.abs(map_jacobian(d, grid) - choppy.jacobian(sea, grid, lam)))) < 1e-4
    assert float(jnp.min(choppy.jacobian(sea, grid, lam))) > 0
    assert float(jnp.min(choppy.jacobian(sea, grid, 1.01 * choppy.fold_choppiness(sea, grid)))) <= 0


@pytest.mark.parametrize("seed", range(2))
@pytest.mark.parametrize("wind_speed", [4.0, 8.0])
def test_foam_fraction_follows_jacobian_statistics(seed, wind_speed):
    """Measured over 6 seas x 4 choppiness: first order within 0.021 up to half the fold value
    (0.057 beyond), second order within 0.033 up to 0.9 of it (docs/physics.md §1.9)."""
    sea, grid = random_sea(n=128, length=64.0, seed=seed + 10, wind_speed=wind_speed)
    fold = choppy.fold_choppiness(sea, grid)
    for frac in (0.3, 0.5, 0.75, 0.9):
        lam = frac * fold
        measured = float(jnp.mean(choppy.foam(choppy.jacobian(sea, grid, lam), 0.7, 0.0)))
        second = choppy.foam_fraction_estimate(sea, grid, lam, 0.7, order=2)
        assert abs(measured - second) < 0.04, (frac, measured, second)
        if frac <= 0.5:
            assert abs(measured - choppy.foam_fraction_estimate(sea, grid, lam, 0.7)) < 0.025, (frac, measured)


def test_foam_coverage_and_accumulation():
    j = jnp.linspace(-0.5, 1.5, 201)
    c = choppy.foam(j, 0.3, 0.1)
    assert float(c.min()) == 0 and float(c.max()) == 1
    assert float(c[j >= 0.3].max()) == 0 and float(c[j <= 0.2].min()) == 1
    f = jnp.ones(5) * 0.8
    f = choppy.accumulate_foam(f, jnp.zeros(5), 1.0, 2.0)
    assert np.allclose(f, 0.8 * math.exp(-0.5))
    assert np.allclose(choppy.accumulate_foam(f, jnp.ones(5), 0.1, 2.0), 1.0)
    with pytest.raises(ValueError, match="choppiness"):
        choppy.displacement(jnp.zeros((8, 8)), Grid(8, 1.0), -1.0)
    with pytest.raises(ValueError, match="height"):
        choppy.displacement(jnp.full((8, 8), jnp.nan), Grid(8, 1.0))


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(2))
def test_resampling_error_falls_with_refinement(seed, x64):
    sea, grid = random_sea(n=64, length=32.0, seed=seed)
    sea = jnp.asarray(sea, jnp.float64)
    lam = 0.8 * choppy.fold_choppiness(sea, grid)
    d = choppy.displacement(sea, grid, lam)
    ref = resample_heights(d, sea, grid, refine=8, iterations=20)
    span = float(jnp.ptp(sea))
    errs = [float(jnp.max(jnp.abs(resample_heights(d, sea, grid, refine=r) - ref))) / span for r in (1, 2)]
    assert errs[0] < 0.01 and errs[1] < 0.003
    assert errs[0] / errs[1] > 3  # second order in the grid spacing
    with pytest.raises(ValueError, match="folds"):
        resample_heights(choppy.displacement(sea, grid, 1.2 * lam / 0.8), sea, grid)


def test_sea_height_travels_at_the_phase_speed():
    from wavephys.physics.dispersion import angular_frequency

    grid = Grid(64, 20.0)
    x, y = grid.mesh()
    k = 2 * np.pi * 4 / 20.0
    sea = 0.1 * jnp.exp(1j * k * y)
    w = float(angular_frequency(k, Water()))
    h = choppy.sea_height(sea, grid, Water(), 1.7)
    assert float(jnp.max(jnp.abs(h - 0.1 * jnp.cos(k * y - w * 1.7)))) < 1e-6
