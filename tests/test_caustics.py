import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from optics.caustics import FLOOR_IRRADIANCE_METHODS, first_fold_depth, floor_irradiance, focal_depth, sinusoid_irradiance
from optics.light.fresnel import N_AIR, N_WATER, reflectance
from wavephys import Grid

GRID = Grid(128, 1.0)
A, K = 0.002, 2 * math.pi * 2  # two wavelengths of 0.5 m on the 1 m domain; slope ak = 0.025
ZF = focal_depth(A, K)


def _wave(grid, diagonal=False, crest=-0.5):
    """A cos(K(x − crest)): the same continuous wave on every grid (crest = −L/2), or with a
    crest through a sample (crest = grid.origin) where a test reads the peak off the map."""
    x, y = grid.mesh()
    if diagonal:  # wave vector (2, 2)·2π/L: the same pattern at 45°
        return A * jnp.cos(2 * math.pi * 2 * (x + y - 2 * crest) / grid.length)
    return A * jnp.cos(K * (x - crest))


def _random_surface(grid):
    x, y = grid.mesh()
    w = 2 * math.pi / grid.length
    return 0.01 * jnp.cos(3 * w * x) * jnp.sin(2 * w * y) + 0.005 * jnp.sin(5 * w * (x + y))


class TestFlux:
    @pytest.mark.parametrize("method,kw", [("reference", {}), ("photon", dict(filter_radius=0)),
                                           ("beam", dict(samples=1, normals="central"))])
    def test_conserved_oblique_sun(self, method, kw):
        e = floor_irradiance(_random_surface(Grid(64, 2.0)), Grid(64, 2.0), 1.0, sun=(0.3, 0.2, 1.0),
                             method=method, fresnel=False, **kw)
        assert float(jnp.mean(e)) == pytest.approx(1.0, abs=1e-5)

    def test_floor_total_equals_transmitted_total(self):
        grid = Grid(64, 2.0)
        eta = _random_surface(grid)
        gx, gy = grid.gradient(eta)
        cos_i = 1.0 / jnp.sqrt(1.0 + gx**2 + gy**2)  # vertical sun
        transmitted = 1.0 - float(jnp.mean(reflectance(cos_i, N_AIR, N_WATER)))
        floor = float(jnp.mean(floor_irradiance(eta, grid, 1.0, method="beam")))
        assert floor == pytest.approx(transmitted, rel=1e-3)

    def test_flat_water_is_uniform(self):
        sun = np.array([0.4, -0.1, 1.0])
        e = floor_irradiance(jnp.zeros((64, 64)), Grid(64, 2.0), 3.0, sun=sun, method="beam")
        t = 1.0 - float(reflectance(sun[2] / np.linalg.norm(sun)))
        assert float(e.min()) == pytest.approx(t, rel=1e-5) and float(e.max()) == pytest.approx(t, rel=1e-5)


class TestSinusoid:
    @pytest.mark.parametrize("diagonal", [False, True])
    @pytest.mark.parametrize("method,kw", [("beam", dict(samples=8, normals="central"))])  # the registry has the rest
    def test_peak_and_trough_at_half_focal_depth(self, method, kw, diagonal):
        k = K * math.sqrt(2) if diagonal else K
        depth = focal_depth(A, k) / 2
        e = floor_irradiance(_wave(GRID, diagonal, GRID.origin), GRID, depth, method=method, fresnel=False, **kw)
        # paraxial theory: E0/(1 − 1/2) = 2 at the crests, E0/(1 + 1/2) = 2/3 under the troughs
        assert float(e.max()) == pytest.approx(2.0, rel=0.01)
        assert float(e.min()) == pytest.approx(2.0 / 3.0, rel=0.01)

    def test_profile_matches_theory(self):
        e = np.asarray(floor_irradiance(_wave(GRID), GRID, ZF / 2, method="beam", samples=8, fresnel=False))[0]
        x = np.linspace(-0.5, 0.5, 20001)
        X, E = sinusoid_irradiance(x + 0.5, A, K, ZF / 2)
        theory = np.interp(np.asarray(GRID.coordinates) + 0.5, X, E, period=1.0)
        assert np.max(np.abs(e / theory - 1)) < 0.01

    def test_blinn_phong_cannot_focus(self):
        """Documented failure: the shading trick ignores where light lands (no caustics)."""
        e = floor_irradiance(_wave(GRID), GRID, ZF / 2, method="blinn_phong")
        assert float(e.max()) < 1.01


