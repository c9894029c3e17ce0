import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from wavephys import Water
from wavephys.physics import dispersion as d

DEEP_GRAVITY = Water(sigma=0.0)


class TestAngularFrequency:
    def test_deep_gravity_is_sqrt_gk(self):
        k = jnp.array([0.1, 1.0, 10.0])
        np.testing.assert_allclose(d.angular_frequency(k, DEEP_GRAVITY), np.sqrt(9.81 * np.asarray(k)), rtol=1e-6)

    def test_full_formula_finite_depth(self):
        w = Water(depth=0.3)
        k = np.array([1.0, 50.0, 400.0])
        expected = np.sqrt((9.81 * k + 0.0728 / 1000 * k**3) * np.tanh(k * 0.3))
        np.testing.assert_allclose(d.angular_frequency(jnp.asarray(k), w), expected, rtol=1e-6)

    def test_zero_and_shape_and_dtype(self):
        out = d.angular_frequency(jnp.zeros((2, 3), jnp.float32), Water())
        assert out.shape == (2, 3) and out.dtype == jnp.float32 and float(out.max()) == 0.0

    def test_float64(self, x64):
        k = jnp.asarray([2.0], jnp.float64)
        assert d.angular_frequency(k, DEEP_GRAVITY).dtype == jnp.float64
        assert abs(float(d.angular_frequency(k, DEEP_GRAVITY)[0]) - math.sqrt(19.62)) < 1e-14

    @pytest.mark.parametrize("bad", [-1.0, math.nan, math.inf, [1.0, -0.5]])
    def test_bad_k(self, bad):
        with pytest.raises(ValueError, match="k "):
            d.angular_frequency(bad, Water())


class TestSpeeds:
    def test_limits(self):
        h = 2.0
        shallow = Water(sigma=0.0, depth=h)
        assert float(d.phase_speed(1e-4, shallow)) == pytest.approx(math.sqrt(9.81 * h), rel=1e-6)
        assert float(d.group_speed(1e-4, shallow)) == pytest.approx(math.sqrt(9.81 * h), rel=1e-6)
        assert float(d.group_speed(3.0, DEEP_GRAVITY) / d.phase_speed(3.0, DEEP_GRAVITY)) == pytest.approx(0.5, rel=1e-6)
        cap = Water()
        assert float(d.group_speed(1e6, cap) / d.phase_speed(1e6, cap)) == pytest.approx(1.5, rel=1e-4)
        assert float(d.phase_speed(1e6, cap)) == pytest.approx(math.sqrt(0.0728e-3 * 1e6), rel=1e-4)

    def test_k_zero_limits(self):
        assert float(d.phase_speed(0.0, Water(depth=4.0))) == pytest.approx(math.sqrt(9.81 * 4))
        assert math.isinf(float(d.group_speed(0.0, Water())))

    @pytest.mark.parametrize("water", [Water(), Water(depth=0.05), Water(sigma=0.0, depth=3.0)])
    def test_group_speed_equals_autodiff(self, water, x64):
        k = jnp.logspace(-3, 4, 500, dtype=jnp.float64)
        auto = jax.vmap(jax.grad(lambda x: d.angular_frequency(x, water)))(k)
        np.testing.assert_allclose(auto, d.group_speed(k, water), rtol=1e-12)

    def test_gradient_finite_at_zero(self):
        assert math.isfinite(float(jax.grad(lambda x: d.angular_frequency(x, Water()))(0.0)))


class TestMinima:
    def test_min_phase_speed_published(self):
        c, k = d.min_phase_speed(Water())
        assert c == pytest.approx((4 * 9.81 * 0.0728 / 1000) ** 0.25, rel=1e-6)
        assert c == pytest.approx(0.2312, abs=5e-5)
        assert 2 * math.pi / k == pytest.approx(0.0171, abs=5e-5)
        assert k == pytest.approx(math.sqrt(9.81 * 1000 / 0.0728), rel=1e-3)

    def test_min_group_speed_published(self):
        c, k = d.min_group_speed(Water())
        assert c == pytest.approx(0.1776, abs=5e-5)
        assert 2 * math.pi / k == pytest.approx(0.0435, abs=5e-5)
        # it is a minimum: c_g is larger on both sides
        assert float(d.group_speed(k * 1.05, Water())) > c < float(d.group_speed(k / 1.05, Water()))

    def test_shallow_strong_tension_has_no_interior_minimum(self):
        w = Water(depth=1e-3)  # h² < 3σ/(ρg): c rises from sqrt(gh)
        c, k = d.min_phase_speed(w)
        assert (c, k) == (pytest.approx(math.sqrt(9.81e-3)), 0.0)

    def test_no_tension_no_minimum(self):
        with pytest.raises(ValueError, match="sigma"):
            d.min_phase_speed(DEEP_GRAVITY)


