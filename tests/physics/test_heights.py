import math

import jax.numpy as jnp
import numpy as np
import pytest

from wavephys import Grid, Water
from wavephys.physics.heights import (first_order_height, monochromatic_wave, potential_from_height,
                                      second_order_error, second_order_height)
from wavephys.physics.stokes import stokes_wave

DEEP = Water(sigma=0.0)


class TestSecondOrder:
    @pytest.mark.parametrize("steepness,mode", [(0.05, 3), (0.15, 7), (0.25, 12)])
    def test_single_wave_in_any_direction_equals_stokes(self, steepness, mode):
        """A family of waves (steepness, wavelength, direction) beyond the registry's one."""
        grid = Grid(128, 8.0)
        psi, k, a = monochromatic_wave(grid, DEEP, steepness, mode)
        eta = np.asarray(second_order_height(psi, grid, DEEP))
        theta = k * (np.asarray(grid.coordinates) + 4.0) + np.pi / 2
        stokes = a * np.cos(theta) + 0.5 * k * a**2 * np.cos(2 * theta)
        np.testing.assert_allclose(eta, np.broadcast_to(stokes, eta.shape), atol=2e-5 * a)
        rotated = np.asarray(second_order_height(jnp.swapaxes(psi, 0, 1), grid, DEEP))
        np.testing.assert_allclose(rotated, eta.T, atol=2e-5 * a)  # the same wave travelling in y

    def test_paper_formula_eq3_with_capillarity(self):
        """Eq. 3 holds for any ω: η = a i(|k|/ω)e^{iθ} − a²|k|³/(2ω²) e^{2iθ}."""
        grid, water = Grid(128, 1.0), Water()
        k = 2 * math.pi * 6
        omega = math.sqrt(9.81 * k + 0.0728e-3 * k**3)
        a = 1e-3 * omega / k
        x = np.asarray(grid.coordinates) + 0.5
        psi = a * np.exp(1j * k * x)[None, :] * np.ones((128, 1))
        eq3 = (a * 1j * k / omega * np.exp(1j * k * x) - a**2 * k**3 / (2 * omega**2) * np.exp(2j * k * x)).real
        got = np.asarray(second_order_height(jnp.asarray(psi, jnp.complex64), grid, water))[0]
        np.testing.assert_allclose(got, eq3, atol=1e-5 * a * k / omega)

    @pytest.mark.slow
    def test_error_grows_with_steepness(self):
        errs = [second_order_error(s)["second"] for s in (0.05, 0.1, 0.2, 0.3)]
        assert all(b > a for a, b in zip(errs, errs[1:]))
        assert errs[0] < 0.002 and errs[-1] > 0.05


class TestStokesReference:
    """The exact solver against Stokes' expansion (independent published coefficients)."""

    @pytest.mark.parametrize("ka", [0.02, 0.05])
    def test_expansion(self, ka):
        w = stokes_wave(ka)
        x = np.linspace(0, 2 * np.pi, 2048, endpoint=False)
        f = np.fft.rfft(w(x)) / 1024
        assert w.speed_factor**2 == pytest.approx(1 + ka**2 + 1.25 * ka**4, abs=5 * ka**6)
        assert f[1].real == pytest.approx(ka, rel=1e-6)
        assert f[2].real == pytest.approx(0.5 * ka**2, rel=3 * ka**2)
        assert f[3].real == pytest.approx(3 / 8 * ka**3, rel=5 * ka**2)
        assert abs(np.mean(w(x))) < 1e-8

    def test_bad_steepness(self):
        with pytest.raises(ValueError, match="steepness"):
            stokes_wave(0.5)


class TestPotentialFromHeight:
    def test_round_trip(self):
        grid = Grid(64, 2.0)
        x, y = grid.mesh()
        eta = 1e-3 * jnp.cos(2 * jnp.pi * 3 * x / 2.0) * jnp.sin(2 * jnp.pi * 2 * y / 2.0)
        back = first_order_height(potential_from_height(eta, grid, DEEP), grid, DEEP)
        np.testing.assert_allclose(back, eta, atol=1e-9)

    def test_bad_shape(self):
        with pytest.raises(ValueError, match="eta"):
            potential_from_height(jnp.zeros((8, 8)), Grid(16, 1.0), DEEP)
