import math

import jax.numpy as jnp
import numpy as np
import pytest

from optics.light.directions import reflect, refract, transmissive_half_vector

UP = jnp.array([0.0, 0.0, 1.0])


def _down_at(theta):
    return jnp.array([math.sin(theta), 0.0, -math.cos(theta)])


def test_reflect_mirrors_and_keeps_length():
    r = reflect(_down_at(0.3), UP)
    np.testing.assert_allclose(r, [math.sin(0.3), 0, math.cos(0.3)], atol=1e-6)


@pytest.mark.parametrize("theta", [0.0, 0.3, 0.8, 1.5])
def test_snell_from_air(theta):
    t, tir = refract(_down_at(theta), UP, 1.000293, 1.333)
    assert not bool(tir)
    assert float(jnp.linalg.norm(t)) == pytest.approx(1.0, abs=1e-6)
    sin_t = math.hypot(float(t[0]), float(t[1]))
    assert 1.333 * sin_t == pytest.approx(1.000293 * math.sin(theta), abs=1e-6)


def test_total_internal_reflection_from_below():
    crit = math.asin(1.000293 / 1.333)
    up_at = lambda th: jnp.array([math.sin(th), 0.0, math.cos(th)])
    _, tir_below = refract(up_at(crit - 1e-3), UP, 1.333, 1.000293)
    t, tir_above = refract(up_at(crit + 1e-3), UP, 1.333, 1.000293)
    assert not bool(tir_below) and bool(tir_above)
    np.testing.assert_allclose(t, reflect(up_at(crit + 1e-3), UP), atol=1e-6)  # reflected instead


def test_normal_orientation_and_length_do_not_matter():
    a, _ = refract(_down_at(0.4) * 3.0, -UP * 2.0, 1.0, 1.333)
    b, _ = refract(_down_at(0.4), UP, 1.0, 1.333)
    np.testing.assert_allclose(a, b, atol=1e-6)


def test_batched():
    d = jnp.stack([_down_at(t) for t in (0.1, 0.5, 1.0)])
    t, tir = refract(d, jnp.broadcast_to(UP, d.shape), 1.0, 1.333)
    assert t.shape == (3, 3) and tir.shape == (3,)


def test_transmissive_half_vector_is_unit():
    h = transmissive_half_vector(jnp.array([0.0, 0.3, 1.0]), jnp.array([0.2, 0.0, 1.0]), 1.333)
    assert float(jnp.linalg.norm(h)) == pytest.approx(1.0, abs=1e-6)


@pytest.mark.parametrize("bad,name", [(jnp.zeros(3), "d"), (jnp.array([1.0, jnp.nan, 0.0]), "d"), (jnp.ones(2), "d")])
def test_bad_directions(bad, name):
    with pytest.raises(ValueError, match=name):
        refract(bad, UP, 1.0, 1.333)


def test_bad_normal_and_index():
    with pytest.raises(ValueError, match="n "):
        reflect(_down_at(0.1), jnp.array([0.0, jnp.nan, 1.0]))
    with pytest.raises(ValueError, match="n2"):
        refract(_down_at(0.1), UP, 1.0, 0.5)