WATERS = [Water(), Water(sigma=0.0), Water(depth=0.01), Water(depth=1.0), Water(depth=100.0),
          Water(sigma=0.0, depth=5.0)]


class TestInverse:
    @staticmethod
    def _ks(water, dtype):
        if water.is_deep:
            return jnp.logspace(-2, 4, 400, dtype=dtype)
        kh = jnp.logspace(-3, 3, 400, dtype=dtype)
        return kh / float(water.depth)

    @pytest.mark.parametrize("water", WATERS)
    def test_round_trip_float64(self, water, x64):
        k = self._ks(water, jnp.float64)
        back = d.wavenumber(d.angular_frequency(k, water), water)
        assert float(jnp.max(jnp.abs(back / k - 1))) < 1e-10

    @pytest.mark.parametrize("water", WATERS)
    def test_round_trip_float32(self, water):
        k = self._ks(water, jnp.float32)
        back = d.wavenumber(d.angular_frequency(k, water), water)
        assert back.dtype == jnp.float32
        assert float(jnp.max(jnp.abs(back / k - 1))) < 1e-5

    def test_jit_vmap_over_depth(self):
        f = jax.jit(jax.vmap(lambda h: d.wavenumber(1.0, Water(sigma=0.0, depth=h))))
        h = jnp.array([0.1, 1.0, 10.0, 1000.0])
        k = f(h)
        np.testing.assert_allclose(k * jnp.tanh(k * h) * 9.81, 1.0, rtol=1e-5)

    def test_zero_and_extremes(self):
        assert float(d.wavenumber(0.0, Water())) == 0.0
        k = d.wavenumber(jnp.array([1e-4, 1e5]), Water(depth=0.5))
        assert bool(jnp.all(jnp.isfinite(k)))

    @pytest.mark.parametrize("bad", [-1.0, math.nan, math.inf])
    def test_bad_omega(self, bad):
        with pytest.raises(ValueError, match="omega"):
            d.wavenumber(bad, Water())


def test_one_program_serves_every_shape_in_a_power_of_two_bucket():
    """Concrete arrays of any shape whose sizes share a power-of-two bucket run one compiled program, with
    the values of the formula compiled for their own shape; a scalar and a traced k keep their own paths (a scalar keeps its weak type; under grad the formula is traced inline)."""
    import jax.monitoring

    compiles = []

    def listen(event, duration, **kw):
        if "backend_compile" in event and "traced" in kw.get("fun_name", ""):
            compiles.append(kw["fun_name"])

    jax.monitoring.register_event_duration_secs_listener(listen)
    water = Water(depth=1.7)
    rng = np.random.default_rng(3)
    shapes = [(71,), (9, 11), (3, 5, 7), (120,), (2, 60)]  # sizes 71 … 120: the 128 bucket
    ks = [jnp.asarray(rng.uniform(0.0, 80.0, s), jnp.float32) for s in shapes]
    try:
        got = [d.group_speed(k, water) for k in ks]
    finally:
        jax.monitoring.unregister_event_duration_listener(listen)
    assert len(compiles) <= 1, compiles
    for k, g in zip(ks, got):
        assert g.shape == k.shape and g.dtype == k.dtype
        np.testing.assert_allclose(np.asarray(g), np.asarray(jax.jit(lambda k: d.group_speed(k, water))(k)),
                                   rtol=2e-7, atol=0)
    assert d.angular_frequency(2.0, water).shape == ()
    assert float(jax.grad(lambda k: d.angular_frequency(k, water))(2.0)) > 0