def _exact_tent_averages(n_pixels, depth, fine=1 << 16):
    """Exact (float64, exact Snell) floor irradiance under A cos Kx, averaged with the same
    tent (cloud-in-cell) weights the deposit uses: a very fine 1-D ray deposit."""
    L = 1.0
    x = (np.arange(fine) + 0.5) * L / fine - L / 2
    slope = -A * K * np.sin(K * (x + L / 2))
    eta = A * np.cos(K * (x + L / 2))
    norm = np.sqrt(1 + slope**2)
    nx, nz = -slope / norm, 1 / norm
    r = N_AIR / N_WATER
    cos_i = nz
    coef = r * cos_i - np.sqrt(1 - r * r * (1 - cos_i**2))
    tx, tz = coef * nx, -r + coef * nz
    X = x + (eta + depth) / (-tz) * tx
    p = L / n_pixels
    u = (X + L / 2) / p - 0.5  # texel coordinates of the cell-centred floor map
    i0 = np.floor(u).astype(int)
    f = u - i0
    out = np.zeros(n_pixels)
    np.add.at(out, i0 % n_pixels, (1 - f) * L / fine)
    np.add.at(out, (i0 + 1) % n_pixels, f * L / fine)
    return out / p


@pytest.mark.parametrize("normals", ["spectral", "central"])
def test_beam_tracing_converges_at_second_order(normals):
    depth, m = ZF / 2, 32
    exact = _exact_tent_averages(m, depth)
    errors = []
    for n in (16, 32, 64, 128):
        grid = Grid(n, 1.0)
        e = np.asarray(floor_irradiance(_wave(grid), grid, depth, method="beam", resolution=m, samples=4,
                                        fresnel=False, normals=normals))[m // 2]
        errors.append(np.max(np.abs(e - exact)))
    order = -np.polyfit(np.log2([16, 32, 64, 128]), np.log2(errors), 1)[0]  # log-log slope
    assert 1.9 < order < 2.3, (errors, order)


@pytest.mark.parametrize("kw,name", [(dict(depth=-1.0), "depth"), (dict(depth=math.nan), "depth"),
                                     (dict(sun=(0.0, 0.0, -1.0)), "sun"), (dict(method="exact"), "method"),
                                     (dict(n_water=0.5), "n_water"), (dict(samples=0), "samples"),
                                     (dict(normals="sobel"), "normals")])
def test_bad_input(kw, name):
    args = dict(depth=1.0)
    args.update(kw)
    with pytest.raises(ValueError, match=name):
        floor_irradiance(jnp.zeros((16, 16)), Grid(16, 1.0), **args)


def test_methods_are_a_family():
    assert set(FLOOR_IRRADIANCE_METHODS) == {"beam", "photon", "reference", "blinn_phong"}
    with pytest.raises(TypeError, match="photons_per_txl"):  # a typo no method takes
        floor_irradiance(jnp.zeros((16, 16)), Grid(16, 1.0), 1.0, method="photon", photons_per_txl=4)
    # options of other methods are not passed on: the beam ignores photons_per_texel
    a = floor_irradiance(jnp.zeros((16, 16)), Grid(16, 1.0), 1.0, method="beam", photons_per_texel=4)
    np.testing.assert_array_equal(a, floor_irradiance(jnp.zeros((16, 16)), Grid(16, 1.0), 1.0, method="beam"))


def test_bad_eta_and_ground():
    with pytest.raises(ValueError, match="eta"):
        floor_irradiance(jnp.full((16, 16), jnp.nan), Grid(16, 1.0), 1.0)
    with pytest.raises(ValueError, match="eta"):
        floor_irradiance(jnp.zeros((8, 16)), Grid(16, 1.0), 1.0)
    with pytest.raises(ValueError, match="depth"):
        floor_irradiance(jnp.zeros((16, 16)), Grid(16, 1.0), jnp.full((16, 16), 0.5))  # ground above water


def test_ground_height_field_equals_flat_floor():
    grid = Grid(64, 2.0)
    eta = _random_surface(grid)
    flat = floor_irradiance(eta, grid, 1.5, method="beam")
    ground = floor_irradiance(eta, grid, jnp.full((64, 64), -1.5), method="beam")
    np.testing.assert_allclose(ground, flat, atol=1e-4)


def test_uneven_ground_conserves_flux_and_moves_the_pattern():
    grid = Grid(64, 2.0)
    x, y = grid.mesh()
    eta = _random_surface(grid)
    ground = -1.5 + 0.3 * jnp.sin(2 * math.pi * x / 2.0)
    e = floor_irradiance(eta, grid, ground, method="beam", fresnel=False)
    flat = floor_irradiance(eta, grid, 1.5, method="beam", fresnel=False)
    assert float(jnp.mean(e)) == pytest.approx(1.0, abs=1e-5)
    assert float(jnp.max(jnp.abs(e - flat))) > 0.05  # the light lands elsewhere
    # where the ground rises the light has travelled less far: closer to the flat-floor result at that depth
    shallow = floor_irradiance(eta, grid, 1.2, method="beam", fresnel=False)
    col = int(np.argmin(np.abs(np.asarray(grid.coordinates) - 0.5)))  # sin peak: ground at −1.2 m
    assert np.abs(np.asarray(e)[:, col] - np.asarray(shallow)[:, col]).mean() < np.abs(
        np.asarray(e)[:, col] - np.asarray(flat)[:, col]).mean()


class TestLowSun:
    """Below the steepest slope's angle, facets face away from the sun and crests hide what is
    behind them: shadowed samples send nothing, so flux is conserved and never negative."""

    @staticmethod
    def _surface(seed, n=128, length=4.0, steepest=0.4):
        grid = Grid(n, length)
        k = grid.wavenumber_magnitude()
        key = jax.random.PRNGKey(seed)
        a, b = jax.random.normal(key, (2, n, n))
        spec = (a + 1j * b) * jnp.exp(-0.5 * ((k - 2 * math.pi / 0.8) / 3.0) ** 2)
        eta = jnp.real(jnp.fft.ifft2(spec))
        gx, gy = grid.gradient(eta)
        return grid, eta * (steepest / float(jnp.max(jnp.hypot(gx, gy))))

    @pytest.mark.parametrize("seed", range(4))
    def test_beam_conserves_flux_below_the_steepest_slope(self, seed):
        grid, eta = self._surface(seed)
        rng = np.random.default_rng(seed)
        for elevation in (20.0, 15.0, 10.0):  # the steepest slope stands at 21.8°
            az, e = rng.uniform(0, 2 * math.pi), math.radians(elevation)
            sun = (math.cos(e) * math.cos(az), math.cos(e) * math.sin(az), math.sin(e))
            out = np.asarray(floor_irradiance(eta, grid, 1.0, sun, method="beam", fresnel=False))
            # measured |mean - 1| <= 3e-4 (without shadows: 1.8-2.3 % too much light at 10°)
            assert abs(out.mean() - 1.0) < 1e-3, (elevation, out.mean())
            assert out.min() >= 0.0

    def test_shadowed_samples_send_nothing(self):
        from optics.caustics.common import shadow_steps, sunlit

        grid = Grid(64, 4.0)
        x, _ = grid.mesh()
        eta = 0.08 * jnp.cos(2 * math.pi * x)  # slope up to 0.50 (26.7°)
        e = math.radians(10.0)
        d = jnp.asarray([-math.cos(e), 0.0, -math.sin(e)], jnp.float32)  # sunlight travelling in -x
        steps = shadow_steps(eta, grid, np.asarray(d))
        assert steps > 0
        lit = np.asarray(sunlit(eta, grid, d, steps))
        gx = np.asarray(grid.gradient(eta)[0])
        facing_away = gx * math.cos(e) - math.sin(e) > 0  # normal · (toward the sun) < 0
        assert lit[facing_away].max() == 0.0  # every facet that faces away is dark
        assert 0.2 < lit.mean() < 0.9  # and crests hide more than those
        assert shadow_steps(eta, grid, np.asarray([0.0, 0.0, -1.0])) == 0  # a high sun costs nothing
