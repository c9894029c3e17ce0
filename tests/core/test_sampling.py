"""The periodic cubic B-spline (wavephys.core.sampling.bspline): it interpolates its samples, wraps,
and its derivatives are its own (finite differences of its values), on a grid whose sides differ so a
swapped axis shows."""

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from wavephys.core.sampling import bspline
from wavephys.core.spectral import bspline_coefficients


@pytest.fixture
def field():
    rng = np.random.default_rng(4)
    rows, cols = 24, 40
    v, u = np.mgrid[0:rows, 0:cols]
    out = np.stack([np.cos(2 * np.pi * (3 * u / cols + 2 * v / rows)) + 0.1 * rng.standard_normal((rows, cols)),
                    np.sin(2 * np.pi * (u / cols - 4 * v / rows))], axis=-1)
    return out


def test_bspline_interpolates_wraps_and_has_its_own_derivatives(field, x64):
    coefficients = jnp.asarray(np.moveaxis(bspline_coefficients(np.moveaxis(field, -1, 0)), 0, -1))
    rows, cols, _ = field.shape
    v, u = np.mgrid[0:rows, 0:cols]
    at_samples = bspline(coefficients, jnp.asarray(u.ravel(), float), jnp.asarray(v.ravel(), float))
    assert np.allclose(np.asarray(at_samples), field.reshape(-1, 2), atol=1e-10)
    rng = np.random.default_rng(5)
    pu, pv = rng.uniform(-cols, 2 * cols, 200), rng.uniform(-rows, 2 * rows, 200)
    value, du, dv = (np.asarray(a) for a in bspline(coefficients, jnp.asarray(pu), jnp.asarray(pv), derivatives=True))
    assert np.allclose(value, np.asarray(bspline(coefficients, jnp.asarray(pu + cols), jnp.asarray(pv - rows))),
                       atol=1e-10)
    assert np.allclose(value, np.asarray(bspline(coefficients, jnp.asarray(pu), jnp.asarray(pv))), atol=1e-12)
    h = 1e-6
    fu = (np.asarray(bspline(coefficients, jnp.asarray(pu + h), jnp.asarray(pv)))
          - np.asarray(bspline(coefficients, jnp.asarray(pu - h), jnp.asarray(pv)))) / (2 * h)
    fv = (np.asarray(bspline(coefficients, jnp.asarray(pu), jnp.asarray(pv + h)))
          - np.asarray(bspline(coefficients, jnp.asarray(pu), jnp.asarray(pv - h)))) / (2 * h)
    assert np.allclose(du, fu, atol=1e-6) and np.allclose(dv, fv, atol=1e-6)
    assert np.abs(du - dv).max() > 0.1  # the two derivatives differ on this field (a swap would show)


def test_bspline_under_jit_matches_eager(field):
    coefficients = jnp.asarray(np.moveaxis(bspline_coefficients(np.moveaxis(field, -1, 0)), 0, -1), jnp.float32)
    u, v = jnp.linspace(-3.0, 50.0, 77), jnp.linspace(30.0, -7.0, 77)
    eager = bspline(coefficients, u, v, derivatives=True)
    jitted = jax.jit(lambda c, a, b: bspline(c, a, b, derivatives=True))(coefficients, u, v)
    for a, b in zip(eager, jitted):
        assert np.allclose(np.asarray(a), np.asarray(b), atol=1e-5)


def test_bspline_between_the_samples_is_the_smooth_field_it_samples(x64):
    """Between samples the spline is the band-limited field it was made from to fourth order (waves of
    8–12 samples: measured 5.2e-4 of their amplitude, bound 2e-3), so a tap read from the wrong place shows."""
    rows, cols = 24, 40
    exact = lambda u, v: np.cos(2 * np.pi * (3 * u / cols + 2 * v / rows)) + np.sin(2 * np.pi * (u / cols - 2 * v / rows))
    v, u = np.mgrid[0:rows, 0:cols]
    coefficients = jnp.asarray(bspline_coefficients(exact(u, v))[..., None])
    rng = np.random.default_rng(6)
    pu, pv = rng.uniform(0, cols, 500), rng.uniform(0, rows, 500)
    value = np.asarray(bspline(coefficients, jnp.asarray(pu), jnp.asarray(pv)))[:, 0]
    assert np.abs(value - exact(pu, pv)).max() < 2e-3
