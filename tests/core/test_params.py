import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from wavephys import Grid, Water
from wavephys.physics.dispersion import angular_frequency


class TestWater:
    def test_defaults_are_spec_values(self):
        w = Water()
        assert (w.g, w.rho, w.sigma, w.depth) == (9.81, 1000.0, 0.0728, math.inf)
        assert w.is_deep and not Water(depth=3.0).is_deep

    @pytest.mark.parametrize("field,value", [("g", 0.0), ("g", -9.81), ("rho", 0.0), ("sigma", -1e-3),
                                             ("depth", 0.0), ("depth", -1.0), ("g", math.nan),
                                             ("sigma", math.inf), ("depth", math.nan)])
    def test_bad_values_name_the_parameter(self, field, value):
        with pytest.raises(ValueError, match=field):
            Water(**{field: value})

    @pytest.mark.parametrize("field,value", [("rho", "x"), ("g", None), ("sigma", True), ("depth", 1j)])
    def test_wrong_kinds_are_type_errors(self, field, value):
        with pytest.raises(TypeError, match=field):
            Water(**{field: value})

    def test_is_a_pytree_that_jit_and_vmap_sweep(self):
        assert len(jax.tree_util.tree_leaves(Water())) == 4
        depths = jnp.array([0.5, 1.0, 2.0])
        # vmap over depth (a traced leaf): shallow-water speed grows as sqrt(h)
        w = jax.vmap(lambda h: angular_frequency(0.01, Water(sigma=0.0, depth=h)))(depths)
        np.testing.assert_allclose(np.asarray(w) / 0.01, np.sqrt(9.81 * np.asarray(depths)), rtol=1e-4)

    def test_replace_validates(self):
        assert Water().replace(sigma=0.0).sigma == 0.0
        with pytest.raises(ValueError, match="sigma"):
            Water().replace(sigma=-1.0)


class TestGrid:
    def test_spacing_and_wavenumbers(self):
        g = Grid(8, 2.0)
        assert g.dx == 0.25
        ky, kx = g.wavenumbers()
        np.testing.assert_allclose(np.asarray(kx[0]), 2 * np.pi * np.fft.fftfreq(8, 0.25), rtol=1e-6)
        assert g.wavenumber_magnitude(real=True).shape == (8, 5)
        # samples at the cell centres −L/2 + (i + ½)·dx: symmetric about 0, edges at ±L/2
        np.testing.assert_allclose(np.asarray(g.coordinates), np.arange(-0.875, 1.0, 0.25))
        np.testing.assert_allclose(np.asarray(g.edges), np.arange(-1.0, 1.01, 0.25))
        assert g.nearest(0.01, -0.99) == (0, 4) and g.nearest(1.01, 0.0) == (4, 0)  # wraps

    @pytest.mark.parametrize("n,length,name", [(0, 1.0, "n"), (1, 1.0, "n"), (7, 1.0, "n"),
                                               (8, 0.0, "length"), (8, -1.0, "length"),
                                               (8, math.nan, "length"), (8, math.inf, "length")])
    def test_bad_grid(self, n, length, name):
        with pytest.raises(ValueError, match=name):
            Grid(n, length)

    @pytest.mark.parametrize("n,length,name", [(8.0, 1.0, "n"), ("8", 1.0, "n"), (8, None, "length")])
    def test_wrong_kinds(self, n, length, name):
        with pytest.raises(TypeError, match=name):
            Grid(n, length)

    def test_pytree_keeps_n_static(self):
        g = Grid(16, 3.0)
        out = jax.jit(lambda g: g.wavenumber_magnitude())(g)
        assert out.shape == (16, 16)
